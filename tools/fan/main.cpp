// lodbake-fan: builds the fan-merge hierarchy (lib/fanmerge) of one mesh and
// writes it with the mesh as a container (META + BASE + FANH; over an
// asset, each mesh's group also holds its corners' wedges, WEDG). With
// --compare it also builds the balanced vertex hierarchy (lib/hierarchy) of
// the same mesh and reports both side by side; that hierarchy's sections
// (VHIE + RFIN) are encoded to count their bytes, never written. Thin: the
// constructions live in lib/, the encodings in formats/.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/fanh.h"
#include "formats/sections/meta.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/support/file_io.h"
#include "lib/bake/fan_step.h"
#include "lib/fanmerge/fan_build.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/ingest/load_mesh.h"
#include "lib/scene/asset_build.h"
#include "tools/common/asset_report.h"
#include "tools/common/cli.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {
namespace {

constexpr const char* kFanSchema = "lodbake.fan/1";

struct Request : FanStepOptions {
  std::string input;
  std::string output;
  bool compare = false;
};

// The figures --compare puts side by side, defined alike for both
// hierarchies (docs/fan.md "Comparison with the balanced vertex hierarchy").
struct HierarchyFigures {
  double build_seconds = 0;
  uint64_t internal_nodes = 0;
  uint64_t leaves = 0;
  uint64_t roots = 0;
  uint64_t depth = 0;           // edges on the longest root-to-leaf path
  double average_children = 0;  // collapsed children per internal node
  uint64_t bytes = 0;           // the hierarchy's own sections
  nlohmann::json sections;      // tag -> bytes
};

nlohmann::json figures_json(const HierarchyFigures& f) {
  return {{"build_seconds", f.build_seconds},
          {"internal_nodes", f.internal_nodes},
          {"leaves", f.leaves},
          {"roots", f.roots},
          {"depth", f.depth},
          {"average_children", f.average_children},
          {"total_bytes", f.bytes},
          {"sections", f.sections}};
}

// The balanced vertex hierarchy of `mesh` as lodbake-hierarchy builds it
// (default options but the fan's boundary weight, so both rank boundaries
// alike), timed like that tool (build + refinement data), its VHIE and RFIN
// encoded only to count their bytes. Half-edge collapses: every split has
// two children of which one (the right) is collapsed, so its average of
// collapsed children is 1 by construction.
Result<HierarchyFigures> balanced_figures(const TriangleMesh& input, double boundary_weight) {
  TriangleMesh mesh;
  mesh.positions = input.positions;
  mesh.triangles = input.triangles;
  BalancedBuildOptions options;
  options.boundary_weight = boundary_weight;
  const auto start = std::chrono::steady_clock::now();
  LODBAKE_ASSIGN_OR_RETURN(BalancedHierarchy built, build_balanced_hierarchy(mesh, options));
  LODBAKE_ASSIGN_OR_RETURN(std::vector<NodeRefinement> refinement,
                           compute_refinement_data(built.hierarchy, mesh));
  HierarchyFigures f;
  f.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  LODBAKE_ASSIGN_OR_RETURN(Bytes vhie, encode_vhie(built.hierarchy));
  LODBAKE_ASSIGN_OR_RETURN(Bytes rfin, encode_rfin(built.hierarchy, refinement));
  const HierarchyShape shape = hierarchy_shape(built.hierarchy);
  f.internal_nodes = shape.splits;
  f.leaves = shape.leaves;
  f.roots = shape.roots;
  f.depth = shape.depth > 0 ? shape.depth - 1 : 0;  // shape counts levels
  f.average_children = shape.splits > 0 ? 1.0 : 0.0;
  f.bytes = vhie.size() + rfin.size();
  f.sections = {{"VHIE", vhie.size()}, {"RFIN", rfin.size()}};
  return f;
}

// balanced / fan; null when the fan side is 0 (nothing merged).
nlohmann::json ratio(double balanced, double fan) {
  return fan > 0 ? nlohmann::json(balanced / fan) : nlohmann::json(nullptr);
}

void print_comparison(const HierarchyFigures& fan, const HierarchyFigures& balanced,
                      const nlohmann::json& comparison) {
  auto row = [](const char* name, const std::string& a, const std::string& b,
                const std::string& r) {
    std::printf("  %-18s %16s %16s %10s\n", name, a.c_str(), b.c_str(), r.c_str());
  };
  auto num = [](double x, const char* format) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, x);
    return std::string(buffer);
  };
  auto count = [](uint64_t x) { return std::to_string(x); };
  auto shown = [&](const nlohmann::json& r) {
    return r.is_number() ? num(r.get<double>(), "%.2fx") : std::string("-");
  };
  std::printf(
      "compare         (balanced / fan; paper: 4-6x the internal nodes, 1.3-1.7x the size)\n");
  row("", "fan", "balanced", "ratio");
  row("build seconds", num(fan.build_seconds, "%.3f"), num(balanced.build_seconds, "%.3f"),
      shown(ratio(balanced.build_seconds, fan.build_seconds)));
  row("internal nodes", count(fan.internal_nodes), count(balanced.internal_nodes),
      shown(comparison["internal_nodes_ratio"]));
  row("leaves", count(fan.leaves), count(balanced.leaves), "");
  row("roots", count(fan.roots), count(balanced.roots), "");
  row("depth", count(fan.depth), count(balanced.depth), "");
  row("average children", num(fan.average_children, "%.2f"), num(balanced.average_children, "%.2f"),
      "");
  row("total bytes", count(fan.bytes), count(balanced.bytes),
      shown(comparison["total_size_ratio"]));
  std::fflush(stdout);
}

