// Replaying a camera path on the DAG of vertex splits (issue 8, mode dag):
// Zheng and Chan's MANAGE-TRAVERSAL over DagFronts (lib/dag) with each of the
// paper's three traversals (priority-oriented, linear, constant-time), in
// BUDGET or FREE mode, with a mesh-change limit per frame and a triangle
// budget, and the accuracy measure of the paper's Figure 7.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/vsplit_dag.h"
#include "formats/support/status.h"
#include "lib/dag/dag_fronts.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/replay/camera_path.h"
#include "lib/simplify/wedge_replay.h"

namespace lodbake {

/// The three traversals of the paper's section 5.
enum class DagTraversal {
  kPriority,      ///< Figure 3: every front node evaluated, best first
  kLinear,        ///< Figure 4: FIFO fronts kept across frames, N changes
  kConstantTime,  ///< Figure 5: FIFO fronts kept across frames, N nodes visited
};

/// "priority", "linear", "constant".
const char* dag_traversal_name(DagTraversal traversal);

/// How MANAGE-TRAVERSAL's mode is chosen each frame.
enum class DagBudgetMode {
  /// The client's rule of section 4: FREE while N changes cannot reach the
  /// budget, BUDGET once they could.
  kAuto,
  kBudget,  ///< always BUDGET-MODE
  kFree,    ///< always FREE-MODE: no triangle budget at all
};

struct DagReplayOptions {
  Viewport viewport;
  /// A split is wanted while its projected error exceeds this many pixels.
  float tolerance_pixels = 1.0f;
  /// N: at most this many splits and this many collapses per frame (the
  /// paper: 300); for the constant-time traversal, the nodes each of
  /// TRAVERSE-COLLAPSE and TRAVERSE-SPLIT visits.
  size_t max_changes = 300;
  /// The triangle budget (the paper: 60000).
  size_t triangle_budget = 60000;
  DagTraversal traversal = DagTraversal::kPriority;
  DagBudgetMode budget_mode = DagBudgetMode::kAuto;
  /// The first frame runs without the mesh-change limit N (the mesh a
  /// client would load before the route starts); N holds from the second.
  bool warm_start = false;
  /// Back-facing simplification (the paper's experiments use it): a node
  /// whose cone of normals faces away from the eye needs no split.
  bool back_face = true;
};

struct DagFrameStats {
  size_t splits = 0;
  size_t collapses = 0;
  /// Front nodes evaluated (ERROR-EVALUATE calls; a FIFO traversal's second
  /// visit of a node in one frame counts, reusing the first one's answer).
  size_t visited = 0;
  bool budget_mode = false;   ///< the frame ran in BUDGET-MODE
  size_t split_front = 0;     ///< |Fs| after the frame
  size_t collapse_front = 0;  ///< |Fc| after the frame
  size_t triangles = 0;
  double traversal_ms = 0;  ///< wall time of the frame's MANAGE-TRAVERSAL
};

/// The DAG, the PM it was built from, the triangle lineage of the PM, the
/// fronts, and the FIFO queues the linear and constant-time traversals keep
/// from one frame to the next.
class DagReplay {
 public:
  /// Fails when `dag` is not the PM's (node count, base vertex count) or the
  /// lineage cannot be built. `pm` and `dag` must outlive the replay.
  static Result<DagReplay> create(const ProgressiveMesh& pm, const VsplitDag& dag);

  /// One frame of MANAGE-TRAVERSAL for `frame` with options.traversal.
  Result<DagFrameStats> adapt(const BoundingSphere& sphere, const CameraFrame& frame,
                              const DagReplayOptions& options);

