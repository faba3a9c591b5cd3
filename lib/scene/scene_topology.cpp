#include "lib/scene/scene_topology.h"

#include "formats/scene/accessor_values.h"

namespace lodbake {

MeshTopology mesh_topology(const SceneMesh& mesh) {
  MeshTopology topology;
  topology.mesh.positions.resize(mesh.point_count);
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const ScenePrimitive& primitive = mesh.primitives[p];
    const SceneAttribute* position = primitive.find("POSITION");
    const std::vector<uint32_t>& points = mesh.point_of_vertex[p];
    if (position != nullptr && position->data.components() == 3) {
      for (size_t v = 0; v < points.size() && v < position->data.count; ++v)
        for (uint32_t c = 0; c < 3; ++c)
          topology.mesh.positions[points[v]][c] = float_value(position->data, v, c);
    }
    const std::vector<std::array<uint32_t, 3>> triangles = primitive_triangles(primitive);
    topology.triangles_per_primitive.push_back(triangles.size());
    for (const std::array<uint32_t, 3>& t : triangles) {
      topology.mesh.triangles.push_back({points[t[0]], points[t[1]], points[t[2]]});
      topology.primitive_of_triangle.push_back(static_cast<uint32_t>(p));
    }
  }
  return topology;
}

uint64_t mesh_triangle_count(const SceneMesh& mesh) {
  uint64_t n = 0;
  for (const ScenePrimitive& primitive : mesh.primitives)
    n += primitive_triangles(primitive).size();
  return n;
}

}  // namespace lodbake
