// Mode fan of the replay runtime: the dual-path adapt of Livny, Sokolovsky &
// El-Sana 2007 (section 3.4: traverse only the active nodes; coarse changes
// by fan-merge / fan-split, fine ones by moving the merge pointer, chosen by
// the difference between the current and the target level of detail;
// section 4: fan-merge decided on the parent's error, fan-split on the last
// child's). The operations and their legality are lib/fanmerge's
// FanRuntime. Choices where the paper is vague:
// - dependencies: FanRuntime's construction dependencies (a step needs
//   the neighbourhood it had in the construction, the paper's implicit
//   dependencies). Without them a fan out of view can take a triangle of a
//   neighbour still split in view, and that neighbour can never merge again
//   (the test LookingAwayReachesTheCoarsestMesh shows both);
// - start: the coarsest mesh (FanRuntime::merge_all), as vhier starts at its
//   base mesh, so the replay refines what comes into view;
// - view test: a node is outside the view when the sphere around its vertex
//   holding every vertex of its subtree (radius computed once, bottom up)
//   lies entirely outside one frustum plane; its target is then every child
//   merged. There is no back-face test (FANH has no normal cones);
// - error: FANH's Delta(v) is a squared length (a sum of mean squared
//   distances), saturated up the forest, E(n) = max(Delta(n), E(children)),
//   so that a node never looks finer than what it covers and a parent that
//   wants its fan merged does not wait forever on a child that wants to
//   stay split at the same distance;
// - target: per-child errors are not stored, so merging the first k of K
//   children is estimated to cost E * k / K, an upper bound of the first k
//   collapse errors' sum (children are in increasing error order). The
//   target is the largest k with E * k / K < (kappa z)^2, z the distance
//   from the eye to the node's vertex (the paper's dist(v, C), at least the
//   near distance) and kappa the tolerance as vhier uses it
//   (docs/replay.md). So the fan is merged whole exactly when its own error
//   projects under the tolerance, and the pointer retreats when the error
//   with its last merged child does not. Eq. 3's view-direction and light
//   factors are not used (a replay has no light; FANH has no normals);
// - dual path: the coarse path is taken when the target is an end of the
//   fine path (all or none merged) at least max(1, ceil(f K)) steps from
//   the pointer, f = FanReplayOptions::coarse_fraction (default 1/2);
//   otherwise the pointer is stepped until it reaches the target. A refused
//   fan-merge / fan-split falls back to single steps, as far as they go;
// - traversal: the active list is scanned in place from its first entry to
//   its current end, so nodes activated during the scan (appended) are
//   visited in the same frame and a split cascades down the forest at once;
//   a node moved into a scanned slot by a removal waits for the next frame.
//   For each active node, the node itself (when it is internal, its pointer
//   is nonzero) and its parent are evaluated, each node at most once per
//   frame. A parent evaluated before its children are fully merged merges
//   in a later frame (temporal coherence, as the paper relies on);
// - no adapt-time budget: every frame runs to the end of the scan, so the
//   figures compare with vhier's.
#include "lib/replay/fan_replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>

#include "lib/check/mesh_check.h"
#include "lib/replay/replay_check.h"

namespace lodbake {
namespace {

double distance(const Vec3f& a, const Vec3f& b) {
  double d2 = 0;
  for (int i = 0; i < 3; ++i)
    d2 += (double{a[i]} - b[i]) * (double{a[i]} - b[i]);
  return std::sqrt(d2);
}

}  // namespace

Result<FanReplay> FanReplay::create(const TriangleMesh& input, const FanHierarchy& hierarchy,
                                    Start start, bool dependencies) {
  FanRuntimeOptions runtime_options;
  runtime_options.construction_dependencies = dependencies;
  LODBAKE_ASSIGN_OR_RETURN(FanRuntime runtime,
                           FanRuntime::create(input, hierarchy, runtime_options));
  try {
    FanReplay r(std::move(runtime));
    // The merges are the file's (FANH): when they cannot all be made on
    // the mesh, the data is damaged.
    if (start == Start::kCoarsest && !r.runtime_.merge_all())
      return invalid_input("the fan hierarchy's coarsest mesh cannot be reached");
    r.positions_ = input.positions;
    const FanRuntime& rt = r.runtime_;
    const size_t n = rt.node_count();
    r.saturated_.assign(n, 0.f);
    r.radius_.assign(n, 0.f);
    // Children have smaller ids than their parent: one pass in id order.
    for (uint32_t node = rt.leaf_count(); node < n; ++node) {
      const Vec3f& centre = r.positions_[rt.vertex(node)];
      float error = rt.error(node);
      double radius = 0;
      for (uint32_t i = 0; i <= rt.collapsible_children(node); ++i) {
        const uint32_t c = rt.child(node, i);
        error = std::max(error, r.saturated_[c]);
        radius = std::max(radius, distance(centre, r.positions_[rt.vertex(c)]) + r.radius_[c]);
      }
      r.saturated_[node] = error;
      r.radius_[node] = static_cast<float>(radius);
    }
    r.visited_.assign(n, 0);
    return r;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the fan replay");
  }
}

uint32_t FanReplay::target(uint32_t node) const {
  const uint32_t k = runtime_.collapsible_children(node);
  if (k == 0) return 0;
  const Vec3f& p = positions_[runtime_.vertex(node)];
  const float r = radius_[node];
  for (const std::array<float, 4>& q : view_.frustum) {
    if (q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] < -r) return k;
  }
  const double z = std::max(distance(p, view_.eye), double{near_});
  const double budget = double{view_.kappa} * z * double{view_.kappa} * z;
  const double e = saturated_[node];
  if (e < budget) return k;
  // The largest t with e * t / k < budget, i.e. t < x.
  const double x = k * budget / e;
  if (!(x > 0)) return 0;
  return std::min(k, static_cast<uint32_t>(std::ceil(x)) - 1);
}

