// lodbake-simplify: QEM edge-collapse simplification (lib/simplify) of one
// mesh to a mesh file, an LOD chain, and/or a progressive mesh container.
// Thin: import, simplification, PM encoding and metrics live in lib/ and
// formats/.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/sections/vspl.h"
#include "formats/sections/wedg.h"
#include "formats/support/file_io.h"
#include "lib/bake/simplify_step.h"
#include "lib/ingest/load_mesh.h"
#include "lib/meshio/mesh_writers.h"
#include "lib/metrics/surface_distance.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_lods.h"
#include "lib/scene/scene_summary.h"
#include "lib/simplify/lod_chain.h"
#include "lib/simplify/simplify.h"
#include "tools/common/asset_report.h"
#include "tools/common/cli.h"
#include "tools/common/deviation_report.h"
#include "tools/common/mesh_report.h"
#include "tools/simplify/out_of_core_run.h"

namespace lodbake::cli {
namespace {

constexpr const char* kSimplifySchema = "lodbake.simplify/1";

struct Request : SimplifyStepOptions {
  std::string input;
  std::string output;  // mesh file, or a pattern with %d for --lods
  std::string pm_output;
  std::string lods;            // "0.5,0.25,0.1" as given
  std::vector<double> ratios;  // parsed --lods
  bool metrics = true;
  std::string weight_option;  // the first weight option given, for the usage error
};

Result<std::vector<double>> parse_ratios(const std::string& text) {
  std::vector<double> ratios;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    double r = std::strtod(item.c_str(), &end);
    if (item.empty() || end == nullptr || *end != '\0' || !(r > 0 && r <= 1))
      return Status(ErrorKind::kUsage,
                    "--lods takes ratios in (0, 1] separated by commas, not '" + item + "'");
    // Two levels of one ratio would be two identical files.
    if (std::find(ratios.begin(), ratios.end(), r) != ratios.end())
      return Status(ErrorKind::kUsage, "--lods lists the ratio " + item + " twice");
    ratios.push_back(r);
  }
  if (ratios.empty()) return Status(ErrorKind::kUsage, "--lods needs at least one ratio");
  return ratios;
}

// True when two output paths name one file, existing or not ("a.obj" and
// "./a.obj", or a symbolic link to it).
bool same_output_path(const std::string& a, const std::string& b) {
  if (same_file(a, b)) return true;
  std::error_code error_a, error_b;
  std::filesystem::path full_a =
      std::filesystem::weakly_canonical(std::filesystem::absolute(a), error_a);
  std::filesystem::path full_b =
      std::filesystem::weakly_canonical(std::filesystem::absolute(b), error_b);
  return error_a || error_b ? a == b : full_a == full_b;
}

// "out_%d.glb" with index 2 -> "out_2.glb".
std::string lod_path(const std::string& pattern, size_t index) {
  std::string path = pattern;
  size_t at = path.find("%d");
  return path.replace(at, 2, std::to_string(index));
}

// The achieved geometric error of `output` against `input` (docs/metrics.md),
// as JSON, or nothing with --no-metrics.
Result<nlohmann::json> measure(const Request& request, const TriangleMesh& input,
                               const TriangleMesh& output) {
  if (!request.metrics) return nlohmann::json(nullptr);
  DistanceOptions options;
  options.threads = request.options.threads;
  Result<SurfaceDistance> measured = measure_surface_distance(input, output, options);
  if (!measured.is_ok()) {
    // The library's "first mesh" / "second mesh" are the input and the result.
    std::string message = measured.status().message();
    for (auto [from, to] : {std::pair<std::string, std::string>{"first mesh", "the input"},
                            {"second mesh", "the simplified mesh"}}) {
      if (message.rfind(from, 0) == 0) message = to + message.substr(from.size());
    }
    return Status(measured.status().kind(),
                  "cannot measure the distance to the input (--no-metrics skips it): " + message);
  }
  const SurfaceDistance& d = measured.value();
  nlohmann::json metrics = {{"hausdorff_relative", d.hausdorff_relative},
                            {"mean_relative", d.mean_relative},
                            {"hausdorff", d.hausdorff},
                            {"mean", d.mean},
                            {"diagonal", d.diagonal},
                            {"samples", d.a_to_b.vertex_samples + d.a_to_b.area_samples +
                                            d.b_to_a.vertex_samples + d.b_to_a.area_samples}};
  LODBAKE_RETURN_IF_ERROR(add_mesh_attribute_metrics(input, output, &metrics));
  return metrics;
}

// Written to a temporary file; `outputs` renames every output into place at
// the end, so that a run failing at its second output leaves not even the first.
// A path whose format loses attributes is added to `*lossy`, warned about
// once everything is written (a failed run prints its error alone).
Status stage_mesh(StagedOutputs* outputs, const std::string& path, const TriangleMesh& mesh,
                  std::vector<std::string>* lossy) {
  if (drops_attributes(path, mesh)) lossy->push_back(path);
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, write_mesh_for_path(path, mesh));
  return outputs->stage(path, bytes);
}