Result<Bytes> fan_container(const Request& request, const LoadedMesh& loaded, const FanBuilt& built,
                            nlohmann::json* sections) {
  MetaSection meta = fan_meta(request);
  meta.input = meta_input(request.input, loaded);
  meta.counts = built.counts;
  LODBAKE_ASSIGN_OR_RETURN(Bytes meta_bytes, encode_meta(meta));
  *sections = {
      {"META", meta_bytes.size()}, {"BASE", built.base.size()}, {"FANH", built.fanh.size()}};
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes)));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kBaseTag, built.base));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kFanhTag, built.fanh));
  return writer.finish();
}

// An asset (glTF, or a container with SCNE): every mesh's fan hierarchy,
// each in its group beside the scene.
int run_asset(const Tool& tool, const Request& request, const Bytes& bytes) {
  // The comparison is a table for one mesh; on an asset, compare a mesh
  // extracted from it.
  if (request.compare) return tool.usage_error("--compare applies to a single mesh, not an asset");
  AssetRun run = asset_run(request, kFanSchema, "building the fan hierarchies");
  // Every front carries the asset's wedges (WEDG): each mesh's corners,
  // read once.
  run.attributes = true;
  std::map<uint32_t, MeshCornerWedges> corners;
  Status read_corners = Status::ok();
  read_on_scene(
      &run, [&](const Scene& scene) { return fan_asset_corners(request, scene); }, &corners,
      &read_corners);
  return run_asset_build(
      tool, run, fan_meta(request), bytes,
      [&](uint32_t scene_mesh, const TriangleMesh& mesh) -> Result<MeshSections> {
        LODBAKE_RETURN_IF_ERROR(read_corners);
        LODBAKE_ASSIGN_OR_RETURN(FanBuilt b, build_fan(request.options, mesh));
        return fan_asset_sections(std::move(b), corners, scene_mesh, mesh);
      });
}

