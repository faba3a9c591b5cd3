#include "lib/bake/fan_step.h"

#include <chrono>

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"

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

}  // namespace lodbake
