// Sequential vertex-split replay for the DAG and vertex-tree builders. The
// record checks and the fan walk are PmRefiner's (collect_moved_faces() in
// lib/simplify/split_fan.h): counter-clockwise around vs from the face
// (vs, vr, .) until (vs, ., vl) or the boundary, then clockwise from
// (vs, ., vl) to the boundary when vl was not reached. The simulator keeps
// its own face slots because the builders need the slots that move, which
// the refiner keeps private; the DAG tests compare both replays on every mesh.
#include "lib/dag/split_simulator.h"

#include <algorithm>
#include <string>

#include "lib/simplify/split_fan.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {

Result<SplitSimulator> SplitSimulator::create(const ProgressiveMesh& pm) {
  const size_t n0 = pm.base.positions.size();
  if (pm.full_vertex_count() >= kNoVertex) {
    return invalid_input("progressive mesh has too many vertices");
  }
  SplitSimulator s(pm);
  s.faces_of_.resize(n0);
  s.faces_.reserve(pm.base.triangles.size() + 2 * pm.splits.size());
  for (size_t t = 0; t < pm.base.triangles.size(); ++t) {
    const Triangle& tri = pm.base.triangles[t];
    if (tri[0] >= n0 || tri[1] >= n0 || tri[2] >= n0 || tri[0] == tri[1] || tri[1] == tri[2] ||
        tri[0] == tri[2]) {
      return invalid_input("base triangle " + std::to_string(t) +
                           " has an out-of-range or repeated vertex index");
    }
    s.faces_.push_back(tri);
    for (uint32_t v : tri)
      s.faces_of_[v].push_back(static_cast<uint32_t>(t));
  }
  return s;
}

Status SplitSimulator::split_next(Effect* effect) {
  effect->moved.clear();
  effect->added.clear();
  if (applied_ >= pm_->splits.size()) return invalid_input("no vertex split left to apply");
  const VertexSplit& s = pm_->splits[applied_];
  const uint32_t vt = static_cast<uint32_t>(faces_of_.size());
  const uint32_t vs = s.vs;
  const uint32_t vl = s.vl;
  const uint32_t vr = s.vr;
  std::vector<uint32_t>& moved = effect->moved;
  LODBAKE_RETURN_IF_ERROR(collect_moved_faces(faces_, faces_of_, vt, s, applied_, &moved));

  faces_of_.emplace_back();
  std::vector<uint32_t>& vs_faces = faces_of_[vs];
  for (uint32_t f : moved) {
    Triangle& t = faces_[f];
    t[corner_of(t, vs)] = vt;
    vs_faces.erase(std::find(vs_faces.begin(), vs_faces.end(), f));
    faces_of_[vt].push_back(f);
  }
  auto add = [&](const Triangle& t) {
    const uint32_t f = static_cast<uint32_t>(faces_.size());
    faces_.push_back(t);
    for (uint32_t v : t)
      faces_of_[v].push_back(f);
    effect->added.push_back(f);
  };
  if (vl != kNoVertex) add({vs, vt, vl});
  if (vr != kNoVertex) add({vt, vs, vr});
  ++applied_;
  return Status::ok();
}

void SplitSimulator::boundary_half_edges(uint32_t v, std::vector<HalfEdgeKey>* out) const {
  // Every face holding v -> a or a -> v is a face of v: v -> a exists for each
  // face (v, a, .) and b -> v for each face (v, ., b), so v's faces alone
  // tell which of the two directions of each edge at v is missing.
  const std::vector<uint32_t>& faces = faces_of_[v];
  auto has_next = [&](uint32_t a) {  // v -> a exists
    for (uint32_t f : faces) {
      const Triangle& t = faces_[f];
      if (t[(corner_of(t, v) + 1) % 3] == a) return true;
    }
    return false;
  };
  auto has_prev = [&](uint32_t b) {  // b -> v exists
    for (uint32_t f : faces) {
      const Triangle& t = faces_[f];
      if (t[(corner_of(t, v) + 2) % 3] == b) return true;
    }
    return false;
  };
  for (uint32_t f : faces) {
    const Triangle& t = faces_[f];
    const int c = corner_of(t, v);
    const uint32_t a = t[(c + 1) % 3];
    const uint32_t b = t[(c + 2) % 3];
    if (!has_prev(a)) out->push_back(half_edge_key(a, v));
    if (!has_next(b)) out->push_back(half_edge_key(v, b));
  }
}

std::vector<FanRun> SplitSimulator::fan(uint32_t v) const {
  // Counter-clockwise successor of each neighbour a: the b of face (v, a, b).
  std::vector<std::pair<uint32_t, uint32_t>> next;
  for (uint32_t f : faces_of_[v]) {
    const Triangle& t = faces_[f];
    const int c = corner_of(t, v);
    next.emplace_back(t[(c + 1) % 3], t[(c + 2) % 3]);
  }
  std::sort(next.begin(), next.end());
  std::vector<uint8_t> used(next.size(), 0);
  auto find_from = [&](uint32_t a) -> size_t {
    auto it = std::lower_bound(next.begin(), next.end(), std::make_pair(a, uint32_t{0}));
    while (it != next.end() && it->first == a) {
      if (!used[static_cast<size_t>(it - next.begin())])
        return static_cast<size_t>(it - next.begin());
      ++it;
    }
    return next.size();
  };
  std::vector<uint32_t> targets;
  for (const auto& e : next)
    targets.push_back(e.second);
  std::sort(targets.begin(), targets.end());
  std::vector<FanRun> runs;
  // Open runs start at a neighbour that is no face's successor.
  auto walk = [&](size_t start, bool closed) {
    std::vector<uint32_t> ccw{next[start].first};
    size_t e = start;
    while (e < next.size()) {
      used[e] = 1;
      ccw.push_back(next[e].second);
      e = find_from(next[e].second);
    }
    if (closed) ccw.pop_back();  // the walk came back to its start
    FanRun run;
    run.closed = closed;
    run.vertices.assign(ccw.rbegin(), ccw.rend());
    if (closed) {
      const auto smallest = std::min_element(run.vertices.begin(), run.vertices.end());
      std::rotate(run.vertices.begin(), smallest, run.vertices.end());
    }
    runs.push_back(std::move(run));
  };
  for (size_t e = 0; e < next.size(); ++e) {
    if (!used[e] && !std::binary_search(targets.begin(), targets.end(), next[e].first)) {
      walk(e, false);
    }
  }
  for (size_t e = 0; e < next.size(); ++e) {
    if (!used[e]) walk(e, true);
  }
  std::sort(runs.begin(), runs.end(), [](const FanRun& a, const FanRun& b) {
    return a.vertices.front() < b.vertices.front();
  });
  return runs;
}

}  // namespace lodbake
