#include "lib/bake/simplify_step.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/vspl.h"
#include "formats/sections/wedg.h"
#include "lib/scene/scene_summary.h"
#include "lib/simplify/pm_replay.h"

namespace lodbake {

nlohmann::json pm_meta_options(const SimplifyStepOptions& request) {
  nlohmann::json options = {
      {"placement", request.placement},
      {"boundary_weight", request.options.boundary_weight},
      {"lock_border", request.options.lock_border},
      {"max_normal_change_degrees", request.options.max_normal_change_degrees},
      {"permissive", request.options.permissive},
      {"repair", request.repair},
      {"quantize_bits", request.quantize_bits == 0 ? nlohmann::json(nullptr)
                                                   : nlohmann::json(request.quantize_bits)}};
  // Only when on (the factor only when not the default), so that files made
  // without them keep their bytes.
  if (request.options.height_guard) options["height_guard"] = true;
  if (request.options.height_guard &&
      request.options.height_guard_factor != kDefaultHeightGuardFactor)
    options["height_guard_factor"] = request.options.height_guard_factor;
  if (request.options.target_ratio) options["ratio"] = *request.options.target_ratio;
  if (request.options.target_triangles) options["triangles"] = *request.options.target_triangles;
  if (request.options.max_error) options["error"] = *request.options.max_error;
  // Only when not the default, so that files made before the option keep
  // their bytes; null: seams never move.
  if (request.options.seam_release != kDefaultSeamRelease)
    options["seam_release"] =
        request.options.seam_release && std::isfinite(*request.options.seam_release)
            ? nlohmann::json(*request.options.seam_release)
            : nlohmann::json(nullptr);
  return options;
}

Result<PmSections> pm_sections(const SimplifyStepOptions& request, const ProgressiveMesh& pm) {
  PmSections out;
  out.counts = {{"vertices", pm.base.vertex_count()},
                {"triangles", pm.base.triangle_count()},
                {"splits", pm.splits.size()},
                {"full_vertices", pm.full_vertex_count()},
                {"full_triangles", full_triangle_count(pm.base.triangle_count(), pm.splits)}};
  BaseEncodeOptions base_encoding;
  VsplEncodeOptions vspl_encoding;
  base_encoding.quantize = vspl_encoding.quantize = request.quantize_bits != 0;
  if (request.quantize_bits != 0) base_encoding.bits = vspl_encoding.bits = request.quantize_bits;
  LODBAKE_ASSIGN_OR_RETURN(out.base, encode_base(pm.base, base_encoding));
  LODBAKE_ASSIGN_OR_RETURN(out.vspl, encode_vspl(pm, vspl_encoding));
  return out;
}

Result<Bytes> pm_container_bytes(const SimplifyStepOptions& request, const MetaInput& input,
                                 const ProgressiveMesh& pm,
                                 std::map<std::string, uint64_t>* sizes) {
  MetaSection meta = make_meta("lodbake-simplify");
  meta.options = pm_meta_options(request);
  meta.input = input;
  LODBAKE_ASSIGN_OR_RETURN(PmSections sections, pm_sections(request, pm));
  meta.counts = sections.counts;
  LODBAKE_ASSIGN_OR_RETURN(Bytes meta_bytes, encode_meta(meta));
  if (sizes != nullptr)
    *sizes = {{"META", meta_bytes.size()},
              {"BASE", sections.base.size()},
              {"VSPL", sections.vspl.size()}};
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes)));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kBaseTag, std::move(sections.base)));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kVsplTag, std::move(sections.vspl)));
  return writer.finish();
}

Result<std::map<uint32_t, MeshPm>> asset_progressive_meshes(const SimplifyStepOptions& request,
                                                            const Scene& scene) {
  SceneLodOptions options;
  options.simplify = request.options;
  options.load.repair = request.repair;
  options.load.strict = request.strict;
  options.weights = request.weights;
  const uint64_t triangles = summarize_scene(scene).triangles;
  if (request.options.target_triangles && triangles > 0) {
    const double ratio = std::min(1.0, static_cast<double>(*request.options.target_triangles) /
                                           static_cast<double>(triangles));
    if (!options.simplify.target_ratio || ratio < *options.simplify.target_ratio)
      options.simplify.target_ratio = ratio;
  }
  options.simplify.target_triangles.reset();
  LODBAKE_ASSIGN_OR_RETURN(std::vector<MeshPm> all, scene_progressive_meshes(scene, options));
  std::map<uint32_t, MeshPm> pms;
  for (MeshPm& m : all)
    pms.emplace(m.mesh, std::move(m));
  return pms;
}

Result<MeshSections> asset_pm_sections(const SimplifyStepOptions& request, const MeshPm& m) {
  LODBAKE_ASSIGN_OR_RETURN(PmSections pm, pm_sections(request, m.pm));
  LODBAKE_ASSIGN_OR_RETURN(Bytes wedg, encode_wedg(m.wedges));
  MeshSections out;
  out.sections.emplace_back(kBaseTag, std::move(pm.base));
  out.sections.emplace_back(kVsplTag, std::move(pm.vspl));
  out.sections.emplace_back(kWedgTag, std::move(wedg));
  out.counts = pm.counts;
  out.report = pm.counts;
  out.report["wedges"] = m.wedges.wedge_count();
  out.report["target_reached"] = !m.blocked.has_value();
  return out;
}

}  // namespace lodbake
