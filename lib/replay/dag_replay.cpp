// Mode dag of the replay runtime: MANAGE-TRAVERSAL (Zheng & Chan 2006,
// sections 4-5, Figures 2-5) over the fronts of the DAG of vertex splits.
// Choices where the paper leaves room (docs/replay.md, "Mode dag"):
// - ERROR-EVALUATE: the DAG carries no bounding spheres or error bounds,
//   and a split's own collapse error (VSPL) is neither monotone down the DAG
//   nor tied to where its descendants lie, so a coarse split whose new vertex
//   is out of view or far would block the refinement of a visible region
//   below it. create() therefore derives, once, for every node a bounding
//   sphere around its new vertex holding its triangles and its descendants'
//   spheres, and an error bound, the largest collapse error of the node and
//   its descendants (both in reverse id order: children have larger ids).
//   A node's error is its bound projected at the distance from the eye to
//   its sphere (at least the near distance), in pixels; 0 when the sphere is
//   outside the frustum, or when its cone of normals (derived the same way
//   from the normals of the triangles the node and its descendants create)
//   faces away from every point of the sphere: the paper's experiments use
//   out-of-view and back-facing simplification. Spheres, cones and bounds
//   only shrink down the DAG, so a node that needs a split never sits under
//   one that does not. NEED-APPLY: split while the error is at least the
//   tolerance, collapse while it is below, so a node just split is never
//   collapsed on the same view.
// - The mode: kAuto is the client's rule of section 4, FREE while
//   triangles + N * (most triangles one split adds) stays within the budget,
//   BUDGET otherwise. Splits are not all manifold (a boundary split adds one
//   triangle), so BUDGET-MODE restricts TRAVERSE-SPLIT by triangles, as the
//   paper's closing paragraph of section 4 proposes: a split is applied only
//   while the mesh stays within the budget, i.e. it may add the triangles
//   TRAVERSE-COLLAPSE deleted plus any room left under the budget (exactly
//   the deleted ones when the mesh was at the budget), and at most N splits.
// - A split that is needed but does not fit the budget ends TRAVERSE-SPLIT
//   in every traversal ("the traversal stops when further refinement
//   operations would exceed the triangle budget"); the FIFO traversals keep
//   that node first in their queue for the next frame.
// - The FIFO queues hold each front node once; nodes that left the front
//   are dropped when popped and count as no visit. A node visited again in
//   the frame that found it needing nothing reuses that answer (the view
//   is the same) and counts as a visit. Linear traversal stops
//   when a whole front was visited without a change (Figure 4, line 11);
//   constant-time traversal visits exactly N live nodes per traversal, as
//   Figure 5 has it, even when that means visiting a small front twice.
#include "lib/replay/dag_replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <new>
#include <queue>
#include <utility>

#include "lib/check/mesh_check.h"
#include "lib/replay/replay_check.h"

namespace lodbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
// evaluate()'s cone_from for an exact error: every error is at least this.
constexpr float kAlwaysCone = -std::numeric_limits<float>::infinity();

}  // namespace

const char* dag_traversal_name(DagTraversal traversal) {
  switch (traversal) {
    case DagTraversal::kPriority:
      return "priority";
    case DagTraversal::kLinear:
      return "linear";
    case DagTraversal::kConstantTime:
      return "constant";
  }
  return "?";
}

