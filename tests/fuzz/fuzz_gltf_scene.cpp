// Fuzz target: read_gltf_scene (glTF JSON and GLB, memory only: any external
// file is refused). On success every stream must hold count x element bytes,
// every index and point id must be in range, every accessor reference in
// the carried skins and animations must name a Scene accessor, and reading
// the same bytes again must give the same scene (determinism).
#include <cstddef>
#include <cstdint>

#include "lib/scene/scene_io.h"
#include "tests/fuzz/mesh_invariants.h"

namespace {

using namespace lodbake;

void check_stream(const AccessorData& a) {
  fuzz::require(a.bytes.size() == uint64_t{a.count} * a.element_size());
}

void check_reference(const SceneJson& object, const char* key, size_t limit) {
  if (!object.is_object() || !object.contains(key)) return;
  fuzz::require(object[key].is_number_unsigned() && object[key].get<uint64_t>() < limit);
}

void check_scene(const Scene& scene) {
  for (const AccessorData& a : scene.accessors)
    check_stream(a);
  for (const SceneMesh& mesh : scene.meshes) {
    fuzz::require(mesh.point_of_vertex.size() == mesh.primitives.size());
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const ScenePrimitive& prim = mesh.primitives[p];
      fuzz::require(!prim.attributes.empty());
      const uint32_t vertices = prim.attributes.front().data.count;
      for (size_t i = 0; i < prim.attributes.size(); ++i) {
        check_stream(prim.attributes[i].data);
        fuzz::require(prim.attributes[i].data.count == vertices);
        if (i > 0) fuzz::require(prim.attributes[i - 1].semantic < prim.attributes[i].semantic);
      }
      for (const auto& target : prim.targets) {
        for (const SceneAttribute& a : target) {
          check_stream(a.data);
          fuzz::require(a.data.count == vertices);
        }
      }
      if (prim.indices) {
        for (uint32_t i : *prim.indices)
          fuzz::require(i < vertices);
      }
      for (uint32_t point : mesh.point_of_vertex[p])
        fuzz::require(point < mesh.point_count);
    }
  }
  for (const SceneNode& node : scene.nodes) {
    fuzz::require(node.mesh < static_cast<int64_t>(scene.meshes.size()));
    for (uint32_t c : node.children)
      fuzz::require(c < scene.nodes.size());
  }
  if (scene.skins.is_array()) {
    for (const SceneJson& skin : scene.skins)
      check_reference(skin, "inverseBindMatrices", scene.accessors.size());
  }
  if (scene.animations.is_array()) {
    for (const SceneJson& animation : scene.animations) {
      if (!animation.contains("samplers")) continue;
      for (const SceneJson& sampler : animation["samplers"]) {
        check_reference(sampler, "input", scene.accessors.size());
        check_reference(sampler, "output", scene.accessors.size());
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const SceneResources memory_only;
  ImportReport report;
  auto scene = read_gltf_scene(data, size, memory_only, &report);
  if (!scene.is_ok()) {
    fuzz::check_error(scene.status());
    return 0;
  }
  check_scene(scene.value());
  ImportReport again_report;
  auto again = read_gltf_scene(data, size, memory_only, &again_report);
  fuzz::require(again.is_ok());
  fuzz::require(again.value() == scene.value());
  fuzz::require(again_report.warnings == report.warnings);
  return 0;
}
