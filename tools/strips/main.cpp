// lodbake-strips: triangle strips over a mesh (lib/strips/stripify.h) and
// the SETS multiresolution strip graph over its progressive mesh
// (lib/strips/sets_build.h), written as a container. Thin: the algorithms
// live in lib/strips and lib/simplify, the codecs in formats/sections.
#include <chrono>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/sections/open_container.h"
#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/sections/vspl.h"
#include "formats/support/file_io.h"
#include "lib/core/sha256.h"
#include "lib/ingest/container_mesh.h"
#include "lib/ingest/load_mesh.h"
#include "lib/scene/asset_build.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "lib/strips/sets_build.h"
#include "lib/strips/stripify.h"
#include "tools/common/asset_report.h"
#include "tools/common/cli.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {
namespace {

constexpr const char* kStripsSchema = "lodbake.strips/1";

struct Request {
  std::string input;
  std::string output;
  bool strips_only = false;
  bool repair = false;
  bool strict = false;
};

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

// What the input gives: a mesh (strips-only), or a progressive mesh.
struct Input {
  MetaInput meta;
  TriangleMesh mesh;                  // strips-only: the mesh the strips index
  std::optional<ProgressiveMesh> pm;  // full mode
  nlohmann::json report;
};

int load_container_input(const Tool& tool, const Request& request, Input* in) {
  Result<Bytes> bytes = read_file(request.input);
  if (!bytes.is_ok()) return tool.fail(request.input, bytes.status());
  size_t slash = request.input.find_last_of('/');
  in->meta = MetaInput{
      to_valid_utf8(slash == std::string::npos ? request.input : request.input.substr(slash + 1)),
      sha256_hex(bytes.value().data(), bytes.value().size()), bytes.value().size()};
  Result<OpenedContainer> file = open_container(std::move(bytes).value());
  if (!file.is_ok()) return tool.fail(request.input, file.status());
  if (std::optional<MetaInput> original = container_meta_input(file.value())) in->meta = *original;
  if (request.strips_only) {
    Result<ContainerMesh> mesh = container_input_mesh(file.value());
    if (!mesh.is_ok()) return tool.fail(request.input, mesh.status());
    in->report = {{"kind", mesh.value().source}};
    in->mesh = std::move(mesh.value().mesh);
    return 0;
  }
  Result<uint32_t> group =
      file.value().group_with({kBaseTag, kVsplTag}, "lodbake-strips", "lodbake-simplify --pm");
  if (!group.is_ok()) return tool.fail(request.input, group.status());
  const Section* base = file.value().find(kBaseTag, group.value());
  const Section* vspl = file.value().find(kVsplTag, group.value());
  Result<ProgressiveMesh> pm =
      decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size);
  if (!pm.is_ok()) return tool.fail(request.input, pm.status());
  in->report = {{"kind", "progressive mesh"}, {"splits", pm.value().splits.size()}};
  in->pm = std::move(pm).value();
  return 0;
}

// The progressive mesh the strips' graph follows: QEM half-edge collapses
// as far as legal.
Result<ProgressiveMesh> record_pm(const TriangleMesh& mesh, std::function<void(double)> progress) {
  SimplifyOptions options;
  options.record_pm = true;
  options.placement = Placement::kHalf;
  options.progress = std::move(progress);
  LODBAKE_ASSIGN_OR_RETURN(SimplifyResult simplified, simplify(mesh, options));
  return std::move(*simplified.pm);
}

