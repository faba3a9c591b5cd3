#include "lib/simplify/wedge_replay.h"

#include <algorithm>
#include <string>
#include <utility>

#include "lib/simplify/vec_math.h"

namespace lodbake {

Result<WedgeRefiner> WedgeRefiner::create(const ProgressiveMesh& pm, const PmWedges& wedges) {
  const size_t count = wedges.wedge_count();
  if (wedges.wedge_vertex.size() != count || wedges.wedge_home.size() != count)
    return invalid_input("the wedge table's lists differ in length");
  for (uint32_t home : wedges.wedge_home)
    if (home >= pm.full_vertex_count())
      return invalid_input("a wedge's vertex " + std::to_string(home) + " is out of range");
  if (wedges.base.size() != pm.base.triangles.size())
    return invalid_input("the wedges name " + std::to_string(wedges.base.size()) +
                         " base triangles, the base mesh has " +
                         std::to_string(pm.base.triangles.size()));
  if (wedges.added.size() != pm.splits.size() || wedges.moved_offset.size() != pm.splits.size() + 1)
    return invalid_input("the wedges describe another number of splits than the " +
                         std::to_string(pm.splits.size()) + " of the progressive mesh");
  if (wedges.moved_offset.front() != 0 || wedges.moved_offset.back() != wedges.moved.size())
    return invalid_input("the moved wedges' offsets do not cover their list");
  for (size_t i = 1; i < wedges.moved_offset.size(); ++i)
    if (wedges.moved_offset[i] < wedges.moved_offset[i - 1])
      return invalid_input("the moved wedges' offsets decrease at split " + std::to_string(i - 1));
  for (const std::array<uint32_t, 3>& t : wedges.base)
    for (uint32_t w : t)
      if (w >= count) return invalid_input("a base corner's wedge is out of range");
  for (size_t i = 0; i < wedges.added.size(); ++i) {
    const VertexSplit& s = pm.splits[i];
    for (int k = 0; k < 6; ++k) {
      const bool wing = (k < 3 ? s.vl : s.vr) != kNoVertex;
      const uint32_t w = wedges.added[i][k];
      if (wing ? w >= count : w != kNoVertex)
        return invalid_input("split " + std::to_string(i) + "'s added faces' wedges do not match " +
                             "its wings");
    }
  }
  for (uint32_t w : wedges.moved)
    if (w >= count) return invalid_input("a moved corner's wedge is out of range");
  LODBAKE_ASSIGN_OR_RETURN(PmRefiner refiner, PmRefiner::create(pm));
  WedgeRefiner r(std::move(refiner), wedges);
  r.corners_ = wedges.base;
  return r;
}

Status WedgeRefiner::split_next() {
  const size_t i = refiner_.applied_splits();
  LODBAKE_RETURN_IF_ERROR(refiner_.split_next());
  const auto [begin, end] = refiner_.last_moved_faces();
  const uint32_t first = wedges_->moved_offset[i];
  if (static_cast<size_t>(end - begin) != wedges_->moved_offset[i + 1] - first)
    return invalid_input("split " + std::to_string(i) + " moves " + std::to_string(end - begin) +
                         " faces, its wedges name " +
                         std::to_string(wedges_->moved_offset[i + 1] - first));
  const TriangleMesh& m = refiner_.mesh();
  const uint32_t vt = static_cast<uint32_t>(m.positions.size() - 1);
  for (const uint32_t* f = begin; f != end; ++f) {
    const int k = corner_of(m.triangles[*f], vt);
    undo_.push_back(corners_[*f][k]);
    corners_[*f][k] = wedges_->moved[first + (f - begin)];
  }
  const std::array<uint32_t, 6>& added = wedges_->added[i];
  if (added[0] != kNoVertex) corners_.push_back({added[0], added[1], added[2]});
  if (added[3] != kNoVertex) corners_.push_back({added[3], added[4], added[5]});
  return Status::ok();
}

Status WedgeRefiner::collapse_last() {
  const size_t applied = refiner_.applied_splits();
  if (applied == 0) return invalid_input("no vertex split to undo");
  const size_t i = applied - 1;
  const auto [begin, end] = refiner_.last_moved_faces();
  const TriangleMesh& m = refiner_.mesh();
  const uint32_t vt = static_cast<uint32_t>(m.positions.size() - 1);
  const size_t moved = static_cast<size_t>(end - begin);
  for (size_t j = moved; j-- > 0;) {
    const uint32_t f = begin[j];
    corners_[f][corner_of(m.triangles[f], vt)] = undo_.back();
    undo_.pop_back();
  }
  const std::array<uint32_t, 6>& added = wedges_->added[i];
  corners_.resize(corners_.size() - (added[0] != kNoVertex ? 1 : 0) -
                  (added[3] != kNoVertex ? 1 : 0));
  return refiner_.collapse_last();
}

Status WedgeRefiner::refine_to(size_t vertex_count) {
  const size_t n0 = refiner_.vertex_count() - refiner_.applied_splits();
  if (vertex_count < n0 || vertex_count > n0 + wedges_->added.size())
    return invalid_input("level of detail of " + std::to_string(vertex_count) +
                         " vertices is outside [" + std::to_string(n0) + ", " +
                         std::to_string(n0 + wedges_->added.size()) + "]");
  while (refiner_.vertex_count() < vertex_count)
    LODBAKE_RETURN_IF_ERROR(split_next());
  while (refiner_.vertex_count() > vertex_count)
    LODBAKE_RETURN_IF_ERROR(collapse_last());
  return Status::ok();
}

Result<CornerWedges> CornerWedges::create(const ProgressiveMesh& pm, const PmWedges& wedges) {
  LODBAKE_ASSIGN_OR_RETURN(WedgeRefiner refiner, WedgeRefiner::create(pm, wedges));
  std::vector<std::pair<uint64_t, uint32_t>> entries;
  auto add = [&](size_t face, uint32_t vertex, uint32_t wedge) {
    entries.emplace_back(uint64_t{static_cast<uint32_t>(face)} << 32 | vertex, wedge);
  };
  for (size_t f = 0; f < refiner.mesh().triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      add(f, refiner.mesh().triangles[f][k], refiner.corners()[f][k]);
  while (!refiner.refiner().fully_refined()) {
    const size_t first_new = refiner.mesh().triangles.size();
    LODBAKE_RETURN_IF_ERROR(refiner.split_next());
    const TriangleMesh& m = refiner.mesh();
    const uint32_t vt = static_cast<uint32_t>(m.positions.size() - 1);
    const auto [begin, end] = refiner.refiner().last_moved_faces();
    for (const uint32_t* f = begin; f != end; ++f)
      add(*f, vt, refiner.corners()[*f][corner_of(m.triangles[*f], vt)]);
    for (size_t f = first_new; f < m.triangles.size(); ++f)
      for (int k = 0; k < 3; ++k)
        add(f, m.triangles[f][k], refiner.corners()[f][k]);
  }
  std::sort(entries.begin(), entries.end());
  CornerWedges out;
  out.keys_.reserve(entries.size());
  out.values_.reserve(entries.size());
  for (const auto& [key, wedge] : entries) {
    // A face's corner is at a vertex once: the same pair cannot come twice
    // with two wedges (the replay would have refused the record).
    if (!out.keys_.empty() && out.keys_.back() == key) continue;
    out.keys_.push_back(key);
    out.values_.push_back(wedge);
  }
  return out;
}

uint32_t CornerWedges::wedge(uint32_t face, uint32_t vertex) const {
  const uint64_t key = uint64_t{face} << 32 | vertex;
  auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  if (it == keys_.end() || *it != key) return kNoVertex;
  return values_[static_cast<size_t>(it - keys_.begin())];
}

}  // namespace lodbake