Result<DagReplay> DagReplay::create(const ProgressiveMesh& pm, const VsplitDag& dag) {
  if (dag.node_count() != pm.splits.size() || dag.base_vertex_count != pm.base.vertex_count()) {
    return invalid_input("DAG has " + std::to_string(dag.node_count()) + " nodes over " +
                         std::to_string(dag.base_vertex_count) +
                         " base vertices, the progressive mesh " +
                         std::to_string(pm.splits.size()) + " splits over " +
                         std::to_string(pm.base.vertex_count()));
  }
  try {
    LODBAKE_ASSIGN_OR_RETURN(DagFronts fronts, DagFronts::create(dag));
    DagReplay replay(pm, dag, std::move(fronts));
    LODBAKE_ASSIGN_OR_RETURN(replay.lineage_, build_split_lineage(pm));
    const SplitLineage& l = replay.lineage_;
    std::vector<uint32_t> changed(l.split_count(), 0);
    for (uint32_t s : l.changed_by) {
      if (s != kNoVertex && s < changed.size()) ++changed[s];
    }
    replay.added_.resize(l.split_count());
    for (size_t i = 0; i < l.split_count(); ++i) {
      const uint32_t created = l.created_offsets[i + 1] - l.created_offsets[i];
      if (created < changed[i]) {
        // The splits are the file's (VSPL): damaged data.
        return invalid_input("split " + std::to_string(i) + " changes " +
                             std::to_string(changed[i]) + " triangles but creates only " +
                             std::to_string(created));
      }
      replay.added_[i] = created - changed[i];
      replay.max_added_ = std::max(replay.max_added_, replay.added_[i]);
    }
    replay.derive_bounds();
    replay.triangles_ = pm.base.triangle_count();
    const size_t nodes = dag.node_count();
    replay.split_queue_.queued.assign(nodes, 0);
    replay.collapse_queue_.queued.assign(nodes, 0);
    std::vector<uint32_t> roots = replay.fronts_.split_front();
    std::sort(roots.begin(), roots.end());
    for (uint32_t n : roots)
      replay.split_queue_.push(n);
    return replay;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the DAG replay");
  }
}