int run(const Tool& tool, Request& request) {
  {
    Result<Bytes> bytes = read_file(request.input);
    if (bytes.is_ok() && is_asset(request.input, bytes.value()))
      return run_asset(tool, request, bytes.value());
  }
  LoadOptions load;
  load.repair = request.repair;
  load.strict = request.strict;
  load.drop_unreferenced = true;
  load.threads = request.options.threads;
  LoadedMesh loaded;
  if (int code = load_input(tool, request.input, load, &loaded); code != 0) return code;

  Progress progress(tool, "building the fan hierarchy");
  request.options.progress = [&](double fraction) { progress.update(fraction); };
  Result<FanBuilt> built = build_fan(request.options, loaded.mesh);
  if (!built.is_ok()) return tool.fail(request.input, built.status());
  const FanBuilt& made = built.value();
  const FanBuildResult& result = made.result;
  const FanhStats& stats = made.stats;
  const double seconds = made.seconds;

  nlohmann::json sections;
  Result<Bytes> container = fan_container(request, loaded, made, &sections);
  if (!container.is_ok()) return tool.fail(request.output, container.status());

  // Built before writing, so a mesh the balanced build refuses leaves no
  // output behind.
  HierarchyFigures fan_side, balanced_side;
  nlohmann::json comparison;
  if (request.compare) {
    Result<HierarchyFigures> balanced =
        balanced_figures(loaded.mesh, request.options.boundary_weight);
    if (!balanced.is_ok()) {
      const Status& s = balanced.status();
      return tool.fail(
          request.input,
          Status(s.kind(), "--compare: balanced vertex hierarchy: " + s.message(), s.code()));
    }
    balanced_side = std::move(balanced).value();
    fan_side.build_seconds = seconds;
    fan_side.internal_nodes = stats.internal_nodes;
    fan_side.leaves = stats.leaves;
    fan_side.roots = stats.roots;
    fan_side.depth = stats.depth;
    fan_side.average_children = stats.average_children;
    fan_side.bytes = sections["FANH"].get<uint64_t>();
    fan_side.sections = {{"FANH", fan_side.bytes}};
    comparison = {
        {"fan", figures_json(fan_side)},
        {"balanced", figures_json(balanced_side)},
        {"internal_nodes_ratio", ratio(static_cast<double>(balanced_side.internal_nodes),
                                       static_cast<double>(fan_side.internal_nodes))},
        {"total_size_ratio",
         ratio(static_cast<double>(balanced_side.bytes), static_cast<double>(fan_side.bytes))},
        {"build_time_ratio", ratio(balanced_side.build_seconds, fan_side.build_seconds)},
        {"paper", {{"internal_nodes_ratio", {4.0, 6.0}}, {"total_size_ratio", {1.3, 1.7}}}}};
  }
  Status written = write_file_atomic(request.output, container.value());
  if (!written.is_ok()) return tool.fail(request.output, written);

  const nlohmann::json report = {
      {"schema", kFanSchema},
      {"input", request.input},
      {"output", request.output},
      {"import", to_json(loaded.import)},
      {"repairs", repairs_json(load, loaded)},
      {"input_counts",
       {{"vertices", loaded.mesh.vertex_count()}, {"triangles", loaded.mesh.triangle_count()}}},
      {"coarsest_counts",
       {{"vertices", result.stats.output_vertices}, {"triangles", result.stats.output_triangles}}},
      {"build_seconds", seconds},
      {"fan_hierarchy",
       {{"internal_nodes", stats.internal_nodes},
        {"leaves", stats.leaves},
        {"roots", stats.roots},
        {"depth", stats.depth},
        {"average_children", stats.average_children},
        {"removed_entries", stats.removed_entries},
        {"modified_entries", stats.modified_entries},
        {"bytes", sections["FANH"]}}},
      {"refused",
       {{"topology", result.stats.refused_topology},
        {"fold_over", result.stats.refused_flip},
        {"over_error", result.stats.skipped_error}}},
      {"sections", sections},
      {"total_bytes", container.value().size()}};
  if (tool.json()) {
    if (request.compare) {
      nlohmann::json with_comparison = report;
      with_comparison["compare"] = comparison;
      tool.print_json(with_comparison);
    } else {
      tool.print_json(report);
    }
    return 0;
  }
  std::cout << "input         " << request.input << ": " << loaded.mesh.vertex_count()
            << " vertices, " << loaded.mesh.triangle_count() << " triangles\n";
  std::cout << "built         in " << seconds << " s: " << stats.internal_nodes
            << " internal nodes, " << stats.leaves << " leaves, depth " << stats.depth << ", "
            << stats.average_children << " children on average\n";
  std::cout << "coarsest      " << result.stats.output_vertices << " vertices, "
            << result.stats.output_triangles << " triangles (" << stats.roots << " roots)\n";
  std::cout << "wrote         " << request.output << ": " << container.value().size()
            << " bytes (FANH " << sections["FANH"].get<uint64_t>() << ", BASE "
            << sections["BASE"].get<uint64_t>() << ")\n";
  if (request.compare) print_comparison(fan_side, balanced_side, comparison);
  return 0;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  Tool tool("lodbake-fan", "MESH -o OUT.lbk [options]",
            "Builds the fan-merge hierarchy of a mesh (Livny, Sokolovsky & El-Sana 2007):\n"
            "fan-merges in increasing order of their quadric error, each a node whose\n"
            "children are the fine path of edge collapses giving the same mesh. Writes\n"
            "META, the mesh (BASE) and the hierarchy (FANH). Stops at the first of\n"
            "--vertices and --ratio reached, or when no legal fan-merge is left;\n"
            "--error skips fans over the limit. --compare also builds the balanced vertex\n"
            "hierarchy of the same mesh (as lodbake-hierarchy) and reports both side by side.\n"
            "MESH may also be a lodbake container (.lbk), read as the mesh it stands for; a\n"
            "glTF asset (or an OBJ with materials, a PLY with colours: docs/import.md), or\n"
            "its container, gets every mesh built in its own group, with its corners'\n"
            "wedges (WEDG), so that every front keeps the asset's attributes.");
  Request request;
  double ratio = 0, error = 0;
  uint64_t vertices = 0;
  tool.options().add_options()("output,o",
                               po::value<std::string>(&request.output)->value_name("OUT.lbk"),
                               "the container to write")(
      "vertices", po::value<uint64_t>(&vertices)->value_name("N"), "stop at N vertices or fewer")(
      "ratio", po::value<double>(&ratio)->value_name("R"),
      "stop at R times the input's vertices, 0 < R <= 1")(
      "error", po::value<double>(&error)->value_name("E"),
      "skip fan-merges whose error sqrt(Delta) exceeds E times the bounding-box diagonal")(
      "degree-weight", po::value<double>(&request.options.degree_weight)->value_name("W"),
      "priority = error * (degree / 6)^W: low-degree fans first (default 0: off)")(
      "boundary-weight", po::value<double>(&request.options.boundary_weight)->value_name("W"),
      "weight of the boundary-preserving quadrics (default 10)")(
      "max-normal-change",
      po::value<double>(&request.options.max_normal_change_degrees)->value_name("DEG"),
      "refuse fan-merges that turn a modified triangle by more than DEG degrees (default 90)")(
      "repair", po::bool_switch(&request.repair), "repair the input first (see lodbake-pack)")(
      "strict", po::bool_switch(&request.strict),
      "refuse a mesh that needs repairing (exit 3) instead of repairing it by default: "
      "non-manifold edges or vertices, degenerate or duplicate triangles, inconsistent "
      "orientation")(
      "compare", po::bool_switch(&request.compare),
      "also build the balanced vertex hierarchy of the mesh and report both side by side: build "
      "time, internal nodes, leaves, depth, average children, bytes and their ratios")(
      "threads", po::value<unsigned>(&request.options.threads)->value_name("N"),
      "threads for the quadric set-up and the first keys (oneTBB): 0 (default) every core, or "
      "any count up to 4096; the output is the same for any N");
  tool.positional("mesh", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("mesh", "MESH", &request.input))
    return *code;
  if (request.output.empty()) return tool.usage_error("missing -o OUT.lbk");
  if (request.options.threads > 4096)
    return tool.usage_error("--threads takes a count from 0 (every core) to 4096");
  if (tool.has("vertices")) request.options.target_vertices = vertices;
  if (tool.has("ratio")) {
    if (!(ratio > 0 && ratio <= 1)) return tool.usage_error("--ratio takes a value in (0, 1]");
    request.options.target_ratio = ratio;
  }
  if (tool.has("error")) {
    if (!(error >= 0 && std::isfinite(error)))
      return tool.usage_error("--error takes a finite value >= 0");
    request.options.max_error = error;
  }
  if (!(request.options.max_normal_change_degrees >= 0 &&
        request.options.max_normal_change_degrees <= 180))
    return tool.usage_error("--max-normal-change takes degrees in [0, 180]");
  if (!std::isfinite(request.options.degree_weight) ||
      !(request.options.boundary_weight >= 0 && std::isfinite(request.options.boundary_weight)))
    return tool.usage_error("--degree-weight must be finite and --boundary-weight finite and >= 0");
  if (same_file(request.input, request.output))
    return tool.usage_error("the output '" + request.output + "' is the input mesh itself");
  if (std::optional<int> code = tool.check_outputs({request.output})) return *code;
  return tool.run([&] { return run(tool, request); });
}
