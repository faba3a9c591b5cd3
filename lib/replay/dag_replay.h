// Replaying a camera path on the DAG of vertex splits (issue 8, mode dag):
// Zheng and Chan's MANAGE-TRAVERSAL with the priority-oriented traversal in
// budget mode over DagFronts (lib/dag), a mesh-change limit per frame and a
// triangle budget.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/vsplit_dag.h"
#include "formats/support/status.h"
#include "lib/dag/dag_fronts.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/replay/camera_path.h"

namespace lodbake {

struct DagReplayOptions {
  Viewport viewport;
  /// A split is wanted while its projected error exceeds this many pixels.
  float tolerance_pixels = 1.0f;
  /// N: at most this many splits + collapses per frame (the paper: 300).
  size_t max_changes = 300;
  /// The triangle budget (the paper: 60000).
  size_t triangle_budget = 60000;
};

struct DagFrameStats {
  size_t splits = 0;
  size_t collapses = 0;
  size_t split_front = 0;     ///< |Fs| after the frame
  size_t collapse_front = 0;  ///< |Fc| after the frame
  size_t triangles = 0;
  double traversal_ms = 0;  ///< wall time of the frame's traversal
};

/// The DAG, the PM it was built from, and the triangle lineage of the PM.
class DagReplay {
 public:
  /// Fails when `dag` is not the PM's (node count, base vertex count) or the
  /// lineage cannot be built. `pm` and `dag` must outlive the replay.
  static Result<DagReplay> create(const ProgressiveMesh& pm, const VsplitDag& dag);

  /// One frame of MANAGE-TRAVERSAL for `frame`.
  Result<DagFrameStats> adapt(const BoundingSphere& sphere, const CameraFrame& frame,
                              const DagReplayOptions& options);

  size_t triangle_count() const { return triangles_; }
  const DagFronts& fronts() const { return fronts_; }
  /// Projected error of split `node` in pixels for the view (0 outside the
  /// frustum); exposed for tests.
  float priority(uint32_t node) const;

  /// Problems of the current cut, empty when its triangles form an
  /// edge-manifold, consistently oriented triangulation without repeated
  /// indices or duplicates, the front counters are consistent and the
  /// tracked triangle count is the cut's.
  std::vector<std::string> check() const;

 private:
  DagReplay(const ProgressiveMesh& pm, const VsplitDag& dag, DagFronts fronts)
      : pm_(&pm), dag_(&dag), fronts_(std::move(fronts)) {}
  bool is_parent(uint32_t parent, uint32_t node) const;

  const ProgressiveMesh* pm_;
  const VsplitDag* dag_;
  DagFronts fronts_;
  SplitLineage lineage_;
  std::vector<uint32_t> added_;  // net triangles a split adds
  size_t triangles_ = 0;
  // The current frame's view (set by adapt()).
  ViewParameters view_;
  double pixels_per_unit_at_1_ = 0;  // height / (2 tan(fov/2))
};

}  // namespace lodbake
