// Building To-Lau-Green vertex trees from a half-edge progressive mesh.
// Definitions and choices: docs/hierarchy-dag-vtrees.md.
#pragma once

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/vertex_trees.h"
#include "formats/support/status.h"

namespace lodbake {

/// Replays `pm` in split order: base nodes get their fans in the base mesh,
/// split k's left and right nodes the fans of vt and vs right after the
/// split. Vertex and triangle states follow the paper's equations (1)-(3)
/// over the collapse order (the splits reversed).
/// \return kUnsupported when a split moves vs (optimal placement: a right
///         node has no coordinate of its own), kInvalidInput when a record
///         does not fit the mesh, kRuntime when memory runs out.
Result<VertexTrees> build_vertex_trees(const ProgressiveMesh& pm);

}  // namespace lodbake
