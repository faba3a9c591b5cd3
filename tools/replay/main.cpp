// lodbake-replay: replays a camera path on a container's view-dependent
// structure and measures it (issue 8). Mode vhier: BASE + VHIE + RFIN, the
// SelectiveRefiner adapted per frame (lib/replay/vhier_replay.h); mode dag:
// BASE + VSPL + DAGE, MANAGE-TRAVERSAL (lib/replay/dag_replay.h). Mode sets
// is not camera-driven: BASE + VSPL + SETS, the strip paper's LoD-recovery
// tests (lib/replay/sets_replay.h), one step per LoD recovered; it runs
// through run_sets(), the camera modes through run_camera_path(). Thin:
// decoding lives in formats/, the runtime in lib/replay.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "formats/container/container_reader.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/dage.h"
#include "formats/sections/rfin.h"
#include "formats/sections/sets.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/support/file_io.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/dag_replay.h"
#include "lib/replay/sets_replay.h"
#include "lib/replay/vhier_replay.h"
#include "tools/common/cli.h"

namespace lodbake::cli {
namespace {

constexpr const char* kReplaySchema = "lodbake.replay/1";

struct Request {
  std::string input;
  std::string mode = "vhier";
  std::string path = "scan";
  std::string csv;
  float fov_degrees = 60;
  bool validate = false;
  VhierReplayOptions options;
  DagReplayOptions dag;
  // Mode sets.
  std::vector<double> percents = paper_recovery_percents();
  std::string spacing = "both";
};

// One frame's measures in either mode: `front` is the vertex front (vhier)
// or |Fs| (dag), `collapse_front` |Fc| (dag only).
struct Row {
  size_t splits = 0;
  size_t collapses = 0;
  size_t passes = 0;
  size_t front = 0;
  size_t collapse_front = 0;
  size_t triangles = 0;
  double ms = 0;
};

// A loaded structure, stepped one camera at a time.
struct Session {
  BoundingSphere sphere;
  nlohmann::json structure;
  std::string structure_text;
  std::function<Result<Row>(const CameraFrame&)> step;
  std::function<std::vector<std::string>()> check;
};

struct VhierState {
  VertexHierarchy h;
  std::vector<NodeRefinement> data;
  std::optional<SelectiveRefiner> refiner;
};

struct DagState {
  ProgressiveMesh pm;
  VsplitDag dag;
  std::optional<DagReplay> replay;
};

Result<Session> load_vhier(const Container& container, const Section& base,
                           const Request& request) {
  const Section* vhie = container.find(kVhieTag);
  const Section* rfin = container.find(kRfinTag);
  if (vhie == nullptr || rfin == nullptr) {
    return invalid_input(std::string("container has no ") + (vhie == nullptr ? "VHIE" : "RFIN") +
                         " section; mode vhier needs BASE + VHIE + RFIN (lodbake-hierarchy "
                         "--sections vhie)");
  }
  auto state = std::make_shared<VhierState>();
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh base_mesh, decode_base(base.data, base.size));
  LODBAKE_ASSIGN_OR_RETURN(state->h, decode_vhie(vhie->data, vhie->size, std::move(base_mesh)));
  LODBAKE_ASSIGN_OR_RETURN(state->data, decode_rfin(rfin->data, rfin->size, state->h));
  LODBAKE_ASSIGN_OR_RETURN(SelectiveRefiner refiner, SelectiveRefiner::create(state->h));
  state->refiner.emplace(std::move(refiner));
  const VertexHierarchy& h = state->h;
  Session session;
  session.sphere = bounding_sphere(h.position);
  session.structure = {{"nodes", h.node_count()},
                       {"roots", h.root_count()},
                       {"base_triangles", h.base.triangle_count()}};
  session.structure_text = std::to_string(h.node_count()) + " nodes, " +
                           std::to_string(h.root_count()) + " roots, " +
                           std::to_string(h.base.triangle_count()) + " base triangles";
  const VhierReplayOptions options = request.options;
  const BoundingSphere sphere = session.sphere;
  session.step = [state, options, sphere](const CameraFrame& frame) -> Result<Row> {
    LODBAKE_ASSIGN_OR_RETURN(
        VhierFrameStats f,
        adapt_vhier_frame(&*state->refiner, state->h, state->data, sphere, frame, options));
    Row row;
    row.splits = f.splits;
    row.collapses = f.collapses;
    row.passes = f.passes;
    row.front = f.front_size;
    row.triangles = f.triangles;
    row.ms = f.adapt_ms;
    return row;
  };
  session.check = [state] { return check_vhier_mesh(*state->refiner); };
  return session;
}

Result<Session> load_dag(const Container& container, const Section& base, const Request& request) {
  const Section* vspl = container.find(kVsplTag);
  const Section* dage = container.find(kDageTag);
  if (vspl == nullptr || dage == nullptr) {
    return invalid_input(std::string("container has no ") + (vspl == nullptr ? "VSPL" : "DAGE") +
                         " section; mode dag needs BASE + VSPL + DAGE (lodbake-hierarchy "
                         "--sections dage)");
  }
  auto state = std::make_shared<DagState>();
  LODBAKE_ASSIGN_OR_RETURN(state->pm,
                           decode_progressive_mesh(base.data, base.size, vspl->data, vspl->size));
  LODBAKE_ASSIGN_OR_RETURN(state->dag, decode_dage(dage->data, dage->size));
  LODBAKE_ASSIGN_OR_RETURN(DagReplay replay, DagReplay::create(state->pm, state->dag));
  state->replay.emplace(std::move(replay));
  std::vector<Vec3f> points = state->pm.base.positions;
  for (const VertexSplit& split : state->pm.splits)
    points.push_back(split.vt_position);
  Session session;
  session.sphere = bounding_sphere(points);
  session.structure = {{"nodes", state->dag.node_count()},
                       {"edges", state->dag.edge_count()},
                       {"base_triangles", state->pm.base.triangle_count()}};
  session.structure_text = std::to_string(state->dag.node_count()) + " nodes, " +
                           std::to_string(state->dag.edge_count()) + " edges, " +
                           std::to_string(state->pm.base.triangle_count()) + " base triangles";
  const DagReplayOptions options = request.dag;
  const BoundingSphere sphere = session.sphere;
  session.step = [state, options, sphere](const CameraFrame& frame) -> Result<Row> {
    LODBAKE_ASSIGN_OR_RETURN(DagFrameStats f, state->replay->adapt(sphere, frame, options));
    Row row;
    row.splits = f.splits;
    row.collapses = f.collapses;
    row.front = f.split_front;
    row.collapse_front = f.collapse_front;
    row.triangles = f.triangles;
    row.ms = f.traversal_ms;
    return row;
  };
  session.check = [state] { return state->replay->check(); };
  return session;
}

// The camera modes' structure.
Result<Session> load(const Bytes& bytes, const Request& request) {
  LODBAKE_ASSIGN_OR_RETURN(Container container, read_container(bytes.data(), bytes.size()));
  LODBAKE_ASSIGN_OR_RETURN(const Section* base, container.require(kBaseTag));
  try {
    if (request.mode == "dag") return load_dag(container, *base, request);
    return load_vhier(container, *base, request);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory loading the container");
  }
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int run_camera_path(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<Session> loaded = load(bytes, request);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  const Session& session = loaded.value();
  const bool dag = request.mode == "dag";

  std::vector<CameraFrame> path;
  if (request.path == "scan" || request.path == "orbit") {
    path = builtin_path(request.path, session.sphere, request.fov_degrees).value();
  } else {
    Result<Bytes> path_bytes = read_file(request.path, uint64_t{1} << 30);
    if (!path_bytes.is_ok()) return tool.fail(request.path, path_bytes.status());
    Result<std::vector<CameraFrame>> parsed =
        parse_camera_path_csv(path_bytes.value().data(), path_bytes.value().size());
    if (!parsed.is_ok()) return tool.fail(request.path, parsed.status());
    path = std::move(parsed).value();
  }

  std::vector<Row> frames;
  frames.reserve(path.size());
  Progress progress(tool, "replaying");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<Row> row = session.step(path[i]);
    if (!row.is_ok()) {
      return tool.fail(request.input,
                       Status(row.status().kind(),
                              "frame " + std::to_string(i) + ": " + row.status().message()));
    }
    frames.push_back(row.value());
    if (request.validate) {
      const std::vector<std::string> problems = session.check();
      if (!problems.empty()) {
        std::string message = "frame " + std::to_string(i) + ": invalid mesh: " + problems[0];
        for (size_t k = 1; k < problems.size(); ++k)
          message += "; " + problems[k];
        return tool.fail(request.input, Status(ErrorKind::kValidation, message));
      }
    }
    progress.update(static_cast<double>(i + 1) / path.size());
  }

  if (!request.csv.empty()) {
    std::ostringstream csv;
    csv << (dag ? "frame,splits,collapses,fs,fc,triangles,traversal_ms\n"
                : "frame,splits,collapses,passes,front,triangles,adapt_ms\n");
    for (size_t i = 0; i < frames.size(); ++i) {
      const Row& f = frames[i];
      csv << i << ',' << f.splits << ',' << f.collapses << ',' << (dag ? f.front : f.passes) << ','
          << (dag ? f.collapse_front : f.front) << ',' << f.triangles << ',' << f.ms << '\n';
    }
    Status written = write_file_atomic(request.csv, csv.str());
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  size_t splits = 0, collapses = 0, max_front = 0, max_fc = 0, max_triangles = 0;
  size_t pass_limited = 0;
  double front_sum = 0, fc_sum = 0, triangle_sum = 0, ms_sum = 0, ms_max = 0;
  std::vector<double> ms;
  for (const Row& f : frames) {
    splits += f.splits;
    collapses += f.collapses;
    max_front = std::max(max_front, f.front);
    max_fc = std::max(max_fc, f.collapse_front);
    max_triangles = std::max(max_triangles, f.triangles);
    front_sum += static_cast<double>(f.front);
    fc_sum += static_cast<double>(f.collapse_front);
    triangle_sum += static_cast<double>(f.triangles);
    ms_sum += f.ms;
    ms_max = std::max(ms_max, f.ms);
    ms.push_back(f.ms);
    if (!dag && f.passes >= request.options.max_passes) ++pass_limited;
  }
  const double n = static_cast<double>(frames.size());
  nlohmann::json report = {{"schema", kReplaySchema},
                           {"input", request.input},
                           {"mode", request.mode},
                           {"path", request.path},
                           {"frames", frames.size()},
                           {"validated", request.validate},
                           {"viewport",
                            {{"width", request.options.viewport.width},
                             {"height", request.options.viewport.height},
                             {"fov_degrees", request.fov_degrees},
                             {"near_fraction", request.options.viewport.near_fraction}}},
                           {"tolerance_pixels", request.options.tolerance_pixels},
                           {dag ? "dag" : "hierarchy", session.structure},
                           {"splits", splits},
                           {"collapses", collapses},
                           {"triangles", {{"mean", triangle_sum / n}, {"max", max_triangles}}}};
  const nlohmann::json timing = {{"mean", ms_sum / n}, {"median", median(ms)}, {"max", ms_max}};
  if (dag) {
    report["traversal"] = "priority-oriented";
    report["budget_mode"] = true;
    report["max_changes"] = request.dag.max_changes;
    report["triangle_budget"] = request.dag.triangle_budget;
    report["split_front"] = {{"mean", front_sum / n}, {"max", max_front}};
    report["collapse_front"] = {{"mean", fc_sum / n}, {"max", max_fc}};
    report["traversal_ms"] = timing;
  } else {
    report["front_size"] = {{"mean", front_sum / n}, {"max", max_front}};
    report["adapt_ms"] = timing;
    report["frames_at_pass_limit"] = pass_limited;
  }
  if (tool.json()) {
    tool.print_json(report);
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode " << request.mode << ", path "
            << request.path << ", " << frames.size() << " frames"
            << (request.validate ? ", every frame validated" : "") << "\n";
  std::cout << (dag ? "dag           " : "hierarchy     ") << session.structure_text << "\n";
  std::cout << "view          " << request.options.viewport.width << "x"
            << request.options.viewport.height << ", fov " << request.fov_degrees
            << " deg, tolerance " << request.options.tolerance_pixels << " px\n";
  if (dag) {
    std::cout << "traversal     priority-oriented, budget " << request.dag.triangle_budget
              << " triangles, at most " << request.dag.max_changes << " changes per frame\n";
  }
  std::cout << "operations    " << splits << " splits, " << collapses << " collapses\n";
  if (dag) {
    std::cout << "fronts        |Fs| mean " << front_sum / n << ", max " << max_front
              << "; |Fc| mean " << fc_sum / n << ", max " << max_fc << "\n";
  } else {
    std::cout << "front size    mean " << front_sum / n << ", max " << max_front << "\n";
  }
  std::cout << "triangles     mean " << triangle_sum / n << ", max " << max_triangles << "\n";
  std::cout << (dag ? "frame time    " : "adapt time    ") << "mean " << ms_sum / n
            << " ms, median " << median(ms) << " ms, max " << ms_max << " ms per frame\n";
  if (pass_limited != 0) {
    std::cout << "pass limit    " << pass_limited << " frames stopped at "
              << request.options.max_passes << " passes\n";
  }
  return 0;
}

// Mode sets: the progressive mesh and its SETS graph.
struct SetsData {
  ProgressiveMesh pm;
  SetsGraph graph;
};

Result<SetsData> load_sets(const Bytes& bytes) {
  LODBAKE_ASSIGN_OR_RETURN(Container container, read_container(bytes.data(), bytes.size()));
  LODBAKE_ASSIGN_OR_RETURN(const Section* base, container.require(kBaseTag));
  const Section* vspl = container.find(kVsplTag);
  const Section* sets = container.find(kSetsTag);
  if (vspl == nullptr || sets == nullptr) {
    return invalid_input(std::string("container has no ") + (vspl == nullptr ? "VSPL" : "SETS") +
                         " section; mode sets needs BASE + VSPL + SETS (lodbake-strips)");
  }
  try {
    SetsData data;
    LODBAKE_ASSIGN_OR_RETURN(
        data.pm, decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size));
    LODBAKE_ASSIGN_OR_RETURN(data.graph, decode_sets(sets->data, sets->size));
    return data;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory loading the container");
  }
}

std::string percent_text(double percent) {
  std::ostringstream out;
  out << percent;
  return out.str();
}

// The recovery tests: every (spacing, percent), linear first, each from LoD
// 0 to the coarsest LoD and back.
int run_sets(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<SetsData> loaded = load_sets(bytes);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  const SetsData& data = loaded.value();
  Result<SetsReplay> created = SetsReplay::create(data.pm, data.graph);
  if (!created.is_ok()) return tool.fail(request.input, created.status());
  SetsReplay& replay = created.value();

  std::vector<LodSpacing> spacings;
  if (request.spacing != "exponential") spacings.push_back(LodSpacing::kLinear);
  if (request.spacing != "linear") spacings.push_back(LodSpacing::kExponential);
  std::vector<SetsTestSummary> summaries;
  std::ostringstream csv;
  csv << "spacing,percent,step,lod,strips,indices,triangles,fresh_us,coherent_us\n";
  size_t recovered = 0;
  Progress progress(tool, "recovering");
  const size_t tests = spacings.size() * request.percents.size();
  for (LodSpacing spacing : spacings) {
    for (double percent : request.percents) {
      const std::vector<uint32_t> lods = recovery_test_lods(replay.lod_count(), percent, spacing);
      Result<std::vector<SetsStep>> steps = run_sets_test(&replay, lods, request.validate);
      if (!steps.is_ok()) {
        return tool.fail(request.input,
                         Status(steps.status().kind(), std::string(spacing_name(spacing)) + " " +
                                                           percent_text(percent) + "%, " +
                                                           steps.status().message()));
      }
      summaries.push_back(summarize_sets_test(spacing, percent, steps.value()));
      recovered += steps.value().size();
      if (!request.csv.empty()) {
        for (size_t k = 0; k < steps.value().size(); ++k) {
          const SetsStep& step = steps.value()[k];
          csv << spacing_name(spacing) << ',' << percent << ',' << k << ',' << step.lod << ','
              << step.strips << ',' << step.indices << ',' << step.triangles << ',' << step.fresh_us
              << ',' << step.coherent_us << '\n';
        }
      }
      progress.update(static_cast<double>(summaries.size()) / tests);
    }
  }
  if (!request.csv.empty()) {
    Status written = write_file_atomic(request.csv, csv.str());
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  const SetsGraph& graph = data.graph;
  if (tool.json()) {
    nlohmann::json rows = nlohmann::json::array();
    for (const SetsTestSummary& t : summaries) {
      rows.push_back({{"spacing", spacing_name(t.spacing)},
                      {"percent", t.percent},
                      {"lods", t.lods},
                      {"indices", t.indices},
                      {"fresh_us_per_lod", t.fresh_us_per_lod},
                      {"coherent_us_per_lod", t.coherent_us_per_lod},
                      {"fresh_mindices_per_s", t.fresh_mindices_per_s},
                      {"coherent_mindices_per_s", t.coherent_mindices_per_s}});
    }
    tool.print_json({{"schema", kReplaySchema},
                     {"input", request.input},
                     {"mode", request.mode},
                     {"validated", request.validate},
                     {"sets",
                      {{"strips", graph.strip_count()},
                       {"nodes", graph.node_count()},
                       {"lods", graph.lod_count},
                       {"base_triangles", data.pm.base.triangle_count()}}},
                     {"spacing", request.spacing},
                     {"percents", request.percents},
                     {"lods_recovered", recovered},
                     {"timing", "steady_clock, recovery alone"},
                     {"tests", rows}});
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode sets, " << summaries.size()
            << " recovery tests, " << recovered << " LoDs recovered"
            << (request.validate ? ", every LoD validated" : "") << "\n";
  std::cout << "sets          " << graph.strip_count() << " strips, " << graph.node_count()
            << " nodes over " << graph.lod_count << " LoDs, " << data.pm.base.triangle_count()
            << " base triangles\n";
  std::cout
      << "tests         LoD 0 to the coarsest and back; recovery alone (steady_clock): fresh\n"
         "              recover() and coherent recover_coherent() at every LoD\n\n";
  char line[160];
  std::snprintf(line, sizeof line, "%-12s %7s %7s %14s %17s %15s %18s\n", "spacing", "percent",
                "LoDs", "fresh us/LoD", "coherent us/LoD", "fresh M idx/s", "coherent M idx/s");
  std::cout << line;
  for (const SetsTestSummary& t : summaries) {
    std::snprintf(line, sizeof line, "%-12s %6s%% %7zu %14.1f %17.1f %15.1f %18.1f\n",
                  spacing_name(t.spacing), percent_text(t.percent).c_str(), t.lods,
                  t.fresh_us_per_lod, t.coherent_us_per_lod, t.fresh_mindices_per_s,
                  t.coherent_mindices_per_s);
    std::cout << line;
  }
  return 0;
}

int run(const Tool& tool, const Request& request) {
  Result<Bytes> bytes = read_file(request.input);
  if (!bytes.is_ok()) return tool.fail(request.input, bytes.status());
  if (request.mode == "sets") return run_sets(tool, request, bytes.value());
  return run_camera_path(tool, request, bytes.value());
}

// "1,3,6" -> {1, 3, 6}: percentages in (0, 100].
Result<std::vector<double>> parse_percents(const std::string& text) {
  std::vector<double> percents;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double p = std::strtod(item.c_str(), &end);
    if (item.empty() || end == nullptr || *end != '\0' || !(p > 0 && p <= 100))
      return Status(
          ErrorKind::kUsage,
          "--percent takes percentages in (0, 100] separated by commas, not '" + item + "'");
    percents.push_back(p);
  }
  if (percents.empty()) return Status(ErrorKind::kUsage, "--percent needs at least one percentage");
  return percents;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  Tool tool("lodbake-replay", "FILE.lbk [--mode vhier|dag|sets] [--path scan|orbit|FILE] [options]",
            "Replays a camera path on a container's view-dependent structure and reports,\n"
            "per frame, the refinement operations, fronts, triangles and adapt time; or\n"
            "(mode sets) runs the SETS strip paper's LoD-recovery tests.\n"
            "Mode vhier (default): BASE + VHIE + RFIN from lodbake-hierarchy; the vertex\n"
            "front is refined while a node's bounding sphere meets the view frustum, its\n"
            "normal cone is not entirely back-facing and its deviation projects to more than\n"
            "--tolerance pixels, and coarsened where none holds (Hoppe 1997).\n"
            "Mode dag: BASE + VSPL + DAGE from lodbake-hierarchy; MANAGE-TRAVERSAL (Zheng &\n"
            "Chan 2006) with the priority-oriented traversal in budget mode: splits by\n"
            "projected error over --tolerance within --budget triangles, at most --changes\n"
            "splits + collapses per frame.\n"
            "Mode sets: BASE + VSPL + SETS from lodbake-strips; not camera-driven (no --path\n"
            "or view options): each test recovers --percent of all LoDs, spaced linearly or\n"
            "exponentially (--spacing), from LoD 0 (the full mesh) to the coarsest and back,\n"
            "each LoD with a fresh and a coherent recovery timed alone (Belmonte et al. 2006).\n"
            "Paths: 'scan' (180 frames: approach the model, then rise from its bottom to its\n"
            "top), 'orbit' (194 frames: approach, then circle it twice, speeding up), both\n"
            "relative to the bounding sphere, or a CSV FILE with one row per frame:\n"
            "eye x,y,z, target x,y,z, up x,y,z, vertical fov in degrees ('#' comments).");
  Request request;
  uint32_t width = 1024, height = 768;
  float near_fraction = 0.01f;
  tool.options().add_options()("mode", po::value<std::string>(&request.mode)->value_name("M"),
                               "the structure replayed: vhier (default), dag or sets")(
      "path", po::value<std::string>(&request.path)->value_name("P"),
      "scan (default), orbit, or a CSV camera path FILE")(
      "tolerance", po::value<float>(&request.options.tolerance_pixels)->value_name("PIXELS"),
      "screen-space error tolerance in pixels of the viewport height (default 1)")(
      "width", po::value<uint32_t>(&width)->value_name("W"), "viewport width (default 1024)")(
      "height", po::value<uint32_t>(&height)->value_name("H"), "viewport height (default 768)")(
      "fov", po::value<float>(&request.fov_degrees)->value_name("DEG"),
      "vertical fov of the built-in paths (default 60)")(
      "near", po::value<float>(&near_fraction)->value_name("F"),
      "near plane at F times the bounding-sphere radius (default 0.01)")(
      "validate", po::bool_switch(&request.validate),
      "after every frame, check that the mesh is an edge-manifold, consistently oriented "
      "triangulation without duplicate triangles and the counters agree (exit 7 naming "
      "the frame otherwise); sets: after every LoD, that the strips' triangles are the "
      "progressive mesh's at that LoD with their orientation, form such a triangulation "
      "and coherent recovery equals fresh recovery (exit 7 naming the LoD)")(
      "csv", po::value<std::string>(&request.csv)->value_name("FILE"),
      "write per-frame rows (frame, splits, collapses, passes, front, triangles, "
      "adapt_ms) to FILE; sets: per-LoD rows (spacing, percent, step, lod, strips, "
      "indices, triangles, fresh_us, coherent_us)");
  tool.options().add_options()("budget",
                               po::value<size_t>(&request.dag.triangle_budget)->value_name("T"),
                               "dag: triangle budget (default 60000)")(
      "changes", po::value<size_t>(&request.dag.max_changes)->value_name("N"),
      "dag: at most N splits + collapses per frame (default 300)");
  std::string percents;
  tool.options().add_options()("percent", po::value<std::string>(&percents)->value_name("LIST"),
                               "sets: percentages of all LoDs each test recovers (default "
                               "1,3,6,10,15,20, the paper's)")(
      "spacing", po::value<std::string>(&request.spacing)->value_name("S"),
      "sets: linear, exponential or both (default)");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("input", "FILE.lbk", &request.input))
    return *code;
  if (request.mode != "vhier" && request.mode != "dag" && request.mode != "sets") {
    return tool.usage_error("--mode '" + request.mode +
                            "' is not available (modes: vhier, dag, sets)");
  }
  // Each option belongs to the camera modes or to mode sets; one given to
  // the other kind is refused rather than silently ignored.
  const bool sets = request.mode == "sets";
  for (const char* option : {"path", "tolerance", "width", "height", "fov", "near", "budget",
                             "changes", "percent", "spacing"}) {
    const bool sets_option = std::string(option) == "percent" || std::string(option) == "spacing";
    if (tool.has(option) && sets_option != sets) {
      return tool.usage_error("--" + std::string(option) + " does not apply to --mode " +
                              request.mode +
                              (sets ? " (its steps are LoDs, not camera frames)" : ""));
    }
  }
  if (tool.has("percent")) {
    Result<std::vector<double>> parsed = parse_percents(percents);
    if (!parsed.is_ok()) return tool.usage_error(parsed.status().message());
    request.percents = parsed.value();
  }
  if (request.spacing != "linear" && request.spacing != "exponential" && request.spacing != "both")
    return tool.usage_error("--spacing takes linear, exponential or both, not '" + request.spacing +
                            "'");
  if (request.dag.max_changes == 0) return tool.usage_error("--changes takes N >= 1");
  if (!(request.options.tolerance_pixels > 0 && std::isfinite(request.options.tolerance_pixels)))
    return tool.usage_error("--tolerance takes pixels > 0");
  if (width == 0 || height == 0 || width > 65536 || height > 65536)
    return tool.usage_error("--width and --height take 1 .. 65536 pixels");
  if (!(request.fov_degrees > 0 && request.fov_degrees < 180))
    return tool.usage_error("--fov takes degrees in (0, 180)");
  if (!(near_fraction > 0 && near_fraction < 1))
    return tool.usage_error("--near takes a fraction in (0, 1)");
  request.options.viewport.width = width;
  request.options.viewport.height = height;
  request.options.viewport.near_fraction = near_fraction;
  request.dag.viewport = request.options.viewport;
  request.dag.tolerance_pixels = request.options.tolerance_pixels;
  if (!request.csv.empty() && same_file(request.input, request.csv))
    return tool.usage_error("the --csv output '" + request.csv + "' is the input itself");
  return tool.run([&] { return run(tool, request); });
}