Result<Bytes> pm_container(const Request& request, const LoadedMesh& loaded,
                           const ProgressiveMesh& pm, nlohmann::json* report) {
  std::map<std::string, uint64_t> sizes;
  LODBAKE_ASSIGN_OR_RETURN(
      Bytes file, pm_container_bytes(request, meta_input(request.input, loaded), pm, &sizes));
  (*report)["pm"] = {
      {"file", request.pm_output}, {"splits", pm.splits.size()}, {"sections", sizes}};
  return file;
}

// --pm on an asset (glTF, or a container with SCNE): every mesh's
// progressive mesh, each in its group beside the scene.
int run_asset_pm(const Tool& tool, Request& request, const Bytes& bytes) {
  MetaSection meta = make_meta("lodbake-simplify");
  meta.options = pm_meta_options(request);
  AssetRun run = asset_run(request, kSimplifySchema, "simplifying");
  run.output = request.pm_output;
  run.attributes = true;
  // Each mesh's progressive mesh with its wedges, recorded once the asset
  // is read.
  std::map<uint32_t, MeshPm> pms;
  Status recorded = Status::ok();
  read_on_scene(
      &run, [&](const Scene& scene) { return asset_progressive_meshes(request, scene); }, &pms,
      &recorded);
  return run_asset_build(
      tool, run, std::move(meta), bytes,
      [&](uint32_t scene_mesh, const TriangleMesh&) -> Result<MeshSections> {
        LODBAKE_RETURN_IF_ERROR(recorded);
        auto found = pms.find(scene_mesh);
        if (found == pms.end())
          return runtime_error("mesh " + std::to_string(scene_mesh) + " has no progressive mesh");
        return asset_pm_sections(request, found->second);
      });
}

// An asset file (or an OBJ with texture coordinates) written as .glb or
// .gltf is simplified as an asset.
bool is_asset_run(const Request& request, const Bytes& bytes) {
  return request.pm_output.empty() && is_scene_output(request.output) &&
         is_scene_source(request.input, bytes);
}

// What held a mesh above its target, as the report names it.
nlohmann::json blocks_json(const CollapseBlocks& b) {
  return {{"seam_corners", b.seam_corners},
          {"locked_border", b.border},
          {"non_manifold", b.non_manifold},
          {"link", b.link},
          {"flip", b.flip},
          {"uv_fold", b.uv_fold},
          {"normal", b.normal},
          {"seam_mismatch", b.seam_mismatch}};
}

// "12 seam corners, 3 flips": the nonzero counts of `blocks`.
std::string blocks_text(const nlohmann::json& blocks) {
  std::string text;
  for (const auto& [name, count] : blocks.items()) {
    if (count.get<uint64_t>() == 0) continue;
    if (!text.empty()) text += ", ";
    text += std::to_string(count.get<uint64_t>()) + " " + name;
  }
  return text.empty() ? "nothing left to collapse" : text;
}