void DagReplay::derive_bounds() {
  using V3 = std::array<double, 3>;
  const size_t nodes = pm_->splits.size();
  const size_t base_vertices = pm_->base.vertex_count();
  auto sub = [](const V3& a, const V3& b) { return V3{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto dot = [](const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto len = [&](const V3& a) { return std::sqrt(dot(a, a)); };
  auto angle = [&](const V3& a, const V3& b) {
    const double l = len(a) * len(b);
    return l > 0 ? std::acos(std::clamp(dot(a, b) / l, -1.0, 1.0)) : kPi;
  };
  auto to_d = [](const Vec3f& p) { return V3{p[0], p[1], p[2]}; };
  // Each split's own triangles as they are when it creates them (with
  // optimal placement vs moves in later splits, which recreate its faces):
  // the radius around vt holding them, and their cone of normals (axis the
  // area-weighted normal sum, half-angle the widest angle to one of them).
  std::vector<double> own_radius(nodes, 0), own_half_angle(nodes, 0);
  std::vector<V3> normal_sum(nodes, V3{0, 0, 0});
  {
    std::vector<V3> at(base_vertices + nodes);
    for (size_t v = 0; v < base_vertices; ++v)
      at[v] = to_d(pm_->base.positions[v]);
    std::vector<V3> normals;
    for (size_t n = 0; n < nodes; ++n) {
      const VertexSplit& s = pm_->splits[n];
      at[s.vs] = to_d(s.vs_position);
      const V3& centre = at[base_vertices + n] = to_d(s.vt_position);
      normals.clear();
      for (uint32_t t = lineage_.created_offsets[n]; t < lineage_.created_offsets[n + 1]; ++t) {
        const Triangle& tri = lineage_.triangles[t];
        for (uint32_t v : tri)
          own_radius[n] = std::max(own_radius[n], len(sub(centre, at[v])));
        const V3 e1 = sub(at[tri[1]], at[tri[0]]), e2 = sub(at[tri[2]], at[tri[0]]);
        normals.push_back({e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]});
        for (int i = 0; i < 3; ++i)
          normal_sum[n][i] += normals.back()[i];
      }
      double a = 0;
      for (const V3& fn : normals) {
        if (len(fn) > 0) a = std::max(a, angle(normal_sum[n], fn));
      }
      own_half_angle[n] = len(normal_sum[n]) > 0 ? a : kPi;
    }
  }
  // The closure over the descendants, in reverse id order (children have
  // larger ids), as lib/hierarchy's refinement data bounds a subtree.
  bounds_.assign(nodes, NodeBound());
  cones_.assign(nodes, NodeCone());
  std::vector<double> half_angle(nodes, kPi);
  for (size_t k = nodes; k-- > 0;) {
    const uint32_t n = static_cast<uint32_t>(k);
    const V3 centre = to_d(pm_->splits[n].vt_position);
    const V3 own_axis = normal_sum[n];
    double r = own_radius[n];
    float e = std::max(pm_->splits[n].error, 0.f);
    V3& sum = normal_sum[n];
    const uint32_t* children_begin = fronts_.children_begin(n);
    const uint32_t* children_end = fronts_.children_end(n);
    for (const uint32_t* c = children_begin; c != children_end; ++c) {
      r = std::max(r, len(sub(centre, to_d(pm_->splits[*c].vt_position))) + bounds_[*c].radius);
      e = std::max(e, bounds_[*c].error);
      for (int i = 0; i < 3; ++i)
        sum[i] += normal_sum[*c][i];
    }
    double a = len(own_axis) > 0 ? angle(sum, own_axis) + own_half_angle[n] : 0;
    for (const uint32_t* c = children_begin; c != children_end; ++c)
      a = std::max(a, angle(sum, normal_sum[*c]) + half_angle[*c]);
    half_angle[n] = len(sum) > 0 ? std::min(kPi, a) : kPi;
    NodeBound& b = bounds_[n];
    b.x = static_cast<float>(centre[0]);
    b.y = static_cast<float>(centre[1]);
    b.z = static_cast<float>(centre[2]);
    // Rounded up so that float storage keeps every child inside.
    b.radius = static_cast<float>(r * (1 + 1e-6)) + 1e-30f;
    b.error = e;
    // A cone of pi/2 or more never faces away; stored a little wider than
    // computed so that float rounding keeps every child's cone inside.
    const double stored = half_angle[n] + 1e-5;
    if (stored < kPi / 2) {
      const double l = len(sum);
      b.ax = static_cast<float>(sum[0] / l);
      b.ay = static_cast<float>(sum[1] / l);
      b.az = static_cast<float>(sum[2] / l);
      const double sin_alpha = static_cast<float>(std::sin(stored));
      cones_[n] = {sin_alpha, std::sqrt(1 - sin_alpha * sin_alpha)};
    }
  }
}

// Every front node is evaluated every frame, in no memory order: one
// 32-byte record per node is what most evaluations read.
float DagReplay::priority(uint32_t node) const {
  return evaluate(node, kAlwaysCone);
}

// The back-face test can only set an error to 0, so for an error under the
// tolerance it cannot change NEED-APPLY's answer (0 and the error are both
// under it): the traversals that only ask NEED-APPLY skip it there, the
// cheapest tests (frustum, then distance) coming first.
float DagReplay::evaluate(uint32_t node, float cone_from) const {
  const NodeBound& b = bounds_[node];
  const double x = b.x, y = b.y, z = b.z, r = b.radius;
  for (const std::array<double, 4>& q : planes_) {
    if (q[0] * x + q[1] * y + q[2] * z + q[3] < -r) return 0;
  }
  const double dx = x - eye_[0], dy = y - eye_[1], dz = z - eye_[2];
  const double centre_distance = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double d = std::max({centre_distance - r, near_distance_, 1e-12});
  const float error = static_cast<float>(double{b.error} / d * pixels_per_unit_at_1_);
  if (!back_face_ || error < cone_from) return error;
  return faces_away(b, cones_[node], dx, dy, dz, centre_distance) ? 0 : error;
}

// Every normal n of the cone and every point p of the sphere have
// n . (p - eye) > 0 when the angle between the axis and the direction to
// the centre (theta), the cone's half-angle (alpha) and the sphere's
// angular radius seen from the eye (beta) sum to under pi/2; compared as
// cos(theta + alpha + beta) > 0 without trigonometry. The early outs come
// cheapest first; a wide cone's zero axis leaves at the first dot product,
// before the NodeCone is read.
bool DagReplay::faces_away(const NodeBound& b, const NodeCone& cone, double dx, double dy,
                           double dz, double distance) {
  if (!(distance > b.radius)) return false;
  // distance > 0, so the sign of cos_theta is the dot product's.
  const double dot = b.ax * dx + b.ay * dy + b.az * dz;
  if (!(dot > 0) || !(cone.sin_half_angle < 1)) return false;
  const double cos_theta = dot / distance;
  const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  const double sin_alpha = cone.sin_half_angle, cos_alpha = cone.cos_half_angle;
  const double sin_beta = b.radius / distance, cos_beta = std::sqrt(1 - sin_beta * sin_beta);
  const double cos_gamma = cos_alpha * cos_beta - sin_alpha * sin_beta;  // gamma = alpha + beta
  if (!(cos_gamma > 0)) return false;
  const double sin_gamma = sin_alpha * cos_beta + cos_alpha * sin_beta;
  return cos_theta * cos_gamma > sin_theta * sin_gamma;
}

Status DagReplay::apply(Side side, uint32_t node, std::vector<uint32_t>* entered) {
  auto enter = [&](FrontQueue* queue, uint32_t n) {
    queue->push(n);
    if (entered != nullptr) entered->push_back(n);
  };
  if (side == Side::kSplit) {
    LODBAKE_RETURN_IF_ERROR(fronts_.split(node));
    triangles_ += added_[node];
    if (fronts_.can_collapse(node)) enter(&collapse_queue_, node);
    for (const uint32_t* c = fronts_.children_begin(node); c != fronts_.children_end(node); ++c) {
      if (fronts_.can_split(*c)) enter(&split_queue_, *c);
    }
  } else {
    LODBAKE_RETURN_IF_ERROR(fronts_.collapse(node));
    triangles_ -= added_[node];
    if (fronts_.can_split(node)) enter(&split_queue_, node);
    for (uint32_t k = dag_->parent_offsets[node]; k < dag_->parent_offsets[node + 1]; ++k) {
      const uint32_t p = dag_->parents[k];
      if (fronts_.can_collapse(p)) enter(&collapse_queue_, p);
    }
  }
  return Status::ok();
}

Status DagReplay::traverse(Side side, DagTraversal traversal, size_t limit, size_t triangle_cap,
                           float tolerance, DagFrameStats* stats) {
  switch (traversal) {
    case DagTraversal::kPriority:
      return traverse_priority(side, limit, triangle_cap, tolerance, stats);
    case DagTraversal::kLinear:
      return traverse_fifo(side, false, limit, triangle_cap, tolerance, stats);
    case DagTraversal::kConstantTime:
      return traverse_fifo(side, true, limit, triangle_cap, tolerance, stats);
  }
  return Status::ok();
}

// Figure 3. Fs pops its largest error first, Fc its smallest; ties go to
// the larger node id (a fixed order). Only the nodes that need the change
// enter the heap: every one of them pops before any that does not (their
// errors lie on either side of the tolerance), and the first that does
// not ends the traversal, so the others would never be applied. Fs's
// order among those needing a split only depends on errors of at least
// the tolerance, which evaluate() gives exactly with cone_from = tolerance;
// Fc's collapses are ordered by errors under it, 0 for a cone facing away,
// so Fc's evaluations are exact.
Status DagReplay::traverse_priority(Side side, size_t limit, size_t triangle_cap, float tolerance,
                                    DagFrameStats* stats) {
  using Entry = std::pair<float, uint32_t>;
  const bool split = side == Side::kSplit;
  auto before = [split](const Entry& a, const Entry& b) { return split ? a < b : b < a; };
  const float cone_from = split ? tolerance : kAlwaysCone;
  std::vector<Entry>& heap = heap_;
  heap.clear();
  const std::vector<uint32_t>& front = split ? fronts_.split_front() : fronts_.collapse_front();
  // The front lists its nodes in no memory order: on a large DAG most
  // records are cache misses, fetched a few nodes ahead.
  constexpr size_t kAhead = 8;
  for (size_t i = 0; i < front.size(); ++i) {
    if (i + kAhead < front.size()) __builtin_prefetch(&bounds_[front[i + kAhead]]);
    const uint32_t n = front[i];
    const float p = evaluate(n, cone_from);
    if (needs(side, p, tolerance)) heap.push_back({p, n});
  }
  stats->visited += front.size();
  std::make_heap(heap.begin(), heap.end(), before);
  std::vector<uint32_t>& entered = entered_;
  size_t changes = 0;
  while (!heap.empty() && changes < limit) {
    std::pop_heap(heap.begin(), heap.end(), before);
    const Entry top = heap.back();
    heap.pop_back();
    if (!in_front(side, top.second)) continue;
    if (split && triangles_ + added_[top.second] > triangle_cap) break;
    entered.clear();
    LODBAKE_RETURN_IF_ERROR(apply(side, top.second, &entered));
    ++changes;
    for (uint32_t n : entered) {
      if (!in_front(side, n)) continue;
      ++stats->visited;
      const float p = evaluate(n, cone_from);
      if (!needs(side, p, tolerance)) continue;
      heap.push_back({p, n});
      std::push_heap(heap.begin(), heap.end(), before);
    }
  }
  (split ? stats->splits : stats->collapses) += changes;
  return Status::ok();
}

// Figures 4 (count_visits false: N changes) and 5 (true: N visits).
Status DagReplay::traverse_fifo(Side side, bool count_visits, size_t limit, size_t triangle_cap,
                                float tolerance, DagFrameStats* stats) {
  const bool split = side == Side::kSplit;
  FrontQueue& queue = split ? split_queue_ : collapse_queue_;
  size_t count = 0, changes = 0, idle = 0;
  constexpr size_t kAhead = 8;  // as in traverse_priority()
  while (!queue.empty() && count < limit) {
    if (kAhead < queue.size()) __builtin_prefetch(&bounds_[queue.node_at(kAhead)]);
    const FrontQueue::Entry entry = queue.pop_front();
    const uint32_t n = entry.node;
    // The view is the frame's: a node that needed nothing earlier in this
    // traversal (the linear traversal's last sweep of the front, a small
    // front visited twice by the constant-time one) still needs nothing,
    // and is still in the front: this side's changes take no node out of
    // its own front but the one they apply.
    const bool needless = entry.needless_in == frame_stamp_;
    if (!needless && !in_front(side, n)) {
      queue.drop(n);
      continue;
    }
    if (count_visits) ++count;
    ++stats->visited;
    if (!needless && needs(side, evaluate(n, tolerance), tolerance)) {
      if (split && triangles_ + added_[n] > triangle_cap) {
        queue.requeue_front(n);
        break;
      }
      queue.drop(n);
      LODBAKE_RETURN_IF_ERROR(apply(side, n, nullptr));
      ++changes;
      if (!count_visits) ++count;
      idle = 0;
    } else {
      queue.requeue_back(n, frame_stamp_);
      if (!count_visits && ++idle >= front_size(side)) break;
    }
  }
  (split ? stats->splits : stats->collapses) += changes;
  return Status::ok();
}

Result<DagFrameStats> DagReplay::adapt(const BoundingSphere& sphere, const CameraFrame& frame,
                                       const DagReplayOptions& options) {
  try {
    const auto start = std::chrono::steady_clock::now();
    near_distance_ = double{options.viewport.near_fraction} * sphere.radius;
    back_face_ = options.back_face;
    view_ = view_parameters(frame, options.viewport, static_cast<float>(near_distance_),
                            options.tolerance_pixels);
    planes_.clear();
    for (const std::array<float, 4>& q : view_.frustum)
      planes_.push_back({double{q[0]}, double{q[1]}, double{q[2]}, double{q[3]}});
    eye_ = {double{view_.eye[0]}, double{view_.eye[1]}, double{view_.eye[2]}};
    pixels_per_unit_at_1_ =
        options.viewport.height / (2 * std::tan(double{frame.fov_degrees} * kPi / 360));
    DagFrameStats stats;
    // A warm start lets the first frame reach its cut in one go: the mesh
    // a client would load before the route begins. Constant-time traversal
    // counts visits, not changes, so that frame runs the linear traversal
    // (which stops once a whole front needs nothing).
    const bool warm = options.warm_start && frames_ == 0;
    const size_t n = warm ? std::numeric_limits<size_t>::max() : options.max_changes;
    const DagTraversal traversal = warm && options.traversal == DagTraversal::kConstantTime
                                       ? DagTraversal::kLinear
                                       : options.traversal;
    ++frames_;
    if (++frame_stamp_ == 0) {
      split_queue_.forget_answers();
      collapse_queue_.forget_answers();
      frame_stamp_ = 1;
    }
    switch (options.budget_mode) {
      case DagBudgetMode::kBudget:
        stats.budget_mode = true;
        break;
      case DagBudgetMode::kFree:
        stats.budget_mode = false;
        break;
      case DagBudgetMode::kAuto:
        // Overflow-safe form of triangles + N * max_added > budget.
        stats.budget_mode =
            options.triangle_budget < triangles_ ||
            (max_added_ != 0 && n > (options.triangle_budget - triangles_) / max_added_);
        break;
    }
    const size_t cap =
        stats.budget_mode ? options.triangle_budget : std::numeric_limits<size_t>::max();
    const float tol = options.tolerance_pixels;
    LODBAKE_RETURN_IF_ERROR(traverse(Side::kCollapse, traversal, n, cap, tol, &stats));
    LODBAKE_RETURN_IF_ERROR(traverse(Side::kSplit, traversal, n, cap, tol, &stats));
    stats.split_front = fronts_.split_front().size();
    stats.collapse_front = fronts_.collapse_front().size();
    stats.triangles = triangles_;
    stats.traversal_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory traversing the DAG");
  }
}

std::vector<std::string> DagReplay::check() const {
  std::vector<std::string> problems = fronts_.check_counters();
  TriangleMesh mesh;
  mesh.positions.assign(pm_->base.vertex_count() + pm_->splits.size(), Vec3f{0, 0, 0});
  mesh.triangles = cut_triangles();
  for (std::string& p : triangulation_problems(mesh))
    problems.push_back(std::move(p));
  if (mesh.triangle_count() != triangles_) {
    problems.push_back("triangle count " + std::to_string(triangles_) + " but the cut has " +
                       std::to_string(mesh.triangle_count()) + " triangles");
  }
  size_t unqueued = 0;
  for (uint32_t n : fronts_.split_front())
    unqueued += split_queue_.queued[n] == 0;
  for (uint32_t n : fronts_.collapse_front())
    unqueued += collapse_queue_.queued[n] == 0;
  if (unqueued != 0)
    problems.push_back(std::to_string(unqueued) +
                       " front nodes missing from their traversal queue");
  return problems;
}

std::vector<std::string> check_dag_wedges(const DagReplay& replay, const CornerWedges& lookup,
                                          const PmWedges& wedges) {
  const SplitLineage& lineage = replay.lineage();
  const std::vector<uint32_t> cut = replay.cut();
  std::vector<std::array<uint32_t, 3>> corners(cut.size());
  for (size_t f = 0; f < cut.size(); ++f)
    for (int k = 0; k < 3; ++k)
      corners[f][k] = lookup.wedge(lineage.face_slot[cut[f]], lineage.triangles[cut[f]][k]);
  return corner_wedge_problems(corners, wedges);
}

double cut_accuracy(const std::vector<Triangle>& reference, const std::vector<Triangle>& other) {
  if (reference.empty()) return 1;
  const std::vector<Triangle> a = sorted_canonical(reference);
  const std::vector<Triangle> b = sorted_canonical(other);
  size_t shared = 0;
  for (size_t i = 0, j = 0; i < a.size() && j < b.size();) {
    if (a[i] < b[j]) {
      ++i;
    } else if (b[j] < a[i]) {
      ++j;
    } else {
      ++shared, ++i, ++j;
    }
  }
  return static_cast<double>(shared) / static_cast<double>(a.size());
}

}  // namespace lodbake
