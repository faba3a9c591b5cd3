// Replaying a camera path on the balanced vertex hierarchy (issue 8, mode
// vhier): per frame, the SelectiveRefiner is adapted to the view with
// adapt_to_view (qrefine: frustum, back-face cone, screen-space error), and
// optionally the current mesh is checked.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"
#include "lib/hierarchy/front_wedges.h"
#include "lib/hierarchy/selective_refiner.h"
#include "lib/replay/camera_path.h"

namespace lodbake {

struct VhierReplayOptions {
  Viewport viewport;
  /// Screen-space tolerance in pixels of the viewport's height.
  float tolerance_pixels = 1.0f;
  /// adapt_to_view's pass limit per frame.
  size_t max_passes = 64;
};

struct VhierFrameStats {
  size_t splits = 0;
  size_t collapses = 0;
  size_t passes = 0;
  size_t front_size = 0;  ///< active nodes = current vertices
  size_t triangles = 0;
  double adapt_ms = 0;  ///< wall time of adapt_to_view (steady clock)
};

/// Adapts `refiner` to one camera. `sphere` is the model's bounding sphere
/// (the near plane is viewport.near_fraction times its radius).
Result<VhierFrameStats> adapt_vhier_frame(SelectiveRefiner* refiner, const VertexHierarchy& h,
                                          const std::vector<NodeRefinement>& data,
                                          const BoundingSphere& sphere, const CameraFrame& frame,
                                          const VhierReplayOptions& options);

/// The current mesh's problems, empty when it is an edge-manifold (at most
/// two faces per edge), consistently oriented triangulation without repeated
/// indices or duplicate triangles, and the refiner's counters (front size,
/// triangle count) agree with it. Each entry is one line.
std::vector<std::string> check_vhier_mesh(const SelectiveRefiner& refiner);

/// The current mesh's attributes: every corner has a wedge
/// (FrontWedges::corners()) and a face's three wedges belong to one
/// primitive of the asset's mesh (one material). One line per problem.
std::vector<std::string> check_vhier_wedges(const SelectiveRefiner& refiner,
                                            const FrontWedges& front, const PmWedges& wedges);

}  // namespace lodbake