int load_mesh_input(const Tool& tool, const Request& request, Input* in) {
  LoadOptions load;
  load.repair = request.repair;
  load.strict = request.strict;
  load.per_vertex_attributes = !request.strips_only;  // the simplification records a PM
  load.drop_unreferenced = true;
  LoadedMesh loaded;
  if (int code = load_input(tool, request.input, load, &loaded); code != 0) return code;
  in->meta = meta_input(request.input, loaded);
  in->report = {{"kind", "mesh"}, {"import", to_json(loaded.import)}};
  in->report["repairs"] = repairs_json(load, loaded);
  if (request.strips_only) {
    in->mesh = std::move(loaded.mesh);
    return 0;
  }
  Progress progress(tool, "simplifying");
  const auto start = std::chrono::steady_clock::now();
  Result<ProgressiveMesh> pm =
      record_pm(loaded.mesh, [&](double fraction) { progress.update(fraction); });
  if (!pm.is_ok()) return tool.fail(request.input, pm.status());
  in->report["simplify_seconds"] = seconds_since(start);
  in->pm = std::move(pm).value();
  return 0;
}

nlohmann::json strip_stats_json(const StripifyStats& s) {
  return {{"triangles", s.triangles},
          {"strips", s.strips},
          {"indices", s.indices},
          {"swaps", s.swaps},
          {"skipped_degenerate", s.skipped_degenerate},
          {"indices_per_triangle", s.indices_per_triangle()}};
}

// What one build made: the sections after META, META's counts, and the
// report's "strips", "sets" and "sections".
struct StripsBuilt {
  std::vector<std::pair<std::string, Bytes>> sections;
  std::map<std::string, uint64_t> counts;
  nlohmann::json report = nlohmann::json::object();
  StripifyStats strip_stats;
  uint64_t stripped_vertices = 0, stripped_triangles = 0;
};

// The strips (and without --strips-only the SETS graph) of one input, for a
// mesh or container input and for each mesh of an asset alike.
Result<StripsBuilt> build_strips(const Request& request, const Input& in) {
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
  LODBAKE_ASSIGN_OR_RETURN(SetsGraph g, build_sets(strips, pm, &sets_stats));
  const double build_seconds = seconds_since(start);
  LODBAKE_ASSIGN_OR_RETURN(Bytes base, encode_base(pm.base, BaseEncodeOptions()));
  LODBAKE_ASSIGN_OR_RETURN(Bytes vspl, encode_vspl(pm, VsplEncodeOptions()));
  LODBAKE_ASSIGN_OR_RETURN(Bytes sets, encode_sets(g));
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
                {"lods", g.lod_count}};
  return out;
}

MetaSection strips_meta(const Request& request) {
  MetaSection meta = make_meta("lodbake-strips");
  meta.options = {{"strips_only", request.strips_only}, {"repair", request.repair}};
  return meta;
}

