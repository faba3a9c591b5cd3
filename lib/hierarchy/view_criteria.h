// Hoppe's view-dependent refinement criteria (Hoppe 1997, section 4;
// Kim, Lee and Kobbelt's qrefine(), section 5.3) on RFIN data, and the
// client's SelectiveRefinement loop on a SelectiveRefiner.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"
#include "lib/hierarchy/selective_refiner.h"

namespace lodbake {

struct ViewParameters {
  Vec3f eye{};
  /// Planes (a, b, c, d) with a*x + b*y + c*z + d >= 0 inside the frustum;
  /// no planes: no frustum test.
  std::vector<std::array<float, 4>> frustum;
  /// Screen-space tolerance as a fraction of the distance (Hoppe's kappa =
  /// 2 tau tan(fov / 2) for a tolerance of tau times the viewport height): a
  /// deviation d at distance z is acceptable while d < kappa z.
  float kappa = 0.001f;
};

/// qrefine(v): true when node v should be split for `view`: its sphere
/// intersects the frustum, its cone of normals does not face entirely away
/// from the eye, and its deviation space projects above the tolerance:
/// mu^2 >= kappa^2 |v-e|^2 or delta^2 (|v-e|^2 - ((v-e).n)^2) >= kappa^2
/// |v-e|^4. A node with zero mu and delta (a leaf) never qualifies.
bool qrefine(const NodeRefinement& data, const Vec3f& position, const ViewParameters& view);

struct AdaptStats {
  size_t splits = 0;
  size_t collapses = 0;
  size_t passes = 0;
};

/// The SelectiveRefinement loop of section 5.3 on the current front, until
/// nothing changes or `max_passes` passes: an active node with qrefine true
/// is split (with SelStreamVSplit's partial order); a node whose children
/// are both active and for which qrefine is false is collapsed when legal.
/// \pre `data` has one entry per node of the refiner's hierarchy.
Result<AdaptStats> adapt_to_view(SelectiveRefiner* refiner, const VertexHierarchy& h,
                                 const std::vector<NodeRefinement>& data,
                                 const ViewParameters& view, size_t max_passes = 64);

}  // namespace lodbake
