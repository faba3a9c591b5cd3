#include "lib/bake/strips_step.h"

#include <chrono>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/sections/vspl.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "lib/strips/sets_build.h"

namespace lodbake {
namespace {

// The paper's in-memory SETS sizes (Table 2), for the report.
struct PaperFigure {
  const char* model;
  uint64_t triangles;
  double megabytes;
};
constexpr PaperFigure kPaperFigures[] = {
    {"Cow", 5804, 0.338}, {"Bunny", 69451, 4.150}, {"Phone", 165963, 9.832}};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

SimplifyOptions strips_pm_options(unsigned threads) {
  SimplifyOptions options;
  options.threads = threads;
  options.record_pm = true;
  options.placement = Placement::kHalf;
  return options;
}

Result<ProgressiveMesh> record_pm(const TriangleMesh& mesh, std::function<void(double)> progress,
                                  unsigned threads) {
  SimplifyOptions options = strips_pm_options(threads);
  options.progress = std::move(progress);
  Result<SimplifyResult> simplified = simplify(mesh, options);
  if (!simplified.is_ok()) return simplified.status();
  if (!simplified.value().pm)
    return runtime_error("the simplification recorded no progressive mesh");
  return std::move(simplified).value().pm.value();
}

nlohmann::json strip_stats_json(const StripifyStats& s) {
  return {{"triangles", s.triangles},
          {"strips", s.strips},
          {"indices", s.indices},
          {"swaps", s.swaps},
          {"skipped_degenerate", s.skipped_degenerate},
          {"indices_per_triangle", s.indices_per_triangle()}};
}

Result<StripsBuilt> build_strips(const StripsStepOptions& request, const StripsInput& in) {
  StripsBuilt out;
  const TriangleMesh* stripped = &in.mesh;
  TriangleMesh full;
  if (in.pm) {
    LODBAKE_ASSIGN_OR_RETURN(full, mesh_at_lod(*in.pm, in.pm->full_vertex_count()));
    stripped = &full;
  }
  out.stripped_vertices = stripped->vertex_count();
  out.stripped_triangles = stripped->triangle_count();
  StripifyStats& strip_stats = out.strip_stats;
  auto start = std::chrono::steady_clock::now();
  LODBAKE_ASSIGN_OR_RETURN(TriangleStrips strips, stripify(*stripped, &strip_stats));
  // Each step's input is freed as soon as it is used: the SETS graph is the
  // tool's peak, and the full mesh (rebuilt from the PM) is no part of it.
  full = TriangleMesh();
  out.report["strips"] = strip_stats_json(strip_stats);
  out.report["strips"]["seconds"] = seconds_since(start);

  if (request.strips_only) {
    LODBAKE_ASSIGN_OR_RETURN(Bytes base, encode_base(in.mesh, BaseEncodeOptions()));
    LODBAKE_ASSIGN_OR_RETURN(Bytes strp, encode_strp(strips));
    out.report["sections"] = {{"BASE", base.size()}, {"STRP", strp.size()}};
    out.sections.emplace_back(kBaseTag, std::move(base));
    out.sections.emplace_back(kStrpTag, std::move(strp));
    out.counts = {{"vertices", in.mesh.vertex_count()},
                  {"triangles", in.mesh.triangle_count()},
                  {"strips", strip_stats.strips},
                  {"strip_indices", strip_stats.indices}};
    return out;
  }
  const ProgressiveMesh& pm = *in.pm;
  SetsBuildStats sets_stats;
  start = std::chrono::steady_clock::now();
  LODBAKE_ASSIGN_OR_RETURN(SetsGraph g, build_sets(strips, pm, &sets_stats, request.threads));
  const double build_seconds = seconds_since(start);
  strips = TriangleStrips();
  LODBAKE_ASSIGN_OR_RETURN(Bytes sets, encode_sets(g));
  const uint32_t lod_count = g.lod_count;
  out.report["sets"] = {{"lods", g.lod_count},
                        {"nodes", g.node_count()},
                        {"arcs", g.arc_count()},
                        {"successors", g.successors.size()},
                        {"beginnings", g.beginning_lod.size()},
                        {"strip_updates", sets_stats.strip_updates},
                        {"removed_indices", sets_stats.removed_indices},
                        {"emptied_strips", sets_stats.emptied_strips},
                        {"seconds", build_seconds},
                        {"bytes", sets.size()}};
  g = SetsGraph();  // encoded: free it before BASE and VSPL are
  LODBAKE_ASSIGN_OR_RETURN(Bytes base, encode_base(pm.base, BaseEncodeOptions()));
  LODBAKE_ASSIGN_OR_RETURN(Bytes vspl, encode_vspl(pm, VsplEncodeOptions()));
  nlohmann::json paper = nlohmann::json::array();
  for (const PaperFigure& f : kPaperFigures)
    paper.push_back({{"model", f.model}, {"triangles", f.triangles}, {"megabytes", f.megabytes}});
  out.report["sets"]["paper_in_memory"] = paper;
  out.report["sections"] = {{"BASE", base.size()}, {"VSPL", vspl.size()}, {"SETS", sets.size()}};
  out.sections.emplace_back(kBaseTag, std::move(base));
  out.sections.emplace_back(kVsplTag, std::move(vspl));
  out.sections.emplace_back(kSetsTag, std::move(sets));
  out.counts = {{"vertices", pm.base.vertex_count()},
                {"triangles", pm.base.triangle_count()},
                {"splits", pm.splits.size()},
                {"full_vertices", pm.full_vertex_count()},
                {"full_triangles", full_triangle_count(pm.base.triangle_count(), pm.splits)},
                {"strips", strip_stats.strips},
                {"lods", lod_count}};
  return out;
}

MetaSection strips_meta(const StripsStepOptions& request) {
  MetaSection meta = make_meta("lodbake-strips");
  meta.options = {{"strips_only", request.strips_only}, {"repair", request.repair}};
  return meta;
}

Result<Bytes> strips_container(const StripsStepOptions& request, const StripsInput& in,
                               StripsBuilt built) {
  MetaSection meta = strips_meta(request);
  meta.input = in.meta;
  meta.counts = built.counts;
  LODBAKE_ASSIGN_OR_RETURN(Bytes meta_bytes, encode_meta(meta));
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes)));
  for (auto& [tag, bytes] : built.sections)
    LODBAKE_RETURN_IF_ERROR(writer.add_known_section(tag, std::move(bytes)));
  return writer.finish();
}

Result<MeshSections> strips_mesh_sections(const StripsStepOptions& request,
                                          const AssetCorners& corners, uint32_t scene_mesh,
                                          const TriangleMesh& mesh) {
  StripsInput in;
  if (request.strips_only) {
    in.mesh = mesh;
  } else {
    LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh pm, record_pm(mesh, nullptr, request.threads));
    in.pm = std::make_shared<const ProgressiveMesh>(std::move(pm));
  }
  LODBAKE_ASSIGN_OR_RETURN(StripsBuilt b, build_strips(request, in));
  MeshSections out;
  for (auto& [tag, bytes] : b.sections) {
    const bool vspl = tag == kVsplTag;
    out.sections.emplace_back(tag, std::move(bytes));
    if (!vspl) continue;
    LODBAKE_ASSIGN_OR_RETURN(Bytes wedg, encode_asset_pm_wedges(*in.pm, corners, scene_mesh, mesh));
    out.sections.emplace_back(kWedgTag, std::move(wedg));
  }
  out.counts = b.counts;
  out.report = b.counts;
  return out;
}

}  // namespace lodbake
