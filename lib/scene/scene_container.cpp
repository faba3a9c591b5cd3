#include "lib/scene/scene_container.h"

#include <algorithm>
#include <utility>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_points.h"

namespace lodbake {

Result<SceneContainerContents> scene_container_contents(const Scene& scene) {
  SceneContainerContents contents;
  SceneWriteReport written;
  Result<Bytes> glb = write_scene_glb(scene, &written);
  if (!glb.is_ok()) return glb.status();
  contents.section.glb = std::move(glb).value();
  contents.warnings = std::move(written.warnings);
  // Only when some image has a name to keep, so the map stays small.
  if (std::any_of(scene.images.begin(), scene.images.end(),
                  [](const SceneImage& image) { return !image.uri.empty(); }))
    for (const SceneImage& image : scene.images)
      contents.section.image_uris.push_back(image.uri);
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    MeshTopology topology = mesh_topology(scene.meshes[m]);
    if (topology.mesh.triangles.empty()) continue;
    SceneMeshGroup entry;
    entry.mesh = m;
    entry.group = static_cast<uint32_t>(contents.topologies.size());
    entry.triangles = topology.triangles_per_primitive;
    contents.section.meshes.push_back(std::move(entry));
    contents.topologies.push_back(std::move(topology));
  }
  return contents;
}

bool has_scene(const Container& container) {
  return container.find(kScneTag, 0) != nullptr;
}

Result<Scene> scene_of_container(const Container& container, SceneSection* map,
                                 ImportReport* report) {
  const Section* scne = container.find(kScneTag, 0);
  if (scne == nullptr) return invalid_input("the container holds no SCNE section (no asset)");
  Result<SceneSection> section = decode_scne(scne->data, scne->size);
  if (!section.is_ok()) return section.status();
  ImportReport ignored;
  Result<Scene> scene = read_gltf_scene(section.value().glb.data(), section.value().glb.size(),
                                        SceneResources{}, report != nullptr ? report : &ignored);
  if (!scene.is_ok()) return malformed_section(kScneTag, scene.status().message());
  for (const SceneMeshGroup& m : section.value().meshes) {
    if (m.mesh >= scene.value().meshes.size())
      return malformed_section(kScneTag, "the map names mesh " + std::to_string(m.mesh) +
                                             ", the scene has " +
                                             std::to_string(scene.value().meshes.size()));
  }
  const std::vector<std::string>& uris = section.value().image_uris;
  for (size_t i = 0; i < uris.size() && i < scene.value().images.size(); ++i)
    scene.value().images[i].uri = uris[i];
  for (SceneMesh& mesh : scene.value().meshes)
    if (mesh.point_of_vertex.size() != mesh.primitives.size()) weld_mesh_points(&mesh);
  if (map != nullptr) *map = std::move(section).value();
  return scene;
}

}  // namespace lodbake
