// Internal vertex numbering for the collapse engine. The engine's walk and
// listing read the vertices of neighbouring triangles together; numbering
// the vertices in the order the triangles first use them puts those records,
// quadrics and corner lists near each other in memory. The triangles keep
// their order, and every comparison of vertex indices in the engine uses the
// input ids, so the collapse sequence is the same as without renumbering.
// Internal to lib/simplify.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "lib/simplify/collapse_engine.h"

namespace lodbake {
namespace simplify_internal {

/// order[internal id] = input id: the vertices in the order the triangles
/// first use them, then the unused ones in input order. False (and `order`
/// left empty) when a triangle has an index out of range.
bool locality_order(const TriangleMesh& mesh, std::vector<uint32_t>* order);

/// `mesh` with its vertices renumbered by `order`: positions and per-vertex
/// attribute values gathered, triangle indices renamed; triangles, their
/// order and per-corner attributes unchanged.
/// \pre locality_order(mesh, &order) returned true.
TriangleMesh renumbered_mesh(const TriangleMesh& mesh, const std::vector<uint32_t>& order);

/// Turns an engine state over renumbered_mesh(mesh, order) into the state
/// over `mesh`: every vertex index, position and per-vertex value back to the
/// input's numbering.
void restore_input_ids(const std::vector<uint32_t>& order, EngineState* state);

}  // namespace simplify_internal
}  // namespace lodbake
