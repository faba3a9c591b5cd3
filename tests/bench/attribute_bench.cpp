// Attribute-aware simplification against its peers (issue "attribute-aware
// simplification", benchmark): every asset at every ratio through
//   - lodbake:     lodbake-simplify IN -o OUT.glb --ratio R --no-metrics -q
//   - gltfpack -si: node gltfpack/cli.js -i IN -o OUT.glb -si R -noq -kn -km
//   - gltfpack -sa: the same with -sa (falls back to the sloppy simplifier
//                   when the precise one stops above the target)
//   - meshopt:     node meshopt_simplify.mjs (meshoptimizer's
//                  simplifyWithAttributes, set up as gltfpack sets it up)
// each a subprocess, side by side in one run, every output scored by
// lodbake's own metric (lib/metrics/attribute_deviation.h): triangles
// reached against the target, symmetric Hausdorff distance relative to the
// input's diagonal, UV and normal deviation (95th percentiles), wall time.
//
// -kn -km keep gltfpack from merging named nodes' meshes and named
// materials, as lodbake keeps every node, mesh and material; they change
// what is merged, not how a mesh is simplified.
//
// Every tool reads the same file: the asset as lodbake reads it, written
// back as one GLB (Draco decoded, which gltfpack cannot read; an OBJ
// converted, which gltf-transform cannot read; images embedded). That GLB,
// read back, is the reference every output is scored against.
//
// Times: lodbake's is its process's wall time (median of --runs).
// gltfpack's is the same pack inside one node process (gltfpack_copy.mjs
// with the same arguments: wasm compiled and V8 warmed before, file in and
// GLB file out, best of --runs), as its CLI's start-up and a cold first
// pack would otherwise make up most of its figure. meshopt's is the
// script's own figure from read to written (node and the module loads
// left out; median). The CLI processes' wall times are in the "process"
// column. Process runs are taken in turns (run 1 of every tool, then run
// 2) so that a change in the load of a shared machine falls on all alike. Nothing here is asserted
// but, with --check, that every tool produced a scored output.
//
//   bench_attributes [--ratios 0.5,0.25,0.1] [--runs N] [--samples N] [--threads N] [--quick]
//                    [--tools LIST] [--json] [--markdown] [--check] [--max-hausdorff H]
//                    [--require-peers] [--keep DIR]
//                    [--lodbake PATH] [--node PATH] [--npm DIR] ASSET...
//
// Without node or the npm packages, the peers' rows are left out with a
// note (--require-peers: exit 77 instead, for the smoke test to skip).
// Built without the metric's implementation, the score columns show "-"
// and a note says so.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_summary.h"
#ifdef LODBAKE_BENCH_WITH_SCORING
#include "lib/metrics/attribute_deviation.h"
#endif

namespace {

namespace fs = std::filesystem;
using lodbake::bench::shell_quoted;

enum class ToolKind { kLodbake, kLodbakePermissive, kGltfpack, kGltfpackAggressive, kMeshopt };

struct Tool {
  ToolKind kind;
  std::string name;  // as the table and --tools name it
};

const std::vector<Tool>& all_tools() {
  static const std::vector<Tool> tools = {{ToolKind::kLodbake, "lodbake"},
                                          {ToolKind::kLodbakePermissive, "lodbake-p"},
                                          {ToolKind::kGltfpack, "gltfpack-si"},
                                          {ToolKind::kGltfpackAggressive, "gltfpack-sa"},
                                          {ToolKind::kMeshopt, "meshopt"}};
  return tools;
}

struct Setup {
  std::string lodbake;  // lodbake-simplify
  std::string node;
  std::string npm;              // the folder with node_modules
  std::string script;           // meshopt_simplify.mjs
  std::string gltfpack_script;  // gltfpack_copy.mjs, for the in-process time
  std::vector<Tool> tools;
  std::vector<double> ratios = {0.5, 0.25, 0.1};
  int runs = 3;
  uint64_t samples = 200000;
  unsigned threads = 0;
  std::string note;  // why peers were left out, or empty
  double node_startup_ms = -1;
  double gltfpack_startup_ms = -1;
};

struct Score {
  bool measured = false;
  std::string error;  // the metric's message when it refused
  double hausdorff_relative = 0;
  double uv_p95 = 0, normal_p95 = 0;
  uint64_t uv_samples = 0, normal_samples = 0;
};

struct Result {
  std::string error;  // empty when the tool wrote an output that could be read
  uint64_t triangles = 0;
  double time_ms = -1;     // the figure compared (see the header comment)
  double process_ms = -1;  // the whole subprocess
  Score score;
};

struct Case {
  size_t asset = 0;
  double ratio = 0;
  uint64_t target = 0;
  std::vector<Result> results;  // one per Setup::tools
};

struct Asset {
  std::string path;
  std::string error;  // why it has no row
  fs::path prepared;  // the GLB every tool reads
  std::optional<lodbake::Scene> reference;
  uint64_t triangles = 0;   // drawn: each mesh once per node that uses it
  uint64_t primitives = 0;  // triangle primitives drawn
};

std::string name_of(const std::string& path) {
  return fs::path(path).filename().string();
}

// The line of a tool's log that says why it failed: the first starting
// with "Error", else the first that is not empty.
std::string failure_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line, first;
  while (std::getline(in, line)) {
    if (line.rfind("Error", 0) == 0) return line;
    if (first.empty()) first = line;
  }
  return first;
}

