// Turning the engine's collapse log into a ProgressiveMesh: vertex ids
// permuted so that the base vertices come first and split i creates vertex
// base_count + i. Internal to lib/simplify.
#pragma once

#include "formats/mesh/progressive_mesh.h"
#include "lib/simplify/collapse_engine.h"

namespace lodbake {
namespace simplify_internal {

/// `input` is the mesh the engine ran on (for the per-vertex attributes the
/// PM carries), `state` what it left.
ProgressiveMesh record_progressive_mesh(const TriangleMesh& input, const EngineState& state);

}  // namespace simplify_internal
}  // namespace lodbake
