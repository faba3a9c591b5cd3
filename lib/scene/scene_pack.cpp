#include "lib/scene/scene_pack.h"

#include <utility>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "lib/scene/scene_container.h"
#include "lib/scene/scene_summary.h"

namespace lodbake {

nlohmann::json scene_counts(const Scene& scene) {
  const SceneSummary s = summarize_scene(scene);
  return {{"nodes", s.nodes},         {"meshes", s.meshes.size()},  {"primitives", s.primitives},
          {"materials", s.materials}, {"textures", s.textures},     {"images", s.images},
          {"skins", s.skins},         {"animations", s.animations}, {"triangles", s.triangles}};
}

Result<ScenePackResult> pack_scene(const Scene& scene, MetaSection meta,
                                   const BaseEncodeOptions& encoding) {
  Result<SceneContainerContents> contents = scene_container_contents(scene);
  if (!contents.is_ok()) return contents.status();
  if (contents.value().topologies.empty())
    return invalid_input("the asset has no triangles (no mesh with a triangle primitive)");
  ScenePackResult result;
  result.warnings = contents.value().warnings;
  const TriangleMesh& first = contents.value().topologies.front().mesh;
  meta.counts = {{"vertices", first.vertex_count()}, {"triangles", first.triangle_count()}};
  meta.extra["scene"] = scene_counts(scene);
  Result<Bytes> meta_bytes = encode_meta(meta);
  if (!meta_bytes.is_ok()) return meta_bytes.status();
  Result<Bytes> scne = encode_scne(contents.value().section);
  if (!scne.is_ok()) return scne.status();
  result.meta_bytes = meta_bytes.value().size();
  result.scne_bytes = scne.value().size();
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes).value()));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kScneTag, std::move(scne).value()));
  const std::vector<MeshTopology>& topologies = contents.value().topologies;
  for (uint32_t g = 0; g < topologies.size(); ++g) {
    Result<Bytes> base = encode_base(topologies[g].mesh, encoding);
    if (!base.is_ok()) return base.status();
    result.base_bytes.push_back(base.value().size());
    result.base_vertices.push_back(topologies[g].mesh.vertex_count());
    result.base_triangles.push_back(topologies[g].mesh.triangle_count());
    LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kBaseTag, std::move(base).value(), g));
  }
  Result<Bytes> file = writer.finish();
  if (!file.is_ok()) return file.status();
  result.file = std::move(file).value();
  return result;
}

}  // namespace lodbake
