#include "lib/simplify/wedge_pm.h"

#include <string>

#include "lib/simplify/pm_replay.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {
namespace {

Vec3f to_f(const Vec3d& p) {
  return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
}

}  // namespace

Result<WedgePm> record_wedge_pm(const WedgeMesh& mesh, const WedgeCollapseResult& result) {
  if (result.levels.size() != 1)
    return runtime_error("a progressive mesh is recorded from a run with one target");
  const WedgeLevel& base = result.levels.front();
  const size_t n = mesh.points.size();
  WedgePm out;
  ProgressiveMesh& pm = out.pm;
  std::vector<uint8_t> removed(n, 0);
  for (const WedgeCollapseRecord& r : result.log)
    removed[r.vt] = 1;
  std::vector<uint32_t> pm_id(n, kNoVertex);
  for (uint32_t v = 0; v < n; ++v) {
    if (removed[v]) continue;
    pm_id[v] = static_cast<uint32_t>(pm.input_vertex.size());
    pm.input_vertex.push_back(v);
    pm.base.positions.push_back(to_f(mesh.points[v]));
  }
  for (size_t i = result.log.size(); i-- > 0;) {
    pm_id[result.log[i].vt] = static_cast<uint32_t>(pm.input_vertex.size());
    pm.input_vertex.push_back(result.log[i].vt);
  }
  auto map = [&](uint32_t v) { return v == kNoVertex ? kNoVertex : pm_id[v]; };
  for (const Triangle& t : base.triangles)
    pm.base.triangles.push_back({pm_id[t[0]], pm_id[t[1]], pm_id[t[2]]});
  out.wedges.base = base.corner_wedge;
  for (uint32_t point : mesh.wedge_point)
    out.wedges.wedge_home.push_back(pm_id[point]);
  out.wedges.moved_offset.push_back(0);
  for (size_t i = result.log.size(); i-- > 0;) {
    const WedgeCollapseRecord& r = result.log[i];
    VertexSplit s;
    s.vs = pm_id[r.vs];
    s.vl = map(r.vl);
    s.vr = map(r.vr);
    s.vt_position = to_f(mesh.points[r.vt]);
    s.vs_position = to_f(mesh.points[r.vs]);
    s.error = r.error;
    pm.splits.push_back(s);
    std::array<uint32_t, 6> added;
    added.fill(kNoVertex);
    if (r.vl != kNoVertex) std::copy(r.left.begin(), r.left.end(), added.begin());
    if (r.vr != kNoVertex) std::copy(r.right.begin(), r.right.end(), added.begin() + 3);
    out.wedges.added.push_back(added);
  }

  // The replay moves a split's faces in the order its walk meets them;
  // the log has them in the engine's order. Face slots: the base's
  // triangles, then each split's added faces.
  std::vector<uint32_t> slot_face = base.faces;
  LODBAKE_ASSIGN_OR_RETURN(PmRefiner refiner, PmRefiner::create(pm));
  for (size_t i = 0; i < pm.splits.size(); ++i) {
    const WedgeCollapseRecord& r = result.log[result.log.size() - 1 - i];
    Status split = refiner.split_next();
    if (!split.is_ok())
      return runtime_error("recorded split " + std::to_string(i) +
                           " does not replay: " + split.message());
    const auto [begin, end] = refiner.last_moved_faces();
    if (static_cast<uint32_t>(end - begin) != r.moved_end - r.moved_begin)
      return runtime_error("recorded split " + std::to_string(i) + " moves " +
                           std::to_string(end - begin) + " faces, its collapse moved " +
                           std::to_string(r.moved_end - r.moved_begin));
    for (const uint32_t* slot = begin; slot != end; ++slot) {
      uint32_t wedge = kNoVertex;
      for (uint32_t j = r.moved_begin; j < r.moved_end; ++j)
        if (result.moved_faces[j] == slot_face[*slot]) wedge = result.moved_wedges[j];
      if (wedge == kNoVertex)
        return runtime_error("recorded split " + std::to_string(i) +
                             " moves a face its collapse did not");
      out.wedges.moved.push_back(wedge);
    }
    out.wedges.moved_offset.push_back(static_cast<uint32_t>(out.wedges.moved.size()));
    if (r.vl != kNoVertex) slot_face.push_back(r.left_face);
    if (r.vr != kNoVertex) slot_face.push_back(r.right_face);
  }
  return out;
}

}  // namespace lodbake
