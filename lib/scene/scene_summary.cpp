#include "lib/scene/scene_summary.h"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "formats/scene/accessor_values.h"

namespace lodbake {
namespace {

const char* mode_name(PrimitiveMode mode) {
  static constexpr const char* kNames[] = {
      "POINTS", "LINES", "LINE_LOOP", "LINE_STRIP", "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return kNames[static_cast<int>(mode)];
}

const char* type_name(ElementType type) {
  static constexpr const char* kNames[] = {"SCALAR", "VEC2", "VEC3", "VEC4",
                                           "MAT2",   "MAT3", "MAT4"};
  return kNames[static_cast<int>(type)];
}

const char* component_name(ComponentType type) {
  switch (type) {
    case ComponentType::kByte:
      return "byte";
    case ComponentType::kUnsignedByte:
      return "unsigned byte";
    case ComponentType::kShort:
      return "short";
    case ComponentType::kUnsignedShort:
      return "unsigned short";
    case ComponentType::kUnsignedInt:
      return "unsigned int";
    case ComponentType::kFloat:
      return "float";
  }
  return "?";
}

// The attribute values of vertex `v` other than its position, with the
// semantics, so that vertices of primitives with different streams differ.
std::string wedge_key(const ScenePrimitive& primitive, uint32_t v) {
  std::string key;
  for (const SceneAttribute& a : primitive.attributes) {
    if (a.semantic == "POSITION") continue;
    key += a.semantic;
    key += '\0';
    const size_t size = a.data.element_size();
    if (v < a.data.count)
      key.append(reinterpret_cast<const char*>(a.data.bytes.data()) + size_t{v} * size, size);
  }
  return key;
}

void summarize_points(const SceneMesh& mesh, MeshSummary* out) {
  constexpr uint32_t kNone = UINT32_MAX;
  std::vector<uint32_t> first_primitive(mesh.point_count, kNone);
  std::vector<std::string> first_key(mesh.point_count);
  std::vector<uint8_t> seam(mesh.point_count, 0), border(mesh.point_count, 0);
  for (uint32_t p = 0; p < mesh.primitives.size(); ++p) {
    const std::vector<uint32_t>& points = mesh.point_of_vertex[p];
    for (uint32_t v = 0; v < points.size(); ++v) {
      const uint32_t point = points[v];
      std::string key = wedge_key(mesh.primitives[p], v);
      if (first_primitive[point] == kNone) {
        first_primitive[point] = p;
        first_key[point] = std::move(key);
        continue;
      }
      if (first_primitive[point] != p) border[point] = 1;
      if (first_key[point] != key) seam[point] = 1;
    }
  }
  out->points = mesh.point_count;
  for (uint32_t point = 0; point < mesh.point_count; ++point) {
    out->seam_points += seam[point];
    out->border_points += border[point];
  }
  for (uint32_t p = 0; p < mesh.primitives.size(); ++p) {
    std::vector<uint32_t> points = mesh.point_of_vertex[p];
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    uint64_t n = 0;
    for (uint32_t point : points)
      n += seam[point];
    out->primitives[p].seam_points = n;
  }
}

uint64_t array_size(const SceneJson& j) {
  return j.is_array() ? j.size() : 0;
}

}  // namespace

std::string describe_stream(const SceneAttribute& attribute) {
  std::string text = attribute.semantic + " " + type_name(attribute.data.type) + " " +
                     component_name(attribute.data.component_type);
  if (attribute.data.normalized) text += " normalized";
  return text;
}

SceneSummary summarize_scene(const Scene& scene) {
  SceneSummary s;
  s.nodes = scene.nodes.size();
  s.scenes = scene.scenes.size();
  s.materials = array_size(scene.materials);
  s.textures = array_size(scene.textures);
  s.images = scene.images.size();
  for (const SceneImage& image : scene.images)
    s.missing_images += image.missing ? 1 : 0;
  s.skins = array_size(scene.skins);
  s.animations = array_size(scene.animations);
  s.cameras = array_size(scene.cameras);
  s.extensions_used = scene.extensions_used;
  s.meshes.resize(scene.meshes.size());
  for (uint32_t n = 0; n < scene.nodes.size(); ++n) {
    const SceneNode& node = scene.nodes[n];
    if (node.mesh < 0 || static_cast<size_t>(node.mesh) >= s.meshes.size()) continue;
    s.meshes[node.mesh].nodes.push_back(n);
    if (node.skin >= 0) s.meshes[node.mesh].skinned = true;
  }
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const SceneMesh& mesh = scene.meshes[m];
    MeshSummary& out = s.meshes[m];
    out.name = mesh.name;
    for (const ScenePrimitive& primitive : mesh.primitives) {
      PrimitiveSummary p;
      p.mode = mode_name(primitive.mode);
      p.vertices = primitive.vertex_count();
      p.triangles = primitive_triangles(primitive).size();
      p.indexed = primitive.indices.has_value();
      for (const SceneAttribute& a : primitive.attributes)
        p.attributes.push_back(describe_stream(a));
      p.targets = primitive.targets.size();
      p.material = primitive.material;
      if (primitive.material >= 0 && scene.materials.is_array() &&
          static_cast<size_t>(primitive.material) < scene.materials.size()) {
        const SceneJson& material = scene.materials[primitive.material];
        if (material.is_object() && material.contains("name") && material["name"].is_string())
          p.material_name = material["name"].get<std::string>();
      }
      out.triangles += p.triangles;
      out.primitives.push_back(std::move(p));
    }
    if (mesh.point_of_vertex.size() == mesh.primitives.size()) summarize_points(mesh, &out);
    s.primitives += out.primitives.size();
    s.triangles += out.triangles;
    s.instanced_triangles += out.triangles * out.nodes.size();
  }
  return s;
}

nlohmann::json to_json(const SceneSummary& s) {
  nlohmann::json meshes = nlohmann::json::array();
  for (const MeshSummary& m : s.meshes) {
    nlohmann::json primitives = nlohmann::json::array();
    for (const PrimitiveSummary& p : m.primitives) {
      primitives.push_back(
          {{"mode", p.mode},
           {"vertices", p.vertices},
           {"triangles", p.triangles},
           {"indexed", p.indexed},
           {"attributes", p.attributes},
           {"morph_targets", p.targets},
           {"material", p.material < 0 ? nlohmann::json(nullptr) : nlohmann::json(p.material)},
           {"material_name", p.material_name},
           {"seam_points", p.seam_points}});
    }
    meshes.push_back({{"name", m.name},
                      {"nodes", m.nodes},
                      {"instances", m.nodes.size()},
                      {"skinned", m.skinned},
                      {"points", m.points},
                      {"triangles", m.triangles},
                      {"seam_points", m.seam_points},
                      {"border_points", m.border_points},
                      {"primitives", primitives}});
  }
  return {{"nodes", s.nodes},
          {"scenes", s.scenes},
          {"meshes", meshes},
          {"primitives", s.primitives},
          {"materials", s.materials},
          {"textures", s.textures},
          {"images", s.images},
          {"missing_images", s.missing_images},
          {"skins", s.skins},
          {"animations", s.animations},
          {"cameras", s.cameras},
          {"triangles", s.triangles},
          {"instanced_triangles", s.instanced_triangles},
          {"extensions_used", s.extensions_used}};
}

}  // namespace lodbake