  size_t triangle_count() const { return triangles_; }
  const DagFronts& fronts() const { return fronts_; }
  /// ERROR-EVALUATE: the error bound of split `node` (the largest collapse
  /// error of it and its descendants) projected at the distance of its
  /// bounding sphere, in pixels, for the last frame's view; 0 when the
  /// sphere is outside the frustum. Never larger for a child than for its
  /// parents. Exposed for tests.
  float priority(uint32_t node) const;
  /// Radius of the sphere around split `node`'s new vertex that holds its
  /// triangles and its descendants' spheres.
  float bound_radius(uint32_t node) const { return bounds_[node].radius; }
  /// The current cut's triangles (vertex ids of the PM: base vertices, then
  /// split i's new vertex as base_vertex_count + i).
  std::vector<Triangle> cut_triangles() const { return dag_cut_triangles(lineage_, fronts_); }
  /// The same cut as indices into lineage().
  std::vector<uint32_t> cut() const { return dag_cut(lineage_, fronts_); }
  const SplitLineage& lineage() const { return lineage_; }

  /// Problems of the current cut, empty when its triangles form an
  /// edge-manifold, consistently oriented triangulation without repeated
  /// indices or duplicates, the front counters are consistent, the tracked
  /// triangle count is the cut's and every front node is in its queue.
  std::vector<std::string> check() const;

 private:
  // A FIFO over one front that outlives the frame. A node is queued at most
  // once; entries whose node has left the front are dropped when popped.
  // An entry remembers the frame stamp (frame_stamp_) of the frame in which
  // its node was evaluated and needed no change, so that a second visit in
  // the same frame, on the same view, reuses the answer; 0: not evaluated.
  // A ring buffer (power-of-two capacity, doubled when full): the queue is
  // popped and pushed once per visit, and std::deque's block allocations
  // cost more than an evaluation.
  class FrontQueue {
   public:
    struct Entry {
      uint32_t node;
      uint32_t needless_in;
    };
    std::vector<uint8_t> queued;  // per node: it has an entry

    bool empty() const { return size_ == 0; }
    // The first entry; its node stays `queued` until requeued or dropped.
    Entry pop_front() {
      const Entry e = ring_[head_];
      head_ = (head_ + 1) & (ring_.size() - 1);
      --size_;
      return e;
    }
    // The node of the i-th entry from the front, i < size().
    size_t size() const { return size_; }
    uint32_t node_at(size_t i) const { return ring_[(head_ + i) & (ring_.size() - 1)].node; }
    void drop(uint32_t node) { queued[node] = 0; }
    // For the node of the entry just popped, neither requeued nor dropped.
    void requeue_front(uint32_t node) {
      reserve_one();
      head_ = (head_ + ring_.size() - 1) & (ring_.size() - 1);
      ring_[head_] = {node, 0};
      ++size_;
    }
    void requeue_back(uint32_t node, uint32_t needless_in) {
      reserve_one();
      ring_[(head_ + size_) & (ring_.size() - 1)] = {node, needless_in};
      ++size_;
    }
    void push(uint32_t node) {
      if (queued[node] == 0) {
        queued[node] = 1;
        requeue_back(node, 0);
      }
    }
    // Forgets every remembered answer (when the frame stamp wraps).
    void forget_answers() {
      for (Entry& e : ring_)
        e.needless_in = 0;
    }

   private:
    void reserve_one() {
      if (size_ < ring_.size()) return;
      std::vector<Entry> grown(ring_.empty() ? 64 : 2 * ring_.size());
      for (size_t i = 0; i < size_; ++i)
        grown[i] = ring_[(head_ + i) & (ring_.size() - 1)];
      ring_ = std::move(grown);
      head_ = 0;
    }
    std::vector<Entry> ring_;
    size_t head_ = 0, size_ = 0;
  };
  enum class Side { kCollapse, kSplit };

