// TriangleMesh -> Scene. The vertex splitting is split_corner_attributes()'s
// (lib/meshio), so a mesh file read as a scene and read as a TriangleMesh
// then written as PLY or GLB duplicate the same vertices.
#include "lib/scene/scene_from_mesh.h"

#include <algorithm>
#include <cstring>

#include "lib/meshio/corner_split.h"
#include "lib/meshio/writer_support.h"

namespace lodbake {
namespace {

constexpr ElementType kFloatTypes[] = {ElementType::kScalar, ElementType::kVec2, ElementType::kVec3,
                                       ElementType::kVec4};

SceneAttribute float_attribute(const char* semantic, const float* values, uint32_t count,
                               uint32_t components) {
  SceneAttribute a;
  a.semantic = semantic;
  a.data = float_accessor(values, count, components);
  return a;
}

// `stream`'s elements in the order of `source` (output vertex -> input vertex).
SceneAttribute gather(const SceneAttribute& stream, const std::vector<uint32_t>& source) {
  SceneAttribute out;
  out.semantic = stream.semantic;
  out.data = stream.data;
  const size_t element = stream.data.element_size();
  out.data.count = static_cast<uint32_t>(source.size());
  out.data.bytes.resize(source.size() * element);
  for (size_t i = 0; i < source.size(); ++i) {
    std::memcpy(out.data.bytes.data() + i * element,
                stream.data.bytes.data() + static_cast<size_t>(source[i]) * element, element);
  }
  return out;
}

}  // namespace

AccessorData float_accessor(const float* values, uint32_t count, uint32_t components) {
  AccessorData data;
  data.component_type = ComponentType::kFloat;
  data.type = kFloatTypes[std::clamp<uint32_t>(components, 1, 4) - 1];
  data.count = count;
  data.bytes.resize(size_t{count} * components * sizeof(float));
  if (!data.bytes.empty()) std::memcpy(data.bytes.data(), values, data.bytes.size());
  return data;
}

Result<ScenePrimitive> primitive_from_mesh(const TriangleMesh& mesh,
                                           const std::vector<SceneAttribute>& vertex_streams) {
  LODBAKE_RETURN_IF_ERROR(check_writable(mesh));
  for (const SceneAttribute& s : vertex_streams) {
    if (s.data.count != mesh.positions.size() ||
        s.data.bytes.size() != size_t{s.data.count} * s.data.element_size()) {
      return invalid_input(s.semantic + " has " + std::to_string(s.data.count) + " values for " +
                           std::to_string(mesh.positions.size()) + " vertices");
    }
  }
  std::vector<uint32_t> source;
  const TriangleMesh split = split_corner_attributes(mesh, &source);
  const auto count = static_cast<uint32_t>(split.positions.size());

  ScenePrimitive primitive;
  primitive.mode = PrimitiveMode::kTriangles;
  std::vector<uint32_t> indices;
  indices.reserve(split.triangles.size() * 3);
  for (const Triangle& t : split.triangles)
    indices.insert(indices.end(), t.begin(), t.end());
  primitive.indices = std::move(indices);

  primitive.attributes.push_back(float_attribute(
      "POSITION", split.positions.empty() ? nullptr : split.positions[0].data(), count, 3));
  if (split.normals.present())
    primitive.attributes.push_back(
        float_attribute("NORMAL", split.normals.values.data(), count, 3));
  if (split.texcoords.present()) {
    // TriangleMesh texture coordinates have OBJ's bottom-left origin.
    std::vector<float> uv = split.texcoords.values;
    for (size_t i = 1; i < uv.size(); i += 2)
      uv[i] = 1.0f - uv[i];
    primitive.attributes.push_back(float_attribute("TEXCOORD_0", uv.data(), count, 2));
  }
  for (const SceneAttribute& s : vertex_streams)
    primitive.attributes.push_back(gather(s, source));
  std::sort(
      primitive.attributes.begin(), primitive.attributes.end(),
      [](const SceneAttribute& a, const SceneAttribute& b) { return a.semantic < b.semantic; });
  return primitive;
}

Scene scene_of_mesh(std::string name, std::vector<ScenePrimitive> primitives) {
  Scene scene;
  SceneMesh mesh;
  mesh.name = std::move(name);
  mesh.primitives = std::move(primitives);
  scene.meshes.push_back(std::move(mesh));
  SceneNode node;
  node.mesh = 0;
  scene.nodes.push_back(std::move(node));
  SceneRoots roots;
  roots.nodes.push_back(0);
  scene.scenes.push_back(std::move(roots));
  scene.default_scene = 0;
  return scene;
}

Result<Scene> scene_from_mesh(const TriangleMesh& mesh, const std::string& name) {
  LODBAKE_ASSIGN_OR_RETURN(ScenePrimitive primitive, primitive_from_mesh(mesh));
  std::vector<ScenePrimitive> primitives;
  primitives.push_back(std::move(primitive));
  return scene_of_mesh(name, std::move(primitives));
}

}  // namespace lodbake
