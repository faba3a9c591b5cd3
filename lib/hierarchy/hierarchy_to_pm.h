// A vertex hierarchy as a progressive mesh (formats/mesh/progressive_mesh.h),
// so that the PM replay, the DAG and the vertex-tree builders can run on the
// balanced hierarchy.
#pragma once

#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"

namespace lodbake {

/// The splits of `h` in a valid coarse-to-fine order: internal nodes in
/// array (breadth-first) order, each preceded by the splits SelStreamVSplit's
/// partial order asks for; every split's wings are its cut vertices' active
/// ancestors at that moment. PM vertex i < #roots is root i; split k creates
/// PM vertex #roots + k (the right child), the left child keeps its parent's
/// PM vertex. input_vertex maps PM vertices to h.input_vertex. Replaying all
/// splits gives the input mesh exactly (in PM vertex ids). When
/// `node_of_split` is not null it gets the node of each split.
/// \return the refiner's error when `h` is malformed or a split is refused.
Result<ProgressiveMesh> hierarchy_to_progressive_mesh(
    const VertexHierarchy& h, std::vector<uint32_t>* node_of_split = nullptr);

}  // namespace lodbake
