#include "lib/scene/asset_build.h"

#include <utility>

#include "formats/container/container_layout.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/open_container.h"
#include "lib/meshio/mesh_import.h"
#include "lib/scene/scene_container.h"
#include "lib/scene/scene_pack.h"

namespace lodbake {
bool is_asset(const std::string& path, const Bytes& bytes) {
  if (starts_with_container_magic(bytes.data(), bytes.size())) {
    // The section table says it; no section needs decoding to know.
    Result<Container> container = read_container(bytes.data(), bytes.size());
    return container.is_ok() && has_scene(container.value());
  }
  ImportReport ignored;
  Result<MeshContent> content = prepare_mesh_content(path, bytes, &ignored);
  return content.is_ok() && (content.value().format == MeshFormat::kGltf ||
                             content.value().format == MeshFormat::kGlb);
}

Result<Scene> read_asset(const std::string& path, const Bytes& bytes,
                         const SceneResources& resources, ImportReport* report) {
  if (starts_with_container_magic(bytes.data(), bytes.size())) {
    LODBAKE_ASSIGN_OR_RETURN(OpenedContainer opened, open_container(bytes));
    report->format = "lodbake container (asset)";
    return scene_of_container(opened.decoded(), nullptr, report);
  }
  return read_scene_bytes(path, bytes, resources, report);
}

Result<AssetBuild> build_asset(const Scene& scene, MetaSection meta, const LoadOptions& load,
                               const MeshBuilder& build) {
  LODBAKE_ASSIGN_OR_RETURN(SceneContainerContents contents, scene_container_contents(scene));
  if (contents.topologies.empty())
    return invalid_input("the asset has no triangles (no mesh with a triangle primitive)");
  AssetBuild result;
  result.warnings = contents.warnings;
  std::vector<MeshSections> built;
  for (size_t g = 0; g < contents.topologies.size(); ++g) {
    const uint32_t mesh = contents.section.meshes[g].mesh;
    const std::string where = "mesh " + std::to_string(mesh);
    LoadedMesh loaded;
    loaded.mesh = contents.topologies[g].mesh;
    LoadOptions options = load;
    options.drop_unreferenced = true;
    options.per_vertex_attributes = false;
    Status prepared = prepare_mesh(options, &loaded);
    if (!prepared.is_ok()) return Status(prepared.kind(), where + ": " + prepared.message());
    Result<MeshSections> sections = build(mesh, loaded.mesh);
    if (!sections.is_ok())
      return Status(sections.status().kind(), where + ": " + sections.status().message());
    result.groups.push_back({{"group", g},
                             {"mesh", mesh},
                             {"triangles", contents.topologies[g].mesh.triangle_count()},
                             {"repaired", loaded.repair.has_value()},
                             {"report", sections.value().report}});
    built.push_back(std::move(sections).value());
  }
  meta.counts = built.front().counts;
  meta.extra["scene"] = scene_counts(scene);
  LODBAKE_ASSIGN_OR_RETURN(Bytes meta_bytes, encode_meta(meta));
  LODBAKE_ASSIGN_OR_RETURN(Bytes scne, encode_scne(contents.section));
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes)));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kScneTag, std::move(scne)));
  for (uint32_t g = 0; g < built.size(); ++g)
    for (auto& [tag, bytes] : built[g].sections)
      LODBAKE_RETURN_IF_ERROR(writer.add_known_section(tag, std::move(bytes), g));
  LODBAKE_ASSIGN_OR_RETURN(result.file, writer.finish());
  return result;
}

}  // namespace lodbake
