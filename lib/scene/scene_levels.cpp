#include "lib/scene/scene_levels.h"

#include <new>
#include <string>
#include <utility>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/scene/accessor_values.h"
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

namespace {

// One mesh's check (check_scene_levels); empty when it passes.
std::string check_mesh_levels(const Container& container, const SceneMesh& mesh,
                              const SceneMeshGroup& m) {
  const Section* base = container.find(kBaseTag, m.group);
  const Section* vspl = container.find(kVsplTag, m.group);
  const Section* wedg = container.find(kWedgTag, m.group);
  Result<ProgressiveMesh> pm =
      decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size);
  if (!pm.is_ok()) return pm.status().message();
  Result<PmWedges> wedges = decode_wedg(wedg->data, wedg->size);
  if (!wedges.is_ok()) return wedges.status().message();
  Result<WedgeRefiner> refiner = WedgeRefiner::create(pm.value(), wedges.value());
  if (!refiner.is_ok()) return refiner.status().message();
  WedgeRefiner& r = refiner.value();
  if (Status s = r.refine_to(pm.value().full_vertex_count()); !s.is_ok()) return s.message();
  const TriangleMesh& full = r.mesh();
  for (size_t f = 0; f < full.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (wedges.value().wedge_home[r.corners()[f][k]] != full.triangles[f][k])
        return "fully refined, face " + std::to_string(f) + " uses a wedge of another vertex";
  Result<std::vector<ScenePrimitive>> finest =
      primitives_at_level(mesh, full, r.corners(), wedges.value());
  if (!finest.is_ok()) return "fully refined: " + finest.status().message();
  std::vector<uint64_t> triangles;
  for (const ScenePrimitive& prim : mesh.primitives)
    if (prim.mode == PrimitiveMode::kTriangles || prim.mode == PrimitiveMode::kTriangleStrip ||
        prim.mode == PrimitiveMode::kTriangleFan)
      triangles.push_back(primitive_triangles(prim).size());
  std::vector<uint64_t> refined;
  for (const ScenePrimitive& prim : finest.value())
    if (prim.mode == PrimitiveMode::kTriangles) refined.push_back(primitive_triangles(prim).size());
  if (refined != triangles)
    return "fully refined, the primitives' triangle counts are not the asset's";
  if (Status s = r.refine_to(pm.value().base.vertex_count()); !s.is_ok())
    return "coarsening back: " + s.message();
  if (r.corners() != wedges.value().base) return "coarsening back does not give the base wedges";
  Result<std::vector<ScenePrimitive>> coarsest =
      primitives_at_level(mesh, r.mesh(), r.corners(), wedges.value());
  if (!coarsest.is_ok()) return "the base: " + coarsest.status().message();
  return "";
}

}  // namespace

std::vector<std::string> check_scene_levels(const Container& container, const Scene& scene) {
  std::vector<std::string> findings;
  const Section* scne = container.find(kScneTag, 0);
  if (scne == nullptr) return findings;
  Result<SceneSection> map = decode_scne(scne->data, scne->size);
  if (!map.is_ok()) return findings;  // SCNE's own finding says why
  for (const SceneMeshGroup& m : map.value().meshes) {
    if (m.mesh >= scene.meshes.size() || container.find(kWedgTag, m.group) == nullptr ||
        container.find(kBaseTag, m.group) == nullptr ||
        container.find(kVsplTag, m.group) == nullptr)
      continue;
    std::string problem;
    try {
      problem = check_mesh_levels(container, scene.meshes[m.mesh], m);
    } catch (const std::bad_alloc&) {
      problem = "out of memory replaying the wedges";
    }
    if (!problem.empty())
      findings.push_back("mesh " + std::to_string(m.mesh) + " (group " + std::to_string(m.group) +
                         "): " + problem);
  }
  return findings;
}

}  // namespace lodbake