int run_asset(const Tool& tool, Request& request, const Bytes& bytes) {
  ImportReport imported;
  Result<Scene> scene = read_scene_bytes(request.input, bytes, SceneResources{}, &imported);
  if (!scene.is_ok()) return tool.fail(request.input, scene.status());
  for (const std::string& warning : imported.warnings)
    tool.warn(request.input, warning);
  print_import_notes(tool, request.input, imported);
  const uint64_t triangles = summarize_scene(scene.value()).triangles;

  SceneLodOptions options;
  options.simplify = request.options;
  options.load.repair = request.repair;
  options.load.strict = request.strict;
  options.weights = request.weights;
  if (!request.ratios.empty()) {
    options.ratios = request.ratios;
  } else if (request.options.target_ratio) {
    options.ratios = {*request.options.target_ratio};
  } else if (request.options.target_triangles && triangles > 0) {
    // The asset's budget, shared by its meshes in proportion to their size.
    options.ratios = {std::min(1.0, static_cast<double>(*request.options.target_triangles) /
                                        static_cast<double>(triangles))};
  }
  options.simplify.target_triangles.reset();
  auto start = std::chrono::steady_clock::now();
  Result<SceneLods> lods = simplify_scene(scene.value(), options);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!lods.is_ok()) return tool.fail(request.input, lods.status());

  StagedOutputs staged;
  nlohmann::json outputs = nlohmann::json::array();
  std::vector<std::string> warnings;
  for (size_t level = 0; level < lods.value().levels.size(); ++level) {
    const std::string path =
        request.ratios.empty() ? request.output : lod_path(request.output, level);
    SceneWriteReport written;
    Status staged_ok = stage_scene_file(&staged, path, lods.value().levels[level], &written);
    if (!staged_ok.is_ok()) return tool.fail(path, staged_ok);
    for (const std::string& w : written.warnings)
      warnings.push_back(path + ": " + w);
    uint64_t level_triangles = 0;
    for (const MeshLodReport& m : lods.value().meshes)
      level_triangles += m.lod_triangles[level];
    nlohmann::json out = {{"file", path}, {"triangles", level_triangles}};
    if (!options.ratios.empty()) out["ratio"] = options.ratios[level];
    out["metrics"] = nullptr;
    if (request.metrics) {
      Result<nlohmann::json> metrics =
          measure_asset_level(scene.value(), lods.value().levels[level]);
      if (!metrics.is_ok()) return tool.fail(request.input, metrics.status());
      out["metrics"] = metrics.value();
    }
    outputs.push_back(std::move(out));
  }
  std::string failed_path;
  if (Status committed = staged.commit(&failed_path); !committed.is_ok())
    return tool.fail(failed_path, committed);
  for (const std::string& w : warnings)
    tool.warn("", w);

  nlohmann::json meshes = nlohmann::json::array();
  uint64_t moved = 0;
  std::string short_of;  // the meshes that stopped above a target
  for (const MeshLodReport& m : lods.value().meshes) {
    moved += m.moved_wedges;
    nlohmann::json mesh = {{"mesh", m.mesh},
                           {"input_triangles", m.input_triangles},
                           {"repaired", m.repaired},
                           {"triangles", m.lod_triangles},
                           {"targets", m.lod_targets},
                           {"target_reached", !m.blocked.has_value()},
                           {"moved_wedges", m.moved_wedges}};
    if (m.blocked) {
      mesh["blocked"] = blocks_json(*m.blocked);
      if (!short_of.empty()) short_of += "; ";
      const size_t last = static_cast<size_t>(
          std::min_element(m.lod_targets.begin(), m.lod_targets.end()) - m.lod_targets.begin());
      short_of += "mesh " + std::to_string(m.mesh) + " at " +
                  std::to_string(m.lod_triangles[last]) + " triangles for " +
                  std::to_string(m.lod_targets[last]) + " (" + blocks_text(mesh["blocked"]) + ")";
    }
    meshes.push_back(std::move(mesh));
  }
  // Stopping short is not a failure (exit 0, docs/simplify.md): the output
  // is the simplest legal mesh, and a build step can read target_reached.
  if (!short_of.empty())
    tool.warn(request.input, "no legal collapse left above the target: " + short_of);
  if (tool.json()) {
    tool.print_json({{"schema", kSimplifySchema},
                     {"input", request.input},
                     {"asset", true},
                     {"import", to_json(imported)},
                     {"input_counts", {{"triangles", triangles}}},
                     {"seconds", seconds},
                     {"meshes", meshes},
                     {"outputs", outputs}});
    return 0;
  }
  std::cout << "input         " << request.input << ": an asset, " << meshes.size()
            << " meshes with " << triangles << " triangles\n";
  std::cout << "simplified    each mesh once, its primitives together, in " << seconds << " s; "
            << moved << " wedges kept their values at a moved point\n";
  for (const nlohmann::json& out : outputs)
    std::cout << "wrote         " << out["file"].get<std::string>() << ": "
              << out["triangles"].get<uint64_t>() << " triangles"
              << level_metrics_text(out["metrics"]) << "\n"
              << primitive_metrics_lines(out["metrics"]);
  return 0;
}