  DagReplay(const ProgressiveMesh& pm, const VsplitDag& dag, DagFronts fronts)
      : pm_(&pm), dag_(&dag), fronts_(std::move(fronts)) {}
  void derive_bounds();
  bool in_front(Side side, uint32_t node) const {
    return side == Side::kSplit ? fronts_.can_split(node) : fronts_.can_collapse(node);
  }
  size_t front_size(Side side) const {
    return side == Side::kSplit ? fronts_.split_front().size() : fronts_.collapse_front().size();
  }
  // NEED-APPLY: a collapse while under the tolerance, a split while not.
  bool needs(Side side, float priority, float tolerance) const {
    return side == Side::kSplit ? !(priority < tolerance) : priority < tolerance;
  }
  // APPLY-OP and ADJUST-FRONTS: applies the operation and queues the nodes
  // that entered a front; `entered` (may be null) receives them too.
  Status apply(Side side, uint32_t node, std::vector<uint32_t>* entered);
  // TRAVERSE-COLLAPSE / TRAVERSE-SPLIT with the chosen traversal; at most
  // `limit` changes (priority, linear) or visits (constant-time); a split
  // must keep the triangle count within `triangle_cap`.
  Status traverse(Side side, DagTraversal traversal, size_t limit, size_t triangle_cap,
                  float tolerance, DagFrameStats* stats);
  Status traverse_priority(Side side, size_t limit, size_t triangle_cap, float tolerance,
                           DagFrameStats* stats);
  Status traverse_fifo(Side side, bool count_visits, size_t limit, size_t triangle_cap,
                       float tolerance, DagFrameStats* stats);

  const ProgressiveMesh* pm_;
  const VsplitDag* dag_;
  DagFronts fronts_;
  SplitLineage lineage_;
  std::vector<uint32_t> added_;  // net triangles a split adds
  uint32_t max_added_ = 0;
  // Per node, what every evaluation of a node in the frustum reads, in one
  // 32-byte record (one cache line): the new vertex (the sphere's centre),
  // bound_radius(), the error bound priority() projects, and the unit axis
  // of the cone of normals, 0 when the cone is pi/2 or wider and never
  // faces away.
  struct alignas(32) NodeBound {
    float x = 0, y = 0, z = 0, radius = 0, error = 0;
    float ax = 0, ay = 0, az = 0;
  };
  static_assert(sizeof(NodeBound) == 32, "one node record per half cache line");
  // The rest of the cone, read only by the few evaluations that get to it:
  // sine of the half-angle (2 when the cone never faces away) and its
  // cosine, precomputed (in double, from the float sine the test used to
  // read, so that the test's arithmetic is unchanged).
  struct NodeCone {
    double sin_half_angle = 2, cos_half_angle = 0;
  };
  // ERROR-EVALUATE (priority()), with the cone test only for an error of at
  // least `cone_from` (kAlwaysCone: always).
  float evaluate(uint32_t node, float cone_from) const;
  static bool faces_away(const NodeBound& b, const NodeCone& cone, double dx, double dy, double dz,
                         double distance);
  std::vector<NodeBound> bounds_;
  std::vector<NodeCone> cones_;
  size_t triangles_ = 0;
  size_t frames_ = 0;         // adapt() calls so far
  uint32_t frame_stamp_ = 0;  // the current frame's FrontQueue stamp, from 1
  FrontQueue split_queue_;
  FrontQueue collapse_queue_;
  // Reused by traverse_priority() from one call to the next.
  std::vector<std::pair<float, uint32_t>> heap_;
  std::vector<uint32_t> entered_;
  // The current frame's view (set by adapt()): the frustum's planes and the
  // eye in double, as the evaluation computes with them.
  ViewParameters view_;
  std::vector<std::array<double, 4>> planes_;
  std::array<double, 3> eye_{};
  double pixels_per_unit_at_1_ = 0;  // height / (2 tan(fov/2))
  double near_distance_ = 0;
  bool back_face_ = true;
};

/// The current cut's corner wedges (an asset's PM with WEDG: `lookup` over
/// the same PM as `replay`): every corner has one, a face's three belong to
/// one primitive (corner_wedge_problems()). One line per problem.
std::vector<std::string> check_dag_wedges(const DagReplay& replay, const CornerWedges& lookup,
                                          const PmWedges& wedges);

/// The share of `reference`'s triangles that `other` also has, in [0, 1]
/// (1 when `reference` has none): the paper's accuracy of a traversal
/// against the priority-oriented one. A triangle is the same when it has
/// the same corners in the same cyclic order.
double cut_accuracy(const std::vector<Triangle>& reference, const std::vector<Triangle>& other);

}  // namespace lodbake
