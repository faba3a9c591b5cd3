// Per-node refinement data (RFIN) of a vertex hierarchy for Hoppe's
// view-dependent criteria (Hoppe 1997; Kim, Lee and Kobbelt 5.3, qrefine).
#pragma once

#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"

namespace lodbake {

/// One entry per node of `h`, computed against `fine`, the fully refined
/// mesh in input vertex ids (h.input_vertex): bounding-sphere radius around
/// the node's position holding its subtree's leaves, the cone of the normals
/// of the faces around those leaves, mu = the largest collapse error in the
/// subtree and delta = the largest distance of a subtree leaf from the
/// node's tangent plane (docs/hierarchy.md). Leaves get radius, mu and delta
/// zero and their own faces' cone.
/// \pre validate_hierarchy(h) is empty.
/// \return kInvalidInput when `fine` does not have one vertex per leaf or
///         has an out-of-range index.
Result<std::vector<NodeRefinement>> compute_refinement_data(const VertexHierarchy& h,
                                                            const TriangleMesh& fine);

}  // namespace lodbake