Result<Bytes> finish_container(const Request& request, const Input& in, StripsBuilt built) {
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

// An asset (glTF, or a container with SCNE): every mesh's strips (and
// graph over its own progressive mesh), each in its group beside the scene.
int run_asset(const Tool& tool, const Request& request, const Bytes& bytes) {
  return run_asset_build(tool, asset_run(request, kStripsSchema, "building the strips"),
                         strips_meta(request), bytes,
                         [&](uint32_t, const TriangleMesh& mesh) -> Result<MeshSections> {
                           Input in;
                           if (request.strips_only) {
                             in.mesh = mesh;
                           } else {
                             LODBAKE_ASSIGN_OR_RETURN(in.pm, record_pm(mesh, nullptr));
                           }
                           LODBAKE_ASSIGN_OR_RETURN(StripsBuilt b, build_strips(request, in));
                           MeshSections out;
                           out.sections = std::move(b.sections);
                           out.counts = b.counts;
                           out.report = b.counts;
                           return out;
                         });
}

int run(const Tool& tool, const Request& request) {
  {
    Result<Bytes> bytes = read_file(request.input);
    if (bytes.is_ok() && is_asset(request.input, bytes.value()))
      return run_asset(tool, request, bytes.value());
  }
  Input in;
  if (is_container_input(request.input) && (request.repair || request.strict))
    return tool.usage_error(std::string(request.repair ? "--repair" : "--strict") +
                            " applies to a mesh input");
  const int loaded = is_container_input(request.input) ? load_container_input(tool, request, &in)
                                                       : load_mesh_input(tool, request, &in);
  if (loaded != 0) return loaded;
  nlohmann::json report = {{"schema", kStripsSchema},
                           {"input", request.input},
                           {"output", request.output},
                           {"source", in.report}};
  Result<StripsBuilt> built = build_strips(request, in);
  if (!built.is_ok()) return tool.fail(request.input, built.status());
  const StripifyStats strip_stats = built.value().strip_stats;
  const uint64_t stripped_vertices = built.value().stripped_vertices;
  const uint64_t stripped_triangles = built.value().stripped_triangles;
  report.update(built.value().report);
  Result<Bytes> container = finish_container(request, in, std::move(built).value());
  if (!container.is_ok()) return tool.fail(request.output, container.status());
  Status written = write_file_atomic(request.output, container.value());
  if (!written.is_ok()) return tool.fail(request.output, written);
  report["bytes"] = container.value().size();

  if (tool.json()) {
    tool.print_json(report);
    return 0;
  }
  std::cout << "input         " << request.input << ": " << stripped_vertices << " vertices, "
            << stripped_triangles << " triangles\n";
  std::cout << "strips        " << strip_stats.strips << " strips, " << strip_stats.indices
            << " indices, " << strip_stats.swaps << " swaps, " << strip_stats.indices_per_triangle()
            << " indices per triangle\n";
  if (report.contains("sets")) {
    const nlohmann::json& s = report["sets"];
    std::cout << "SETS          " << s["lods"].get<uint64_t>() << " LoDs, "
              << s["nodes"].get<uint64_t>() << " nodes, " << s["arcs"].get<uint64_t>() << " arcs, "
              << s["successors"].get<uint64_t>() << " successors, " << s["bytes"].get<uint64_t>()
              << " bytes (" << s["bytes"].get<uint64_t>() / 1e6
              << " MB; the paper's in-memory graphs: Cow 0.338 MB, Bunny 4.150 MB, Phone 9.832 "
                 "MB)\n";
  }
  std::cout << "wrote         " << request.output << ": "
            << (request.strips_only ? "BASE + STRP, " : "BASE + VSPL + SETS, ")
            << report["bytes"].get<uint64_t>() << " bytes\n";
  return 0;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  Tool tool("lodbake-strips", "IN -o OUT.lbk [--strips-only] [options]",
            "Builds triangle strips that keep every triangle's orientation and the SETS\n"
            "multiresolution strip graph (Belmonte et al. 2006) over a progressive mesh's\n"
            "contractions. IN is a mesh (simplified here by QEM half-edge collapses as far as\n"
            "legal) or a .lbk holding BASE + VSPL. Writes META + BASE + VSPL + SETS, or with\n"
            "--strips-only META + BASE + STRP (the strips over the full mesh). A glTF asset\n"
            "(or an OBJ with materials, a PLY with colours: docs/import.md), or its\n"
            "container, gets every mesh built in its own group.");
  Request request;
  tool.options().add_options()(
      "output,o", po::value<std::string>(&request.output)->value_name("OUT.lbk"),
      "the container to write")("strips-only", po::bool_switch(&request.strips_only),
                                "write only the strips of the full mesh (STRP), no graph")(
      "repair", po::bool_switch(&request.repair), "repair a mesh input first (see lodbake-pack)")(
      "strict", po::bool_switch(&request.strict),
      "refuse a mesh that needs repairing (exit 3) instead of repairing it by default: "
      "non-manifold edges or vertices, degenerate or duplicate triangles, inconsistent "
      "orientation");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("input", "IN", &request.input)) return *code;
  if (request.output.empty()) return tool.usage_error("nothing to write: give -o OUT.lbk");
  if (same_file(request.input, request.output))
    return tool.usage_error("the output '" + request.output + "' is the input itself");
  if (std::optional<int> code = tool.check_outputs({request.output})) return *code;
  return tool.run([&] { return run(tool, request); });
}
