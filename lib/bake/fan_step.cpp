#include "lib/bake/fan_step.h"

#include <chrono>

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/wedg.h"
#include "lib/fanmerge/fan_wedges.h"

namespace lodbake {

Result<FanBuilt> build_fan(const FanBuildOptions& options, const TriangleMesh& mesh) {
  FanBuilt out;
  const auto start = std::chrono::steady_clock::now();
  LODBAKE_ASSIGN_OR_RETURN(out.result, build_fan_hierarchy(mesh, options));
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.stats = fanh_stats(out.result.hierarchy);
  out.counts = {{"vertices", mesh.vertex_count()},
                {"triangles", mesh.triangle_count()},
                {"fan_internal_nodes", out.result.hierarchy.internal_count()},
                {"coarsest_vertices", out.result.stats.output_vertices},
                {"coarsest_triangles", out.result.stats.output_triangles}};
  LODBAKE_ASSIGN_OR_RETURN(out.base, encode_base(mesh, BaseEncodeOptions()));
  LODBAKE_ASSIGN_OR_RETURN(out.fanh, encode_fanh(out.result.hierarchy));
  return out;
}

MetaSection fan_meta(const FanStepOptions& request) {
  const FanBuildOptions& o = request.options;
  MetaSection meta = make_meta("lodbake-fan");
  meta.options = {{"degree_weight", o.degree_weight},
                  {"boundary_weight", o.boundary_weight},
                  {"max_normal_change_degrees", o.max_normal_change_degrees},
                  {"repair", request.repair}};
  if (o.target_vertices) meta.options["vertices"] = *o.target_vertices;
  if (o.target_ratio) meta.options["ratio"] = *o.target_ratio;
  if (o.max_error) meta.options["error"] = *o.max_error;
  return meta;
}

MeshSections fan_mesh_sections(FanBuilt&& b) {
  MeshSections out;
  out.sections.emplace_back(kBaseTag, std::move(b.base));
  out.sections.emplace_back(kFanhTag, std::move(b.fanh));
  out.counts = b.counts;
  out.report = b.counts;
  return out;
}

PmWedges fan_input_wedges(const MeshCornerWedges& corners) {
  PmWedges out;
  out.wedge_primitive = corners.wedge_primitive;
  out.wedge_vertex = corners.wedge_vertex;
  out.wedge_home = corners.wedge_point;
  out.base = corners.corner_wedge;
  out.moved_offset.assign(1, 0);
  return out;
}

Result<std::map<uint32_t, MeshCornerWedges>> fan_asset_corners(const FanStepOptions& request,
                                                               const Scene& scene) {
  LoadOptions load;
  load.repair = request.repair;
  load.strict = request.strict;
  LODBAKE_ASSIGN_OR_RETURN(std::vector<MeshCornerWedges> all, scene_corner_wedges(scene, load));
  std::map<uint32_t, MeshCornerWedges> corners;
  for (MeshCornerWedges& c : all)
    corners.emplace(c.mesh, std::move(c));
  return corners;
}

Result<MeshSections> fan_asset_sections(FanBuilt&& built,
                                        const std::map<uint32_t, MeshCornerWedges>& corners,
                                        uint32_t scene_mesh, const TriangleMesh& mesh) {
  auto found = corners.find(scene_mesh);
  if (found == corners.end() || found->second.topology.positions != mesh.positions ||
      found->second.topology.triangles != mesh.triangles)
    return runtime_error("the corners read from the scene are not over the mesh built");
  const PmWedges wedges = fan_input_wedges(found->second);
  // What replay and --validate will ask of the file, asked once here so
  // that a container the tool writes always loads.
  Result<FanWedges> fronts = FanWedges::create(mesh, built.result.hierarchy, wedges);
  if (!fronts.is_ok()) return runtime_error("the fan fronts' wedges: " + fronts.status().message());
  LODBAKE_ASSIGN_OR_RETURN(Bytes wedg, encode_wedg(wedges));
  MeshSections out = fan_mesh_sections(std::move(built));
  out.sections.emplace_back(kWedgTag, std::move(wedg));
  out.report["wedges"] = wedges.wedge_count();
  return out;
}

}  // namespace lodbake
