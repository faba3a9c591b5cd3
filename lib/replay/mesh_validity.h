// The per-frame mesh check every replay mode's --validate shares: lib/check's
// exact index-structure counts turned into the lines a violation reports.
#pragma once

#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

/// Problems of `mesh` as a replayed triangulation: triangles with an
/// out-of-range or repeated index, duplicate triangles, edges with more than
/// two faces, edges walked twice in the same direction (inconsistent
/// orientation). Non-manifold vertices are not a problem (an input may have
/// them and the structures keep them); positions are not looked at. One line
/// per kind, with its count; empty when all is well.
std::vector<std::string> triangulation_problems(const TriangleMesh& mesh);

}  // namespace lodbake