void FanReplay::evaluate(uint32_t node, FanFrameStats* stats) {
  if (visited_[node] == frame_) return;
  visited_[node] = frame_;
  if (runtime_.held(node)) return;
  const uint32_t k = runtime_.collapsible_children(node);
  const uint32_t pointer = runtime_.merge_pointer(node);
  const uint32_t t = target(node);
  if (t == pointer) return;
  const uint32_t steps = t > pointer ? t - pointer : pointer - t;
  const double coarse_min = std::max(1.0, std::ceil(double{coarse_fraction_} * k));
  if ((t == k || t == 0) && steps >= coarse_min) {
    if (t > pointer ? runtime_.fan_merge(node) : runtime_.fan_split(node)) {
      ++(t > pointer ? stats->fan_merges : stats->fan_splits);
      return;
    }
  }
  while (runtime_.merge_pointer(node) < t && runtime_.advance(node))
    ++stats->collapses;
  while (runtime_.merge_pointer(node) > t && runtime_.retreat(node))
    ++stats->splits;
  if (runtime_.merge_pointer(node) != t) ++stats->refused;
}

Result<FanFrameStats> FanReplay::adapt(const BoundingSphere& sphere, const CameraFrame& frame,
                                       const FanReplayOptions& options) {
  try {
    const auto start = std::chrono::steady_clock::now();
    near_ = options.viewport.near_fraction * sphere.radius;
    view_ = view_parameters(frame, options.viewport, near_, options.tolerance_pixels);
    coarse_fraction_ = options.coarse_fraction;
    if (++frame_ == 0) {
      std::fill(visited_.begin(), visited_.end(), 0);
      frame_ = 1;
    }
    FanFrameStats stats;
    const ActiveNodeList& active = runtime_.active();
    for (size_t i = 0; i < active.size(); ++i) {
      const uint32_t a =
          active.block(i / ActiveNodeList::kBlockSize)[i % ActiveNodeList::kBlockSize];
      if (!runtime_.is_leaf(a)) evaluate(a, &stats);
      const uint32_t parent = runtime_.parent(a);
      if (parent != kNoNode) evaluate(parent, &stats);
    }
    stats.active = active.size();
    stats.triangles = runtime_.triangle_count();
    stats.adapt_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory adapting the fan hierarchy");
  }
}

std::vector<std::string> FanReplay::check() const {
  const TriangleMesh mesh = runtime_.mesh();
  std::vector<std::string> problems = triangulation_problems(mesh);
  if (mesh.triangle_count() != runtime_.triangle_count()) {
    problems.push_back("triangle count " + std::to_string(runtime_.triangle_count()) +
                       " but the mesh has " + std::to_string(mesh.triangle_count()) + " triangles");
  }
  std::vector<uint8_t> used(mesh.vertex_count(), 0);
  for (const Triangle& t : mesh.triangles)
    for (uint32_t v : t)
      if (v < used.size()) used[v] = 1;
  const size_t used_count = static_cast<size_t>(std::count(used.begin(), used.end(), 1));
  const std::vector<uint32_t> nodes = runtime_.active().nodes();
  if (nodes.size() != used_count) {
    problems.push_back("active list holds " + std::to_string(nodes.size()) +
                       " nodes but the mesh uses " + std::to_string(used_count) + " vertices");
  }
  size_t stray = 0;
  for (uint32_t node : nodes) {
    uint8_t& u = used[runtime_.vertex(node)];
    if (u != 1) ++stray;  // unused vertex, or a second node for one
    u = 2;
  }
  if (stray != 0) {
    problems.push_back(std::to_string(stray) +
                       " active nodes standing for no vertex of the mesh or for one twice");
  }
  return problems;
}

std::vector<std::string> check_fan_wedges(const FanRuntime& runtime, const FanWedges& fronts,
                                          const PmWedges& wedges) {
  Result<std::vector<std::array<uint32_t, 3>>> corners = fronts.corners(runtime);
  if (!corners.is_ok()) return {corners.status().message()};
  return corner_wedge_problems(corners.value(), wedges);
}

}  // namespace lodbake
