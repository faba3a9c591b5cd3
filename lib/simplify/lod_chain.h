// An LOD chain from one simplification run: the meshes a progressive mesh
// passes through at given triangle counts, taken while refining its base,
// so a chain of N levels costs one simplification and one replay.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

// For each target, the coarsest mesh of `pm` with at least that many
// triangles (the base when it already has as many; the fully refined mesh
// when none has). Meshes are returned in the order of `targets`.
Result<std::vector<TriangleMesh>> extract_lods(const ProgressiveMesh& pm,
                                               const std::vector<uint64_t>& triangle_targets);

}  // namespace lodbake