int run(const Tool& tool, Request& request) {
  {
    Result<Bytes> bytes = read_file(request.input);
    if (bytes.is_ok() && !request.pm_output.empty() && is_asset(request.input, bytes.value())) {
      // Each is a run of its own: -o ASSET.glb keeps the asset's
      // attributes, --pm holds positions only.
      if (!request.output.empty())
        return tool.usage_error("on an asset, -o and --pm are separate runs: give one of them");
      return run_asset_pm(tool, request, bytes.value());
    }
    if (bytes.is_ok() && is_asset_run(request, bytes.value())) {
      if (request.options.placement != Placement::kHalf)
        return tool.usage_error(
            "an asset is simplified with --placement half (its corners keep their "
            "attributes at the input's points)");
      return run_asset(tool, request, bytes.value());
    }
  }
  if (!request.weight_option.empty())
    return tool.usage_error(request.weight_option +
                            " applies to an asset written as .glb or .gltf (a mesh is "
                            "simplified by its geometry)");
  LoadOptions load;
  load.repair = request.repair;
  load.strict = request.strict;
  load.per_vertex_attributes = !request.pm_output.empty() || !request.ratios.empty();
  load.drop_unreferenced = true;
  load.threads = request.options.threads;
  LoadedMesh loaded;
  if (int code = load_input(tool, request.input, load, &loaded); code != 0) return code;

  const std::vector<double>& ratios = request.ratios;
  if (!ratios.empty()) {
    // One run to the smallest level; the others are taken from its PM.
    request.options.target_ratio = *std::min_element(ratios.begin(), ratios.end());
    request.options.record_pm = true;
  }
  if (!request.pm_output.empty()) request.options.record_pm = true;

  Progress progress(tool, "simplifying");
  request.options.progress = [&](double fraction) { progress.update(fraction); };
  auto start = std::chrono::steady_clock::now();
  const uint64_t input_vertices = loaded.mesh.vertex_count();
  const uint64_t input_triangles = loaded.mesh.triangle_count();
  // Only the metrics read the input's geometry afterwards: without them the
  // engine takes it, and holds the only copy of the mesh.
  Result<SimplifyResult> simplified = request.metrics
                                          ? simplify(loaded.mesh, request.options)
                                          : simplify(std::move(loaded.mesh), request.options);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!simplified.is_ok()) return tool.fail(request.input, simplified.status());
  const SimplifyResult& result = simplified.value();

  nlohmann::json report = {
      {"schema", kSimplifySchema},
      {"input", request.input},
      {"import", to_json(loaded.import)},
      {"input_counts", {{"vertices", input_vertices}, {"triangles", input_triangles}}},
      {"output_counts",
       {{"vertices", result.mesh.vertex_count()}, {"triangles", result.mesh.triangle_count()}}},
      {"seconds", seconds},
      {"collapses", result.stats.collapses},
      {"passes", result.stats.passes},
      // Tries refused, by reason (an edge refused in one pass is tried again
      // in the next): what held the simplification back when it stopped
      // short of its target.
      {"refused",
       {{"link", result.stats.refused_link},
        {"flip", result.stats.refused_flip},
        {"other", result.stats.refused_other},
        {"height", result.stats.refused_height}}},
      {"max_collapse_error", result.stats.max_collapse_error}};
  report["repairs"] = repairs_json(load, loaded);

  StagedOutputs staged;
  std::vector<std::string> lossy;
  nlohmann::json outputs = nlohmann::json::array();
  if (!ratios.empty()) {
    std::vector<uint64_t> targets;
    for (double r : ratios)
      targets.push_back(static_cast<uint64_t>(r * static_cast<double>(input_triangles)));
    Result<std::vector<TriangleMesh>> lods = extract_lods(*result.pm, targets);
    if (!lods.is_ok()) return tool.fail(request.input, lods.status());
    for (size_t i = 0; i < lods.value().size(); ++i) {
      std::string path = lod_path(request.output, i);
      Result<nlohmann::json> metrics = measure(request, loaded.mesh, lods.value()[i]);
      if (!metrics.is_ok()) return tool.fail(request.input, metrics.status());
      Status written = stage_mesh(&staged, path, lods.value()[i], &lossy);
      if (!written.is_ok()) return tool.fail(path, written);
      outputs.push_back({{"file", path},
                         {"ratio", ratios[i]},
                         {"vertices", lods.value()[i].vertex_count()},
                         {"triangles", lods.value()[i].triangle_count()},
                         {"metrics", metrics.value()}});
    }
  } else {
    Result<nlohmann::json> metrics = measure(request, loaded.mesh, result.mesh);
    if (!metrics.is_ok()) return tool.fail(request.input, metrics.status());
    report["metrics"] = metrics.value();
    if (!request.output.empty()) {
      Status written = stage_mesh(&staged, request.output, result.mesh, &lossy);
      if (!written.is_ok()) return tool.fail(request.output, written);
      outputs.push_back({{"file", request.output},
                         {"vertices", result.mesh.vertex_count()},
                         {"triangles", result.mesh.triangle_count()},
                         {"metrics", metrics.value()}});
    }
  }
  report["outputs"] = outputs;
  if (!request.pm_output.empty()) {
    Result<Bytes> container = pm_container(request, loaded, *result.pm, &report);
    if (!container.is_ok()) return tool.fail(request.pm_output, container.status());
    Status written = staged.stage(request.pm_output, container.value());
    if (!written.is_ok()) return tool.fail(request.pm_output, written);
    report["pm"]["bytes"] = container.value().size();
  }
  std::string failed_path;
  if (Status committed = staged.commit(&failed_path); !committed.is_ok())
    return tool.fail(failed_path, committed);
  for (const std::string& path : lossy)
    tool.warn(path, "this format cannot store the mesh's normals or texture coordinates");

  if (tool.json()) {
    tool.print_json(report);
    return 0;
  }
  std::cout << "input         " << request.input << ": " << input_vertices << " vertices, "
            << input_triangles << " triangles\n";
  std::cout << "simplified    " << result.mesh.vertex_count() << " vertices, "
            << result.mesh.triangle_count() << " triangles in " << seconds << " s ("
            << result.stats.collapses << " collapses, "
            << (request.options.height_guard ? std::to_string(result.stats.refused_height) +
                                                   " tries refused by the height guard, "
                                             : std::string())
            << "largest collapse error " << result.stats.max_collapse_error << " of the diagonal"
            << level_metrics_text(report.value("metrics", nlohmann::json(nullptr))) << ")\n";
  for (const nlohmann::json& out : outputs)
    std::cout << "wrote         " << out["file"].get<std::string>() << ": "
              << out["triangles"].get<uint64_t>() << " triangles"
              << (ratios.empty() ? std::string() : level_metrics_text(out["metrics"])) << "\n";
  if (report.contains("pm"))
    std::cout << "wrote         " << request.pm_output << ": progressive mesh, "
              << report["pm"]["splits"].get<uint64_t>() << " vertex splits, "
              << report["pm"]["bytes"].get<uint64_t>() << " bytes\n";
  return 0;
}

