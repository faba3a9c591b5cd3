// An LOD chain from one simplification run: the meshes a progressive mesh
// passes through at given triangle counts, taken while refining its base,
// so a chain of N levels costs one simplification and one replay.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

// For each target, the finest mesh of `pm` with at most that many triangles
// (the same rule simplify() stops by, so a target equal to the run's own
// gives its result; the base when even it has more; the fully refined mesh
// when the target exceeds it). Meshes are returned in the order of
// `triangle_targets`.
Result<std::vector<TriangleMesh>> extract_lods(const ProgressiveMesh& pm,
                                               const std::vector<uint64_t>& triangle_targets);

// A level of detail asked for by vertex count, triangle count or ratio of
// the fully refined mesh's triangles.
struct LodRequest {
  enum class Kind { kVertices, kTriangles, kRatio };
  Kind kind = Kind::kVertices;
  uint64_t count = 0;  // kVertices, kTriangles
  double ratio = 1;    // kRatio, in (0, 1]
};

// Parses "5000" (vertices), "5000t" (triangles) or "0.25" (a ratio: has a
// decimal point, 0 < R <= 1). kUsage with a one-line message otherwise.
Result<LodRequest> parse_lod_request(const std::string& text);

// The PM vertex count of the requested level: the vertex count itself
// (clamped to the PM's range), or the finest level with at most the given
// number of triangles (floor(ratio * full triangles) for a ratio).
size_t lod_vertex_count(const ProgressiveMesh& pm, const LodRequest& request);

}  // namespace lodbake