// Reads `path` as a scene; its drawn triangle count when it has triangles.
lodbake::Result<lodbake::Scene> read_scene(const std::string& path) {
  lodbake::ImportReport report;
  return lodbake::read_scene_file(path, lodbake::SceneResources(), &report);
}

uint64_t drawn_primitives(const lodbake::SceneSummary& summary) {
  uint64_t total = 0;
  for (const lodbake::MeshSummary& mesh : summary.meshes) {
    uint64_t triangle_primitives = 0;
    for (const lodbake::PrimitiveSummary& primitive : mesh.primitives)
      triangle_primitives += primitive.triangles > 0;
    total += triangle_primitives * std::max<uint64_t>(1, mesh.nodes.size());
  }
  return total;
}

void prepare_asset(Asset* asset, const fs::path& scratch, size_t index) {
  auto read = read_scene(asset->path);
  if (!read.is_ok()) {
    asset->error = "cannot read: " + read.status().message();
    return;
  }
  asset->prepared =
      scratch / (std::to_string(index) + "-" + fs::path(asset->path).stem().string() + ".glb");
  lodbake::SceneWriteReport written;
  lodbake::Status status =
      lodbake::write_scene_file(asset->prepared.string(), read.value(), &written);
  if (!status.is_ok()) {
    asset->error = "cannot write its GLB: " + status.message();
    return;
  }
  auto reference = read_scene(asset->prepared.string());
  if (!reference.is_ok()) {
    asset->error = "cannot read its GLB back: " + reference.status().message();
    return;
  }
  const lodbake::SceneSummary summary = lodbake::summarize_scene(reference.value());
  asset->triangles = summary.instanced_triangles;
  asset->primitives = drawn_primitives(summary);
  if (asset->triangles == 0) asset->error = "no triangles";
  asset->reference = std::move(reference.value());
}

std::string ratio_text(double ratio) {
  std::ostringstream text;
  text << ratio;
  return text.str();
}

std::vector<std::string> command_of(const Setup& setup, ToolKind kind, const fs::path& input,
                                    const fs::path& output, double ratio) {
  const std::string cli = (fs::path(setup.npm) / "node_modules" / "gltfpack" / "cli.js").string();
  switch (kind) {
    case ToolKind::kLodbake:
      return {setup.lodbake, input.string(),    "-o",           output.string(),
              "--ratio",     ratio_text(ratio), "--no-metrics", "-q"};
    case ToolKind::kLodbakePermissive:  // seams may move, as gltfpack -sa's
      return {setup.lodbake,  input.string(), "-o", output.string(), "--ratio", ratio_text(ratio),
              "--permissive", "--no-metrics", "-q"};
    case ToolKind::kGltfpack:
      return {setup.node,        cli,    "-i",  input.string(), "-o", output.string(), "-si",
              ratio_text(ratio), "-noq", "-kn", "-km"};
    case ToolKind::kGltfpackAggressive:
      return {setup.node,        cli,   "-i",   input.string(), "-o", output.string(), "-si",
              ratio_text(ratio), "-sa", "-noq", "-kn",          "-km"};
    case ToolKind::kMeshopt:
      return {setup.node, setup.script,      "--modules",    setup.npm,
              "--ratio",  ratio_text(ratio), input.string(), output.string()};
  }
  return {};
}