// What a --memory-limit run takes, checked before it starts.
std::optional<int> check_out_of_core(const Tool& tool, const Request& request,
                                     const OutOfCoreRequest& ooc) {
  if (!request.pm_output.empty())
    return tool.usage_error(
        "--pm is not recorded out of core (--memory-limit): a progressive mesh needs the whole "
        "mesh in memory");
  if (!request.ratios.empty()) return tool.usage_error("--lods is not available out of core");
  if (request.repair)
    return tool.usage_error("--repair is not available out of core: blocks are read as they are");
  if (!request.weight_option.empty())
    return tool.usage_error(request.weight_option + " applies to assets, not out of core");
  const std::string& stage = ooc.stage;
  if (!stage.empty() && stage != "split" && stage != "block" && stage != "merge")
    return tool.usage_error("--stage takes split, block or merge, not '" + stage + "'");
  if (!stage.empty() && ooc.work.empty())
    return tool.usage_error("--stage " + stage + " needs --work DIR");
  if ((stage.empty() || stage == "split") && !tool.has("memory-limit"))
    return tool.usage_error("--stage split needs --memory-limit SIZE");
  if (stage == "block" && !tool.has("block"))
    return tool.usage_error("--stage block needs --block N");
  if (stage != "block" && tool.has("block"))
    return tool.usage_error("--block belongs to --stage block");
  if ((stage == "split" || stage == "block") && !request.output.empty())
    return tool.usage_error("--stage " + stage + " writes into --work; -o belongs to merge");
  if (stage == "merge" && request.output.empty())
    return tool.usage_error("--stage merge needs -o OUT");
  // The later stages take the split's options from the plan: giving others
  // there would be ignored, so it is refused.
  if (stage == "block" || stage == "merge") {
    for (const char* name :
         {"memory-limit", "ratio", "triangles", "error", "placement", "boundary-weight",
          "lock-border", "max-normal-change", "height-guard", "height-guard-factor"})
      if (tool.has(name) && !tool.args()[name].defaulted())
        return tool.usage_error(std::string("--") + name +
                                " belongs to the split: the later stages read it from the plan");
  }
  if ((stage.empty() || stage == "split") && !request.options.target_ratio &&
      !request.options.target_triangles && !request.options.max_error)
    return tool.usage_error("--memory-limit needs a target: --ratio, --triangles or --error");
  if (!ooc.work.empty() && !request.output.empty() && same_file(request.input, request.output))
    return tool.usage_error("the output is the input mesh itself");
  return std::nullopt;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  Tool tool("lodbake-simplify", "MESH -o OUT.{obj,ply,off,glb} [--pm OUT.lbk] [options]",
            "Simplifies a mesh by quadric-error edge collapses (Garland & Heckbert) and\n"
            "writes the result, an LOD chain (--lods), and/or the progressive mesh it\n"
            "recorded (--pm: a container with BASE and VSPL that inspect can extract any\n"
            "level of detail from). Stops at the first of --ratio, --triangles and --error\n"
            "reached, or when no collapse is legal. MESH may also be a lodbake container\n"
            "(.lbk), read as the mesh it stands for (a progressive mesh's full mesh, or a\n"
            "BASE that is the input). On an asset (glTF, an OBJ with materials or texture\n"
            "coordinates, a PLY with colours: docs/import.md), -o OUT.glb simplifies every\n"
            "mesh in the asset with its attributes in the error and its seams kept\n"
            "(--permissive lets them move), and --pm (alone) writes every mesh's progressive\n"
            "mesh in its group (an OBJ with texture coordinates only: the mesh's, as for any\n"
            "mesh). A mesh left above its target because no collapse is legal is one\n"
            "warning line and still exit 0 (JSON: target_reached false, and why).");
  Request request;
  OutOfCoreRequest ooc;
  double ratio = 0, error = 0;
  uint64_t triangles = 0;
  std::string seam_release;
  tool.options().add_options()("output,o",
                               po::value<std::string>(&request.output)->value_name("OUT"),
                               "the simplified mesh (.obj .ply .off .glb); with --lods a pattern "
                               "containing %d, replaced by the level's index")(
      "pm", po::value<std::string>(&request.pm_output)->value_name("OUT.lbk"),
      "also write the progressive mesh (META + BASE + VSPL)")(
      "ratio", po::value<double>(&ratio)->value_name("R"),
      "stop at R times the input's triangles, 0 < R <= 1")(
      "triangles", po::value<uint64_t>(&triangles)->value_name("N"), "stop at N triangles")(
      "error", po::value<double>(&error)->value_name("E"),
      "stop before a collapse whose error exceeds E times the bounding-box diagonal")(
      "lods", po::value<std::string>(&request.lods)->value_name("R1,R2,..."),
      "write one mesh per ratio from a single run (-o must contain %d)")(
      "placement", po::value<std::string>(&request.placement)->value_name("half|optimal"),
      "half (default): the surviving vertex keeps an endpoint's position; optimal: the "
      "quadric's minimiser")(
      "boundary-weight", po::value<double>(&request.options.boundary_weight)->value_name("W"),
      "weight of the boundary-preserving quadrics (default 10; times the edge "
      "length in half placement)")("lock-border", po::bool_switch(&request.options.lock_border),
                                   "never move or remove boundary vertices")(
      "max-normal-change",
      po::value<double>(&request.options.max_normal_change_degrees)->value_name("DEG"),
      "refuse collapses that turn a face normal by more than DEG degrees (default 150)")(
      "permissive", po::bool_switch(&request.options.permissive),
      "let texture seams and material borders move: seam corners may go, and a wedge "
      "without a partner keeps its values at the survivor, the attribute error counted")(
      "seam-release", po::value<std::string>(&seam_release)->value_name("E|none"),
      "(assets, without --permissive) seams stay while a collapse that keeps them costs at "
      "most E times the diagonal; past it they may move as with --permissive, at their "
      "error plus E (default 0.01; none: they never move)")(
      "normal-weight", po::value<double>(&request.weights.normal)->value_name("W"),
      "(assets) how much normals weigh: a weighted difference of 1 over a distance d "
      "costs about what moving the surface by d does (default 0.3; 0 leaves them out)")(
      "uv-weight", po::value<double>(&request.weights.texcoord)->value_name("W"),
      "(assets) the same for texture coordinates (default 5)")(
      "color-weight", po::value<double>(&request.weights.color)->value_name("W"),
      "(assets) the same for vertex colours (default 1)")(
      "tangent-weight", po::value<double>(&request.weights.tangent)->value_name("W"),
      "(assets) the same for tangents (default 0.1)")(
      "height-guard", po::bool_switch(&request.options.height_guard),
      "(half placement only) also refuse collapses that leave the removed vertex far from "
      "the plane of a face they move: a lower Hausdorff error for 1.1 to 1.5 times the time")(
      "height-guard-factor",
      po::value<double>(&request.options.height_guard_factor)->value_name("F"),
      "the guard's allowance (implies --height-guard): a moved face may pass at most "
      "sqrt(F * the pass's error scale) from the removed vertex; default 1.333, larger refuses "
      "fewer collapses and is faster (3: about 1.05 times the time)")(
      "repair", po::bool_switch(&request.repair), "repair the input first (see lodbake-pack)")(
      "strict", po::bool_switch(&request.strict),
      "refuse a mesh that needs repairing (exit 3) instead of repairing it by default: "
      "non-manifold edges or vertices, degenerate or duplicate triangles, inconsistent "
      "orientation")("quantize", po::value<int>(&request.quantize_bits)->value_name("BITS"),
                     "store the PM's positions quantized to BITS (1..30) bits")(
      "threads", po::value<unsigned>(&request.options.threads)->value_name("N"),
      "threads for the engine's parallel steps (oneTBB): 0 (default) every core, or any "
      "count up to 4096; the output is the same bytes for every count")(
      "no-metrics",
      "skip measuring the Hausdorff and mean distance, and the UV and normal deviation, to the "
      "input")("memory-limit", po::value<std::string>(&ooc.memory_limit)->value_name("SIZE"),
               "simplify a PLY or OBJ mesh larger than memory in spatial blocks held to about SIZE "
               "(512M, 2G; docs/simplify.md \"Larger than memory\"); no --pm, --lods or metrics")(
      "stage", po::value<std::string>(&ooc.stage)->value_name("split|block|merge"),
      "run one stage of a --memory-limit run: split MESH into blocks in --work, simplify block "
      "--block N there, or merge the blocks into -o OUT")(
      "block", po::value<uint32_t>(&ooc.block)->value_name("N"), "the block of --stage block")(
      "work", po::value<std::string>(&ooc.work)->value_name("DIR"),
      "the folder of a --memory-limit run's blocks (default: a new folder beside -o, removed "
      "at the end)");
  tool.positional("mesh", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  const bool out_of_core = tool.has("memory-limit") || tool.has("stage");
  const bool needs_mesh = ooc.stage != "block" && ooc.stage != "merge";
  if (needs_mesh) {
    if (std::optional<int> code = tool.single_positional("mesh", "MESH", &request.input))
      return *code;
  } else if (!tool.positionals("mesh").empty()) {
    return tool.usage_error("--stage " + ooc.stage + " reads its mesh from --work, not MESH");
  }
  request.metrics = !tool.has("no-metrics");
  if (!out_of_core && (tool.has("work") || tool.has("block")))
    return tool.usage_error("--work and --block belong to a --memory-limit run");
  if (out_of_core && ooc.stage.empty() && request.output.empty() && request.pm_output.empty())
    return tool.usage_error("nothing to write: give -o OUT");
  if (!out_of_core && request.output.empty() && request.pm_output.empty())
    return tool.usage_error("nothing to write: give -o OUT and/or --pm OUT.lbk");
  if (tool.has("ratio")) {
    if (!(ratio > 0 && ratio <= 1)) return tool.usage_error("--ratio takes a value in (0, 1]");
    request.options.target_ratio = ratio;
  }
  if (tool.has("triangles")) request.options.target_triangles = triangles;
  if (tool.has("error")) {
    if (!(error >= 0 && std::isfinite(error)))
      return tool.usage_error("--error takes a finite value >= 0");
    request.options.max_error = error;
  }
  if (seam_release == "none") {
    request.options.seam_release.reset();
  } else if (tool.has("seam-release")) {
    char* end = nullptr;
    const double bound = std::strtod(seam_release.c_str(), &end);
    if (seam_release.empty() || *end != '\0' || !(bound >= 0) || !std::isfinite(bound))
      return tool.usage_error("--seam-release takes a finite value >= 0 or 'none', not '" +
                              seam_release + "'");
    request.options.seam_release = bound;
  }
  if (request.placement == "optimal") {
    request.options.placement = Placement::kOptimal;
  } else if (request.placement != "half") {
    return tool.usage_error("--placement takes 'half' or 'optimal', not '" + request.placement +
                            "'");
  }
  // More is surely a typo (and tbb::task_arena takes an int).
  if (request.options.threads > 4096)
    return tool.usage_error("--threads takes a count from 0 (every core) to 4096");
  if (tool.has("height-guard-factor")) {
    if (!is_valid_height_guard_factor(request.options.height_guard_factor))
      return tool.usage_error("--height-guard-factor takes a finite value above 0");
    request.options.height_guard = true;
  }
  if (request.options.height_guard && request.options.placement != Placement::kHalf)
    return tool.usage_error(
        std::string(tool.has("height-guard-factor") ? "--height-guard-factor" : "--height-guard") +
        " needs --placement half");
  if (tool.has("lods")) {
    Result<std::vector<double>> parsed = parse_ratios(request.lods);
    if (!parsed.is_ok()) return tool.usage_error(parsed.status().message());
    request.ratios = parsed.value();
    if (request.output.find("%d") == std::string::npos)
      return tool.usage_error("--lods needs -o with %d in the name, e.g. -o lod_%d.glb");
    if (tool.has("ratio") || tool.has("triangles") || tool.has("error"))
      return tool.usage_error(
          "--lods sets the ratios; do not combine it with --ratio, "
          "--triangles or --error");
  }
  if (std::optional<int> code = check_quantize_bits(tool, request.quantize_bits)) return *code;
  // Checked here too (the engine refuses them as well), so that they are
  // usage errors, not errors about the input.
  if (!(request.options.boundary_weight >= 0 && std::isfinite(request.options.boundary_weight)))
    return tool.usage_error("--boundary-weight takes a finite value >= 0");
  for (const auto& [name, weight] : {std::make_pair("normal-weight", request.weights.normal),
                                     std::make_pair("uv-weight", request.weights.texcoord),
                                     std::make_pair("color-weight", request.weights.color),
                                     std::make_pair("tangent-weight", request.weights.tangent)}) {
    if (!tool.has(name)) continue;
    if (!(weight >= 0 && std::isfinite(weight)))
      return tool.usage_error(std::string("--") + name + " takes a finite value >= 0");
    if (request.weight_option.empty()) request.weight_option = std::string("--") + name;
  }
  if (!(request.options.max_normal_change_degrees >= 0 &&
        request.options.max_normal_change_degrees <= 180))
    return tool.usage_error("--max-normal-change takes degrees in [0, 180]");
  if (request.quantize_bits != 0 && request.pm_output.empty())
    return tool.usage_error("--quantize applies to the --pm container (meshes keep float32)");
  for (const std::string& out : {request.output, request.pm_output})
    if (!out.empty() && same_file(request.input, out))
      return tool.usage_error("the output '" + out + "' is the input mesh itself");
  if (!request.output.empty() && !request.pm_output.empty() &&
      same_output_path(request.output, request.pm_output))
    return tool.usage_error("-o and --pm name the same file '" + request.pm_output + "'");
  if (out_of_core) {
    if (std::optional<int> code = check_out_of_core(tool, request, ooc)) return *code;
    ooc.input = request.input;
    ooc.output = request.output;
    ooc.options = request.options;
    if (std::optional<int> code = tool.check_outputs({ooc.output})) return *code;
    return tool.run([&] { return run_out_of_core(tool, ooc); });
  }
  std::vector<std::string> outputs = {request.ratios.empty() ? request.output : ""};
  for (size_t i = 0; i < request.ratios.size(); ++i)
    outputs.push_back(lod_path(request.output, i));
  outputs.push_back(request.pm_output);
  if (std::optional<int> code = tool.check_outputs(outputs)) return *code;
  return tool.run([&] { return run(tool, request); });
}
