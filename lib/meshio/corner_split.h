// Per-corner attributes (OBJ-style separate index streams) turned into
// per-vertex ones, for formats that only have per-vertex attributes (PLY,
// OFF variants, glTF).
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

/// Returns `mesh` with every per-corner attribute made per-vertex. A vertex
/// whose corners use different attribute values is duplicated once per
/// distinct combination of values; the first combination met (in triangle
/// order) keeps the vertex's index and the others are appended in the order
/// they are met, so vertex indices stay stable where nothing needs splitting
/// and the result is deterministic. Vertices no triangle uses keep zeros
/// for the attributes that were per-corner. Meshes without per-corner
/// attributes are returned unchanged.
/// \pre check_writable(mesh) is ok.
TriangleMesh split_corner_attributes(const TriangleMesh& mesh);

/// The same, also giving for every vertex of the result the vertex of
/// `mesh` it comes from (so that other per-vertex data can follow the split).
TriangleMesh split_corner_attributes(const TriangleMesh& mesh,
                                     std::vector<uint32_t>* source_vertex);

}  // namespace lodbake