// The script's "ok <simplify ms> <total ms> ..." line; -1 when absent.
double meshopt_total_ms(const fs::path& log) {
  std::ifstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string word;
    double simplify_ms = 0, total_ms = 0;
    if (fields >> word && word == "ok" && fields >> simplify_ms >> total_ms) return total_ms;
  }
  return -1;
}

void score_output(const Asset& asset, const lodbake::Scene& output, const Setup& setup,
                  Score* score) {
#ifdef LODBAKE_BENCH_WITH_SCORING
  lodbake::DeviationOptions options;
  options.area_samples = setup.samples;
  options.threads = setup.threads;
  auto measured = lodbake::measure_scene_deviation(*asset.reference, output, options);
  if (!measured.is_ok()) {
    score->error = measured.status().message();
    return;
  }
  const lodbake::SceneDeviation& deviation = measured.value();
  score->measured = true;
  score->hausdorff_relative = deviation.hausdorff_relative;
  score->uv_p95 = deviation.uv.p95;
  score->uv_samples = deviation.uv.samples;
  score->normal_p95 = deviation.normal_degrees.p95;
  score->normal_samples = deviation.normal_degrees.samples;
#else
  (void)asset, (void)output, (void)setup, (void)score;
#endif
}

// gltfpack's pack with `kind`'s arguments inside one node process, best of
// the runs in milliseconds; -1 when it fails.
double gltfpack_in_process_ms(const Setup& setup, ToolKind kind, const fs::path& input,
                              double ratio, const fs::path& scratch) {
  const fs::path folder = scratch / "in-process";
  std::error_code ignored;
  fs::create_directories(folder, ignored);
  std::vector<std::string> argv = {
      setup.node, setup.gltfpack_script, "--modules", setup.npm,
      "--out",    folder.string(),       "--runs",    std::to_string(setup.runs)};
  const std::vector<std::string> tool = command_of(setup, kind, input, folder / "unused", ratio);
  // After "node cli.js -i IN -o OUT": the simplification arguments.
  for (size_t i = 6; i < tool.size(); ++i)
    if (tool[i] != "-noq") argv.insert(argv.end(), {"--arg", tool[i]});
  argv.push_back(input.string());
  const fs::path log = folder / "log.txt";
  if (lodbake::bench::run_tool(argv, log.string()).exit_status != 0) return -1;
  std::ifstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream stream(line);
    for (std::string field; std::getline(stream, field, '\t');)
      fields.push_back(field);
    if (fields.size() >= 3 && fields[0] == "ok") return std::atof(fields[2].c_str());
  }
  return -1;
}

// Runs every tool on one asset at one ratio, --runs times in turns, then
// reads and scores each output once.
Case run_case(const Setup& setup, const std::vector<Asset>& assets, size_t index, double ratio,
              const fs::path& scratch) {
  const Asset& asset = assets[index];
  Case result;
  result.asset = index;
  result.ratio = ratio;
  result.target = static_cast<uint64_t>(std::llround(ratio * static_cast<double>(asset.triangles)));
  result.results.resize(setup.tools.size());
  const std::string stem = asset.prepared.stem().string() + ".r" + ratio_text(ratio);
  std::vector<std::vector<double>> process(setup.tools.size()), own(setup.tools.size());
  for (int run = 0; run < setup.runs; ++run) {
    for (size_t t = 0; t < setup.tools.size(); ++t) {
      Result& out = result.results[t];
      if (!out.error.empty()) continue;
      const fs::path output = scratch / (stem + "." + setup.tools[t].name + ".glb");
      const fs::path log = scratch / (stem + "." + setup.tools[t].name + ".log");
      std::error_code ignored;
      fs::remove(output, ignored);
      const lodbake::bench::ToolRun ran = lodbake::bench::run_tool(
          command_of(setup, setup.tools[t].kind, asset.prepared, output, ratio), log.string());
      if (ran.exit_status != 0) {
        out.error = "exit " + std::to_string(ran.exit_status) + ": " + failure_line(log);
        continue;
      }
      process[t].push_back(1e3 * ran.wall_seconds);
      if (setup.tools[t].kind == ToolKind::kMeshopt) own[t].push_back(meshopt_total_ms(log));
    }
  }
  for (size_t t = 0; t < setup.tools.size(); ++t) {
    Result& out = result.results[t];
    if (!out.error.empty()) continue;
    out.process_ms = lodbake::bench::median(process[t]);
    switch (setup.tools[t].kind) {
      case ToolKind::kLodbake:
      case ToolKind::kLodbakePermissive:
        out.time_ms = out.process_ms;
        break;
      case ToolKind::kGltfpack:
      case ToolKind::kGltfpackAggressive:
        out.time_ms =
            gltfpack_in_process_ms(setup, setup.tools[t].kind, asset.prepared, ratio, scratch);
        break;
      case ToolKind::kMeshopt:
        out.time_ms = lodbake::bench::median(own[t]);
        break;
    }
    const fs::path output = scratch / (stem + "." + setup.tools[t].name + ".glb");
    auto read = read_scene(output.string());
    if (!read.is_ok()) {
      out.error = "output unreadable: " + read.status().message();
      continue;
    }
    out.triangles = lodbake::summarize_scene(read.value()).instanced_triangles;
    score_output(asset, read.value(), setup, &out.score);
  }
  return result;
}

