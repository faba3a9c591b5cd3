#include "lib/ingest/container_mesh.h"

#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/scne.h"
#include "formats/sections/vspl.h"
#include "lib/simplify/pm_replay.h"

namespace lodbake {

std::optional<MetaInput> container_meta_input(const OpenedContainer& file) {
  const Section* meta = file.find(kMetaTag);
  if (meta == nullptr) return std::nullopt;
  Result<MetaSection> decoded = decode_meta(meta->data, meta->size);
  if (!decoded.is_ok()) return std::nullopt;
  return decoded.value().input;
}

Result<ContainerMesh> container_input_mesh(const OpenedContainer& file) {
  try {
    ContainerMesh out;
    out.input = container_meta_input(file);
    if (const Section* scne = file.find(kScneTag, 0)) {
      Result<SceneSection> scene = decode_scne(scne->data, scne->size);
      if (!scene.is_ok()) return scene.status();
      out.asset_meshes = static_cast<uint32_t>(scene.value().meshes.size());
    }
    for (uint32_t group = 0; group < file.group_count(); ++group) {
      const Section* base = file.find(kBaseTag, group);
      const Section* vspl = file.find(kVsplTag, group);
      if (base == nullptr || vspl == nullptr) continue;
      LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh pm, decode_progressive_mesh(base->data, base->size,
                                                                           vspl->data, vspl->size));
      LODBAKE_ASSIGN_OR_RETURN(TriangleMesh full, mesh_at_lod(pm, pm.full_vertex_count()));
      LODBAKE_ASSIGN_OR_RETURN(out.mesh, map_to_input(pm, full));
      out.source = "progressive mesh";
      out.group = group;
      return out;
    }
    for (uint32_t group = 0; group < file.group_count(); ++group) {
      const Section* base = file.find(kBaseTag, group);
      if (base == nullptr || file.find(kVhieTag, group) != nullptr) continue;
      LODBAKE_ASSIGN_OR_RETURN(out.mesh, decode_base(base->data, base->size));
      out.source = "base mesh";
      out.group = group;
      return out;
    }
    return container_error(ContainerError::kMissingSection,
                           "the container holds no input mesh: it needs BASE + VSPL "
                           "(lodbake-simplify --pm) or a BASE that is the input (lodbake-pack, "
                           "lodbake-fan, lodbake-strips --strips-only)");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory rebuilding the container's mesh");
  }
}

}  // namespace lodbake
