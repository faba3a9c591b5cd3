// Vertex-to-face adjacency of an indexed triangle mesh, built in flat arrays,
// and the check that the mesh is one the collapse engine can take
// (oriented 2-manifold, possibly with boundary). Internal to lib/simplify.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/core/parallel.h"

namespace lodbake {
namespace simplify_internal {

/// A face around a vertex, as the vertices after and before it.
struct FanCorner {
  uint32_t next;
  uint32_t prev;
};

struct MeshTopology {
  std::vector<uint32_t> face_start;  // vertex_count + 1 offsets into `faces` and `corners`
  std::vector<uint32_t> faces;       // the faces of each vertex, in triangle order
  std::vector<FanCorner> corners;    // the same faces seen from the vertex
  std::vector<uint8_t> boundary;     // 1 when the vertex has a boundary edge
};

/// Builds the adjacency and checks, vertex by vertex: indices in range, no
/// triangle repeating a vertex, finite coordinates, every edge in at most two
/// faces walked in opposite directions (consistent orientation), and the
/// faces around each vertex forming a single fan (no non-manifold vertex).
/// Fails with kInvalidInput naming the first offending element. Without
/// `with_faces`, MeshTopology::faces is left empty. The fan checks use
/// `threads` when given; the result is the same.
Status build_topology(const TriangleMesh& mesh, MeshTopology* topology, bool with_faces = true,
                      const ParallelScope* threads = nullptr);

}  // namespace simplify_internal
}  // namespace lodbake