// Each tool rounds the target per primitive (or per mesh): a count above
// the exact ratio by at most one triangle per drawn primitive reaches it.
bool reached(const Asset& asset, const Case& c, const Result& r) {
  return r.error.empty() &&
         static_cast<double>(r.triangles) <=
             c.ratio * static_cast<double>(asset.triangles) + static_cast<double>(asset.primitives);
}

std::string number(double value, const char* format) {
  char text[32];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string score_text(const Result& r, double value, uint64_t samples, const char* format) {
  if (!r.score.measured) return "-";
  if (samples == 0) return "n/a";
  return number(value, format);
}

size_t tool_index(const Setup& setup, ToolKind kind) {
  for (size_t t = 0; t < setup.tools.size(); ++t)
    if (setup.tools[t].kind == kind) return t;
  return setup.tools.size();
}

// The three goals, as counts (lodbake against gltfpack -si, the
// peer it names first, and against any peer for the targets).
struct Goals {
  int targets_needed = 0, targets_met = 0;  // pairs where a peer reaches the target
  int quality_pairs = 0, quality_met = 0;   // pairs where lodbake and gltfpack -si are scored
  int time_assets = 0, time_met = 0;        // assets where both ran at every ratio
  bool have_gltfpack = false;
};

Goals evaluate_goals(const Setup& setup, const std::vector<Asset>& assets,
                     const std::vector<Case>& cases) {
  Goals goals;
  const size_t ours = tool_index(setup, ToolKind::kLodbake);
  const size_t gp = tool_index(setup, ToolKind::kGltfpack);
  goals.have_gltfpack = gp < setup.tools.size();
  if (ours >= setup.tools.size()) return goals;
  for (const Case& c : cases) {
    const Asset& asset = assets[c.asset];
    // lodbake reaches a target with its seams kept, or with --permissive
    // (lodbake-p) where a peer gets there by letting seams go (-sa).
    const size_t permissive = tool_index(setup, ToolKind::kLodbakePermissive);
    bool peer_reaches = false;
    for (size_t t = 0; t < setup.tools.size(); ++t)
      if (t != ours && t != permissive && reached(asset, c, c.results[t])) peer_reaches = true;
    if (peer_reaches) {
      ++goals.targets_needed;
      goals.targets_met +=
          reached(asset, c, c.results[ours]) ||
          (permissive < setup.tools.size() && reached(asset, c, c.results[permissive]));
    }
    if (!goals.have_gltfpack) continue;
    const Score& a = c.results[ours].score;
    const Score& b = c.results[gp].score;
    if (a.measured && b.measured) {
      ++goals.quality_pairs;
      // A stream is compared where both outputs have it (gltfpack drops a
      // TEXCOORD_0 no texture uses, c3d_spot's).
      const bool uv_ok = a.uv_samples == 0 || b.uv_samples == 0 || a.uv_p95 <= b.uv_p95;
      const bool normal_ok =
          a.normal_samples == 0 || b.normal_samples == 0 || a.normal_p95 <= b.normal_p95;
      goals.quality_met += uv_ok && normal_ok && a.hausdorff_relative <= b.hausdorff_relative;
    }
  }
  if (!goals.have_gltfpack) return goals;
  // Per asset, all ratios together.
  for (size_t i = 0; i < assets.size(); ++i) {
    double ours_ms = 0, gp_ms = 0;
    bool complete = false;
    for (const Case& c : cases) {
      if (c.asset != i) continue;
      complete = c.results[ours].error.empty() && c.results[gp].error.empty() &&
                 c.results[gp].time_ms >= 0;
      if (!complete) break;
      ours_ms += c.results[ours].time_ms;
      gp_ms += c.results[gp].time_ms;
    }
    if (!complete) continue;
    ++goals.time_assets;
    goals.time_met += ours_ms <= gp_ms;
  }
  return goals;
}

const char* met(bool yes) {
  return yes ? "met" : "NOT met";
}

void print_goals(const Goals& goals) {
  std::printf("goals (issue \"attribute-aware simplification\"):\n");
  std::printf("  reach every target a peer reaches: %d of %d asset-ratio pairs: %s\n",
              goals.targets_met, goals.targets_needed,
              met(goals.targets_met == goals.targets_needed));
  if (!goals.have_gltfpack) {
    std::printf("  (gltfpack not run: the quality and time goals are not evaluated)\n");
    return;
  }
  if (goals.quality_pairs == 0) {
    std::printf("  UV p95, normal p95 and Hausdorff <= gltfpack -si's: not scored\n");
  } else {
    std::printf(
        "  UV p95, normal p95 and Hausdorff <= gltfpack -si's in >= 4 of 5 pairs: %d of %d: %s\n",
        goals.quality_met, goals.quality_pairs,
        met(5 * goals.quality_met >= 4 * goals.quality_pairs));
  }
  std::printf("  wall time per asset (all ratios) <= gltfpack -si's: %d of %d assets: %s\n",
              goals.time_met, goals.time_assets, met(goals.time_met == goals.time_assets));
}

void print_table(const Setup& setup, const std::vector<Asset>& assets,
                 const std::vector<Case>& cases, const Goals& goals, bool markdown) {
  // The columns, in the plain layout or as a Markdown table for the docs.
  const char* head = markdown ? "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n"
                              : "%-32s %5s %-12s %7s %7s %-7s %9s %8s %8s %9s %9s %7s\n";
  const char* row = markdown ? "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n"
                             : "%-32s %5s %-12s %7s %7s %-7s %9s %8s %8s %9s %9s %7s\n";
  std::printf(head, "asset", "ratio", "tool", "target", "tris", "reached", "haus %", "uv p95",
              "nrm p95", "time ms", "process", "vs lb");
  if (markdown) std::printf("|---|---:|---|---:|---:|---|---:|---:|---:|---:|---:|---:|\n");
  const size_t ours = tool_index(setup, ToolKind::kLodbake);
  for (const Case& c : cases) {
    const Asset& asset = assets[c.asset];
    for (size_t t = 0; t < setup.tools.size(); ++t) {
      const Result& r = c.results[t];
      const std::string target = std::to_string(c.target);
      if (!r.error.empty()) {
        std::printf(row, name_of(asset.path).c_str(), ratio_text(c.ratio).c_str(),
                    setup.tools[t].name.c_str(), target.c_str(), "-", "failed", "-", "-", "-", "-",
                    "-", r.error.c_str());
        continue;
      }
      const Result* base = ours < setup.tools.size() ? &c.results[ours] : nullptr;
      const std::string versus =
          base && base->error.empty() && base->time_ms > 0 && r.time_ms >= 0 && t != ours
              ? number(r.time_ms / base->time_ms, "%.2fx")
              : "";
      std::printf(row, name_of(asset.path).c_str(), ratio_text(c.ratio).c_str(),
                  setup.tools[t].name.c_str(), target.c_str(), std::to_string(r.triangles).c_str(),
                  reached(asset, c, r) ? "yes" : "no",
                  r.score.measured ? number(100 * r.score.hausdorff_relative, "%.3f").c_str() : "-",
                  score_text(r, r.score.uv_p95, r.score.uv_samples, "%.5f").c_str(),
                  score_text(r, r.score.normal_p95, r.score.normal_samples, "%.2f").c_str(),
                  number(r.time_ms, "%.1f").c_str(), number(r.process_ms, "%.1f").c_str(),
                  versus.c_str());
      if (!r.score.error.empty()) std::printf("  (not scored: %s)\n", r.score.error.c_str());
    }
  }
  if (markdown) std::printf("\n");
  for (const Asset& asset : assets)
    if (!asset.error.empty())
      std::printf("left out: %s: %s\n", name_of(asset.path).c_str(), asset.error.c_str());
  std::printf(
      "target = ratio x the input's drawn triangles (each mesh once per node); reached = at most\n"
      "one triangle per drawn primitive above the exact ratio; haus %% = symmetric Hausdorff, %% "
      "of the\n"
      "input's diagonal; uv p95 in UV units, nrm p95 in degrees (n/a: the input or the output has "
      "none);\n"
      "time ms: lodbake's process (median), gltfpack's pack in one warm node process (best),\n"
      "meshopt's script from read to written (median); process = the whole subprocess\n"
      "(median); vs lb = time / lodbake's time (above 1: lodbake is faster); %d run(s),\n"
      "%llu area samples per side\n",
      setup.runs, static_cast<unsigned long long>(setup.samples));
  if (setup.gltfpack_startup_ms >= 0)
    std::printf("node start-up: %.1f ms; gltfpack start-up (node cli.js -v): %.1f ms\n",
                setup.node_startup_ms, setup.gltfpack_startup_ms);
  if (!setup.note.empty()) std::printf("note: %s\n", setup.note.c_str());
#ifndef LODBAKE_BENCH_WITH_SCORING
  std::printf(
      "note: built without lib/metrics/attribute_deviation.cpp: no scores (rebuild once the "
      "metric is in)\n");
#endif
  print_goals(goals);
}

nlohmann::json ms_json(double ms) {
  return ms < 0 ? nlohmann::json() : nlohmann::json(ms);
}

void print_json(const Setup& setup, const std::vector<Asset>& assets,
                const std::vector<Case>& cases, const Goals& goals) {
  nlohmann::json out;
  out["runs"] = setup.runs;
  out["area_samples"] = setup.samples;
  out["node_startup_ms"] = ms_json(setup.node_startup_ms);
  out["gltfpack_startup_ms"] = ms_json(setup.gltfpack_startup_ms);
#ifdef LODBAKE_BENCH_WITH_SCORING
  out["scored"] = true;
#else
  out["scored"] = false;
#endif
  if (!setup.note.empty()) out["note"] = setup.note;
  out["assets"] = nlohmann::json::array();
  for (const Asset& asset : assets) {
    nlohmann::json item = {{"asset", name_of(asset.path)},
                           {"path", asset.path},
                           {"triangles", asset.triangles},
                           {"primitives", asset.primitives}};
    if (!asset.error.empty()) item["error"] = asset.error;
    out["assets"].push_back(item);
  }
  out["cases"] = nlohmann::json::array();
  for (const Case& c : cases) {
    nlohmann::json item = {
        {"asset", name_of(assets[c.asset].path)}, {"ratio", c.ratio}, {"target", c.target}};
    for (size_t t = 0; t < setup.tools.size(); ++t) {
      const Result& r = c.results[t];
      nlohmann::json tool;
      if (!r.error.empty()) {
        tool["error"] = r.error;
      } else {
        tool["triangles"] = r.triangles;
        tool["reached"] = reached(assets[c.asset], c, r);
        tool["time_ms"] = r.time_ms;
        tool["process_ms"] = r.process_ms;
        if (r.score.measured) {
          tool["hausdorff_relative"] = r.score.hausdorff_relative;
          tool["uv_p95"] = r.score.uv_samples ? nlohmann::json(r.score.uv_p95) : nlohmann::json();
          tool["normal_p95_degrees"] =
              r.score.normal_samples ? nlohmann::json(r.score.normal_p95) : nlohmann::json();
        } else if (!r.score.error.empty()) {
          tool["score_error"] = r.score.error;
        }
      }
      item[setup.tools[t].name] = tool;
    }
    out["cases"].push_back(item);
  }
  out["goals"] = {{"targets_met", goals.targets_met}, {"targets_needed", goals.targets_needed},
                  {"quality_met", goals.quality_met}, {"quality_pairs", goals.quality_pairs},
                  {"time_met", goals.time_met},       {"time_assets", goals.time_assets}};
  std::printf("%s\n", out.dump(2).c_str());
}

// --check: every tool wrote a readable output on every case, with
// triangles, scored when the metric is built in, and within
// `max_hausdorff` of the input (relative; a bound that catches an output
// whose streams were scrambled on the way, not a quality goal).
bool check_rows(const Setup& setup, const std::vector<Asset>& assets,
                const std::vector<Case>& cases, double max_hausdorff) {
  bool ok = !cases.empty();
  if (cases.empty()) std::fprintf(stderr, "check: no asset gave a row\n");
  for (const Case& c : cases) {
    for (size_t t = 0; t < setup.tools.size(); ++t) {
      const Result& r = c.results[t];
      std::string problem = r.error;
      if (problem.empty() && r.triangles == 0) problem = "no triangles in the output";
      if (problem.empty() && r.triangles > assets[c.asset].triangles)
        problem = "more triangles than the input";
#ifdef LODBAKE_BENCH_WITH_SCORING
      if (problem.empty() && !r.score.measured) problem = "not scored: " + r.score.error;
      if (problem.empty() && r.score.hausdorff_relative > max_hausdorff)
        problem = "Hausdorff " + number(100 * r.score.hausdorff_relative, "%.2f") +
                  "% of the diagonal, above --max-hausdorff";
#else
      (void)max_hausdorff;
#endif
      if (problem.empty()) continue;
      ok = false;
      std::fprintf(stderr, "check: %s at %s, %s: %s\n", name_of(assets[c.asset].path).c_str(),
                   ratio_text(c.ratio).c_str(), setup.tools[t].name.c_str(), problem.c_str());
    }
  }
  return ok;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

int usage_error(const std::string& message) {
  std::fprintf(
      stderr,
      "Error: %s\nusage: bench_attributes [--ratios 0.5,0.25,0.1] [--runs N] [--samples N] "
      "[--threads N] [--quick] [--tools LIST] [--json] [--markdown] [--check] [--max-hausdorff H] "
      "[--require-peers] "
      "[--keep DIR] [--lodbake PATH] [--node PATH] [--npm DIR] ASSET...\n",
      message.c_str());
  return 1;
}

double median_command_ms(const std::vector<std::string>& argv, const fs::path& log, int runs) {
  std::vector<double> times;
  for (int r = 0; r < runs; ++r) {
    const lodbake::bench::ToolRun run = lodbake::bench::run_tool(argv, log.string());
    if (run.exit_status != 0) return -1;
    times.push_back(1e3 * run.wall_seconds);
  }
  return lodbake::bench::median(times);
}

}  // namespace

int main(int argc, char** argv) {
  Setup setup;
  setup.lodbake = LODBAKE_BENCH_SIMPLIFY;
  setup.node = LODBAKE_BENCH_NODE;
  setup.npm = LODBAKE_BENCH_NPM_DIR;
  setup.script = LODBAKE_BENCH_MESHOPT_SCRIPT;
  setup.gltfpack_script = LODBAKE_BENCH_GLTFPACK_SCRIPT;
  std::vector<std::string> tool_names;
  bool json = false, markdown = false, check = false, require_peers = false;
  double max_hausdorff = 1e300;
  std::string keep;
  std::vector<Asset> assets;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--ratios" && has_value) {
      setup.ratios.clear();
      for (const std::string& item : split_list(argv[++i])) {
        const double ratio = std::atof(item.c_str());
        if (!(ratio > 0 && ratio <= 1)) return usage_error("a ratio must be in (0, 1]: " + item);
        setup.ratios.push_back(ratio);
      }
    } else if (arg == "--runs" && has_value) {
      setup.runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--samples" && has_value) {
      setup.samples = std::max<uint64_t>(1000, std::strtoull(argv[++i], nullptr, 10));
    } else if (arg == "--threads" && has_value) {
      setup.threads = static_cast<unsigned>(std::max(0, std::atoi(argv[++i])));
    } else if (arg == "--quick") {
      setup.runs = 1;
      setup.samples = 20000;
    } else if (arg == "--tools" && has_value) {
      tool_names = split_list(argv[++i]);
    } else if (arg == "--json") {
      json = true;
    } else if (arg == "--markdown") {
      markdown = true;
    } else if (arg == "--check") {
      check = true;
    } else if (arg == "--max-hausdorff" && has_value) {
      max_hausdorff = std::atof(argv[++i]);
    } else if (arg == "--require-peers") {
      require_peers = true;
    } else if (arg == "--keep" && has_value) {
      keep = argv[++i];
    } else if (arg == "--lodbake" && has_value) {
      setup.lodbake = argv[++i];
    } else if (arg == "--node" && has_value) {
      setup.node = argv[++i];
    } else if (arg == "--npm" && has_value) {
      setup.npm = argv[++i];
    } else if (arg.rfind("--", 0) == 0) {
      return usage_error("unknown option or missing value: " + arg);
    } else {
      assets.push_back({arg, {}, {}, {}, 0, 0});
    }
  }
  if (assets.empty()) return usage_error("no asset given");
  for (const Tool& tool : all_tools())
    if (tool_names.empty() ||
        std::find(tool_names.begin(), tool_names.end(), tool.name) != tool_names.end())
      setup.tools.push_back(tool);
  if (setup.tools.size() != (tool_names.empty() ? all_tools().size() : tool_names.size()))
    return usage_error("--tools takes lodbake, lodbake-p, gltfpack-si, gltfpack-sa, meshopt");

  // The peers need node and the npm packages; without them their rows go.
  const fs::path modules = fs::path(setup.npm) / "node_modules";
  std::string missing;
  if (setup.node.empty() || !lodbake::bench::tool_installed(setup.node))
    missing = "node not found";
  else if (!fs::exists(modules / "gltfpack" / "cli.js") ||
           !fs::exists(modules / "meshoptimizer" / "meshopt_simplifier.js") ||
           !fs::exists(modules / "@gltf-transform" / "core") ||
           !fs::exists(modules / "@gltf-transform" / "extensions"))
    missing = "the npm tools are not installed in " + setup.npm + " (make npm-deps)";
  if (!missing.empty()) {
    if (require_peers) {
      std::printf("skipped: %s\n", missing.c_str());
      return 77;
    }
    setup.note = "peers not run: " + missing;
    setup.tools.erase(std::remove_if(setup.tools.begin(), setup.tools.end(),
                                     [](const Tool& t) {
                                       return t.kind != ToolKind::kLodbake &&
                                              t.kind != ToolKind::kLodbakePermissive;
                                     }),
                      setup.tools.end());
  }
  if (tool_index(setup, ToolKind::kLodbake) < setup.tools.size() &&
      !lodbake::bench::tool_installed(setup.lodbake)) {
    std::fprintf(stderr, "Error: %s is not built\n", setup.lodbake.c_str());
    return 2;
  }

  fs::path scratch;
  if (keep.empty()) {
    std::string name = (fs::temp_directory_path() / "bench_attributes.XXXXXX").string();
    if (!::mkdtemp(name.data())) {
      std::fprintf(stderr, "Error: cannot create a scratch folder\n");
      return 2;
    }
    scratch = name;
  } else {
    scratch = keep;
    std::error_code error;
    fs::create_directories(scratch, error);
  }

  if (setup.note.empty()) {
    setup.node_startup_ms =
        median_command_ms({setup.node, "-e", ""}, scratch / "node.log", setup.runs);
    setup.gltfpack_startup_ms =
        median_command_ms({setup.node, (modules / "gltfpack" / "cli.js").string(), "-v"},
                          scratch / "gltfpack.log", setup.runs);
  }

  std::vector<Case> cases;
  for (size_t i = 0; i < assets.size(); ++i) {
    prepare_asset(&assets[i], scratch, i);
    if (!assets[i].error.empty()) continue;
    for (double ratio : setup.ratios) {
      cases.push_back(run_case(setup, assets, i, ratio, scratch));
      if (!json)
        std::fprintf(stderr, "bench_attributes: %s at %s done\n", name_of(assets[i].path).c_str(),
                     ratio_text(ratio).c_str());
    }
  }
  const Goals goals = evaluate_goals(setup, assets, cases);
  if (json)
    print_json(setup, assets, cases, goals);
  else
    print_table(setup, assets, cases, goals, markdown);
  if (keep.empty()) {
    std::error_code error;
    fs::remove_all(scratch, error);
  }
  return check && !check_rows(setup, assets, cases, max_hausdorff) ? 1 : 0;
}
