// A scene mesh as the algorithms see it: one welded topology over all its
// triangle primitives (positions shared along the borders between
// materials, so that nothing built on it opens a crack there), with the way
// back to the primitives.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/scene/scene.h"

namespace lodbake {

struct MeshTopology {
  // positions: the mesh's points (SceneMesh::point_of_vertex) in point
  // order, as float values of POSITION; triangles: every triangle of every
  // triangle primitive (primitive_triangles()), primitive by primitive.
  TriangleMesh mesh;
  std::vector<uint32_t> primitive_of_triangle;    // per triangle of `mesh`
  std::vector<uint64_t> triangles_per_primitive;  // per primitive (0 for points and lines)
};

// Needs `mesh.point_of_vertex` filled (weld_mesh_points()).
MeshTopology mesh_topology(const SceneMesh& mesh);

// Triangles of all triangle primitives of the mesh.
uint64_t mesh_triangle_count(const SceneMesh& mesh);

}  // namespace lodbake
