// The mesh check that runs on every import: counts and problems of an
// indexed triangle mesh, computed exactly on its index structure (no
// geometry kernel needed, so it is fast and CGAL-free). Definitions follow
// ../shared/data/meshes/MANIFEST.md so that its counts can be compared.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

struct MeshCheckReport {
  uint64_t vertices = 0;
  uint64_t triangles = 0;
  // Over referenced, finite vertices only (unreferenced vertices must not
  // change results); both zero when there are none.
  Vec3f bbox_min{0, 0, 0};
  Vec3f bbox_max{0, 0, 0};
  uint64_t components = 0;             // faces connected through shared vertices
  uint64_t edges = 0;                  // distinct undirected edges
  uint64_t boundary_edges = 0;         // edges with exactly one face
  uint64_t boundary_loops = 0;         // closed chains of boundary edges
  uint64_t non_manifold_edges = 0;     // edges with more than two faces
  uint64_t non_manifold_vertices = 0;  // faces around the vertex form more than one fan
  uint64_t degenerate_triangles = 0;   // repeated index or zero area
  uint64_t duplicate_triangles = 0;    // same vertex set as an earlier triangle
  uint64_t unreferenced_vertices = 0;
  uint64_t inconsistent_orientation_edges = 0;  // 2-face edges walked twice the same way
  uint64_t non_finite_coordinates = 0;          // vertices with a NaN or infinite coordinate
  // Euler genus when the mesh is closed, manifold, consistently oriented and
  // one component; -1 otherwise.
  int64_t genus = -1;

  bool closed() const { return boundary_edges == 0; }
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0; }
  // True when any problem count above is non-zero (open boundaries and
  // several components are not problems).
  bool has_problems() const;
  // One line per problem, e.g. "3 non-manifold edges (more than two faces)".
  std::vector<std::string> problems() const;
};

MeshCheckReport check_mesh(const TriangleMesh& mesh);

}  // namespace lodbake
