// Replaying a camera path on the fan-hierarchy (issue 8, mode fan): Livny,
// Sokolovsky & El-Sana's dual-path adapt (section 3.4) over lib/fanmerge's
// FanRuntime. Per frame the active-nodes list is scanned; each node's target
// merge pointer comes from its error projected at its vertex's distance, and
// the node gets there by one fan-merge / fan-split (coarse path) or by
// stepping its merge pointer (fine path: edge collapses, vertex splits).
// No CGAL, no lib/hierarchy: FANH + BASE are all it reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/fan_hierarchy.h"
#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/fanmerge/fan_runtime.h"
#include "lib/fanmerge/fan_wedges.h"
#include "lib/replay/camera_path.h"

namespace lodbake {

struct FanReplayOptions {
  Viewport viewport;
  /// Screen-space tolerance in pixels of the viewport's height (as vhier);
  /// 0 refines everything in view, zero-error fans included.
  float tolerance_pixels = 1.0f;
  /// The dual-path switch: a node whose target is an end of its fine path
  /// (every child merged, or none) and at least
  /// max(1, ceil(coarse_fraction * children)) steps away from its merge
  /// pointer changes by one fan-merge / fan-split; otherwise its pointer is
  /// stepped. 0: the coarse path whenever the target is an end; above 1:
  /// the fine path only.
  float coarse_fraction = 0.5f;
};

struct FanFrameStats {
  size_t fan_merges = 0;  ///< coarse path, coarsening
  size_t fan_splits = 0;  ///< coarse path, refining
  size_t collapses = 0;   ///< fine path: merge pointer advanced (one edge collapse)
  size_t splits = 0;      ///< fine path: merge pointer retreated (one vertex split)
  size_t refused = 0;     ///< nodes left short of their target (FanRuntime refused a step)
  size_t active = 0;      ///< active nodes after the frame (= current vertices)
  size_t triangles = 0;
  double adapt_ms = 0;  ///< wall time of the frame's adapt (steady clock)

  size_t operations() const { return fan_merges + fan_splits + collapses + splits; }
};

class FanReplay {
 public:
  enum class Start {
    kCoarsest,  ///< every node fan-merged (FanRuntime::merge_all), the default
    kInput,     ///< every merge pointer 0
  };

  /// Builds the runtime (FanRuntime::create's checks, with the
  /// construction dependencies unless `dependencies` is false, which only
  /// tests use) and the per-node view data: a bounding sphere around each
  /// node's vertex holding every vertex of its subtree, and the error
  /// saturated up the forest.
  /// \return kInvalidInput from FanRuntime::create or when the coarsest
  ///         mesh cannot be reached (the merges do not fit the mesh);
  ///         kRuntime on out of memory.
  static Result<FanReplay> create(const TriangleMesh& input, const FanHierarchy& hierarchy,
                                  Start start = Start::kCoarsest, bool dependencies = true);

  /// One frame: scan the active-nodes list and move every node it reaches
  /// toward its target. `sphere` is the model's bounding sphere (the near
  /// plane is viewport.near_fraction times its radius).
  Result<FanFrameStats> adapt(const BoundingSphere& sphere, const CameraFrame& frame,
                              const FanReplayOptions& options);

  const FanRuntime& runtime() const { return runtime_; }
  /// The merge pointer `node` should have for the view of the last adapt():
  /// collapsible_children(node) outside the frustum; else the largest k with
  /// saturated_error(node) * k / children < (kappa * distance)^2. Exposed
  /// for tests.
  uint32_t target(uint32_t node) const;
  /// max(the node's FANH error, its children's saturated errors), squared
  /// model units; 0 for a leaf.
  float saturated_error(uint32_t node) const { return saturated_[node]; }
  /// Radius of the sphere around vertex(node) holding its subtree's vertices.
  float radius(uint32_t node) const { return radius_[node]; }

  /// The current mesh's problems, empty when it is an edge-manifold,
  /// consistently oriented triangulation without repeated indices or
  /// duplicate triangles (lib/check's exact counts), the runtime's triangle
  /// count is the mesh's, and the active list holds one node per vertex the
  /// mesh uses. Each entry is one line.
  std::vector<std::string> check() const;

 private:
  explicit FanReplay(FanRuntime runtime) : runtime_(std::move(runtime)) {}
  void evaluate(uint32_t node, FanFrameStats* stats);

  FanRuntime runtime_;
  std::vector<Vec3f> positions_;  // the input's
  std::vector<float> saturated_;
  std::vector<float> radius_;
  std::vector<uint32_t> visited_;  // frame stamp per node: evaluated at most once a frame
  uint32_t frame_ = 0;
  // The view of the current frame.
  ViewParameters view_;
  float near_ = 0;
  float coarse_fraction_ = 0.5f;
};

/// An asset's fan front's attributes: every corner of `runtime`'s current
/// mesh has a wedge (FanWedges::corners()) and a face's three wedges belong
/// to one primitive (corner_wedge_problems()). One line per kind of
/// problem; empty when there is none.
std::vector<std::string> check_fan_wedges(const FanRuntime& runtime, const FanWedges& fronts,
                                          const PmWedges& wedges);

}  // namespace lodbake
