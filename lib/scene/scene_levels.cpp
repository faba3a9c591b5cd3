#include "lib/scene/scene_levels.h"

#include <string>
#include <utility>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/sections/scne.h"
#include "formats/sections/vspl.h"
#include "formats/sections/wedg.h"
#include "lib/scene/scene_lods.h"
#include "lib/simplify/wedge_replay.h"

namespace lodbake {

Result<Scene> scene_at_level(const Container& container, const Scene& scene,
                             const LevelChooser& choose) {
  const Section* scne = container.find(kScneTag, 0);
  if (scne == nullptr)
    return container_error(ContainerError::kMissingSection, "no SCNE section holds an asset");
  LODBAKE_ASSIGN_OR_RETURN(SceneSection map, decode_scne(scne->data, scne->size));
  Scene out = scene;
  for (const SceneMeshGroup& m : map.meshes) {
    if (m.mesh >= scene.meshes.size())
      return malformed_section(kScneTag, "the map names mesh " + std::to_string(m.mesh));
    const std::string where =
        "mesh " + std::to_string(m.mesh) + " (group " + std::to_string(m.group) + ")";
    const Section* base = container.find(kBaseTag, m.group);
    const Section* vspl = container.find(kVsplTag, m.group);
    const Section* wedg = container.find(kWedgTag, m.group);
    if (base == nullptr || vspl == nullptr || wedg == nullptr)
      return container_error(ContainerError::kMissingSection,
                             where +
                                 " has no progressive mesh with wedges (BASE, VSPL and "
                                 "WEDG: lodbake-simplify --pm writes them)");
    LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh pm, decode_progressive_mesh(base->data, base->size,
                                                                         vspl->data, vspl->size));
    LODBAKE_ASSIGN_OR_RETURN(PmWedges wedges, decode_wedg(wedg->data, wedg->size));
    Result<WedgeRefiner> refiner = WedgeRefiner::create(pm, wedges);
    if (!refiner.is_ok())
      return malformed_section(kWedgTag, where + ": " + refiner.status().message());
    if (Status refined = refiner.value().refine_to(choose(pm)); !refined.is_ok())
      return malformed_section(kWedgTag, where + ": " + refined.message());
    Result<std::vector<ScenePrimitive>> primitives = primitives_at_level(
        scene.meshes[m.mesh], refiner.value().mesh(), refiner.value().corners(), wedges);
    if (!primitives.is_ok())
      return malformed_section(kWedgTag, where + ": " + primitives.status().message());
    SceneMesh& mesh = out.meshes[m.mesh];
    mesh.primitives = std::move(primitives).value();
    mesh.point_of_vertex.clear();
    mesh.point_count = 0;
  }
  return out;
}

}  // namespace lodbake
