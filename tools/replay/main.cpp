// lodbake-replay: replays a camera path on a container's view-dependent
// structure and measures it (issue 8). Mode vhier: BASE + VHIE + RFIN, the
// SelectiveRefiner adapted per frame (lib/replay/vhier_replay.h); mode dag:
// BASE + VSPL + DAGE, MANAGE-TRAVERSAL (lib/replay/dag_replay.h); mode fan:
// BASE + FANH, the fan hierarchy's dual-path adapt (lib/replay/fan_replay.h).
// Thin:
// decoding lives in formats/, the runtime in lib/replay.
#include <algorithm>
#include <cmath>
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
#include "formats/sections/fanh.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/support/file_io.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/dag_replay.h"
#include "lib/replay/fan_replay.h"
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
  FanReplayOptions fan;
};

// One frame's measures in any mode: `front` is the vertex front (vhier),
// |Fs| (dag) or the active nodes (fan), `collapse_front` |Fc| (dag only);
// for fan, `splits` / `collapses` are the fine path's steps.
struct Row {
  size_t splits = 0;
  size_t collapses = 0;
  size_t fan_merges = 0;
  size_t fan_splits = 0;
  size_t refused = 0;
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

struct FanState {
  std::optional<FanReplay> replay;
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

Result<Session> load_fan(const Container& container, const Section& base, const Request& request) {
  const Section* fanh = container.find(kFanhTag);
  if (fanh == nullptr) {
    return invalid_input("container has no FANH section; mode fan needs BASE + FANH (lodbake-fan)");
  }
  auto state = std::make_shared<FanState>();
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh input, decode_base(base.data, base.size));
  LODBAKE_ASSIGN_OR_RETURN(FanHierarchy h, decode_fanh(fanh->data, fanh->size));
  LODBAKE_ASSIGN_OR_RETURN(FanReplay replay, FanReplay::create(input, h));
  state->replay.emplace(std::move(replay));
  const FanhStats stats = fanh_stats(h);
  const FanRuntime& rt = state->replay->runtime();
  Session session;
  session.sphere = bounding_sphere(input.positions);
  session.structure = {{"nodes", h.node_count()},
                       {"internal_nodes", stats.internal_nodes},
                       {"roots", stats.roots},
                       {"depth", stats.depth},
                       {"input_triangles", h.triangle_count},
                       {"coarsest_triangles", rt.triangle_count()}};
  session.structure_text = std::to_string(h.node_count()) + " nodes (" +
                           std::to_string(stats.internal_nodes) + " fan-merges), " +
                           std::to_string(stats.roots) + " roots, " +
                           std::to_string(h.triangle_count) + " input triangles, coarsest " +
                           std::to_string(rt.triangle_count());
  const FanReplayOptions options = request.fan;
  const BoundingSphere sphere = session.sphere;
  session.step = [state, options, sphere](const CameraFrame& frame) -> Result<Row> {
    LODBAKE_ASSIGN_OR_RETURN(FanFrameStats f, state->replay->adapt(sphere, frame, options));
    Row row;
    row.fan_merges = f.fan_merges;
    row.fan_splits = f.fan_splits;
    row.collapses = f.collapses;
    row.splits = f.splits;
    row.refused = f.refused;
    row.front = f.active;
    row.triangles = f.triangles;
    row.ms = f.adapt_ms;
    return row;
  };
  session.check = [state] { return state->replay->check(); };
  return session;
}

Result<Session> load(const Bytes& bytes, const Request& request) {
  LODBAKE_ASSIGN_OR_RETURN(Container container, read_container(bytes.data(), bytes.size()));
  LODBAKE_ASSIGN_OR_RETURN(const Section* base, container.require(kBaseTag));
  try {
    if (request.mode == "dag") return load_dag(container, *base, request);
    if (request.mode == "fan") return load_fan(container, *base, request);
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

int run(const Tool& tool, const Request& request) {
  Result<Bytes> bytes = read_file(request.input);
  if (!bytes.is_ok()) return tool.fail(request.input, bytes.status());
  Result<Session> loaded = load(bytes.value(), request);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  const Session& session = loaded.value();
  const bool dag = request.mode == "dag";
  const bool fan = request.mode == "fan";

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
    csv << (dag   ? "frame,splits,collapses,fs,fc,triangles,traversal_ms\n"
            : fan ? "frame,fan_merges,fan_splits,collapses,splits,active,triangles,adapt_ms\n"
                  : "frame,splits,collapses,passes,front,triangles,adapt_ms\n");
    for (size_t i = 0; i < frames.size(); ++i) {
      const Row& f = frames[i];
      if (fan) {
        csv << i << ',' << f.fan_merges << ',' << f.fan_splits << ',' << f.collapses << ','
            << f.splits << ',' << f.front << ',' << f.triangles << ',' << f.ms << '\n';
        continue;
      }
      csv << i << ',' << f.splits << ',' << f.collapses << ',' << (dag ? f.front : f.passes) << ','
          << (dag ? f.collapse_front : f.front) << ',' << f.triangles << ',' << f.ms << '\n';
    }
    Status written = write_file_atomic(request.csv, csv.str());
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  size_t splits = 0, collapses = 0, max_front = 0, max_fc = 0, max_triangles = 0;
  size_t fan_merges = 0, fan_splits = 0, refused = 0;
  size_t pass_limited = 0;
  double front_sum = 0, fc_sum = 0, triangle_sum = 0, ms_sum = 0, ms_max = 0;
  std::vector<double> ms;
  for (const Row& f : frames) {
    splits += f.splits;
    collapses += f.collapses;
    fan_merges += f.fan_merges;
    fan_splits += f.fan_splits;
    refused += f.refused;
    max_front = std::max(max_front, f.front);
    max_fc = std::max(max_fc, f.collapse_front);
    max_triangles = std::max(max_triangles, f.triangles);
    front_sum += static_cast<double>(f.front);
    fc_sum += static_cast<double>(f.collapse_front);
    triangle_sum += static_cast<double>(f.triangles);
    ms_sum += f.ms;
    ms_max = std::max(ms_max, f.ms);
    ms.push_back(f.ms);
    if (!dag && !fan && f.passes >= request.options.max_passes) ++pass_limited;
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
                           {dag   ? "dag"
                            : fan ? "fan_hierarchy"
                                  : "hierarchy",
                            session.structure},
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
  } else if (fan) {
    const size_t operations = fan_merges + fan_splits + collapses + splits;
    report["fan_merges"] = fan_merges;
    report["fan_splits"] = fan_splits;
    report["adapt_operations"] = {{"total", operations},
                                  {"per_frame", static_cast<double>(operations) / n}};
    report["refused"] = refused;
    report["coarse_fraction"] = request.fan.coarse_fraction;
    report["active_nodes"] = {{"mean", front_sum / n}, {"max", max_front}};
    report["adapt_ms"] = timing;
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
  std::cout << (dag   ? "dag           "
                : fan ? "fan hierarchy "
                      : "hierarchy     ")
            << session.structure_text << "\n";
  std::cout << "view          " << request.options.viewport.width << "x"
            << request.options.viewport.height << ", fov " << request.fov_degrees
            << " deg, tolerance " << request.options.tolerance_pixels << " px\n";
  if (dag) {
    std::cout << "traversal     priority-oriented, budget " << request.dag.triangle_budget
              << " triangles, at most " << request.dag.max_changes << " changes per frame\n";
  }
  if (fan) {
    std::cout << "dual path     fan-merge / fan-split when the target is an end of the fine "
                 "path at least "
              << request.fan.coarse_fraction << " x children away, else merge-pointer steps\n";
    std::cout << "operations    " << fan_merges << " fan-merges, " << fan_splits << " fan-splits, "
              << collapses << " edge collapses, " << splits << " vertex splits ("
              << (fan_merges + fan_splits + collapses + splits) / n << " per frame)\n";
    if (refused != 0) {
      std::cout << "refused       " << refused << " nodes left short of their target\n";
    }
  } else {
    std::cout << "operations    " << splits << " splits, " << collapses << " collapses\n";
  }
  if (fan) {
    std::cout << "active nodes  mean " << front_sum / n << ", max " << max_front << "\n";
  } else if (dag) {
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

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  Tool tool("lodbake-replay", "FILE.lbk [--mode vhier|dag|fan] [--path scan|orbit|FILE] [options]",
            "Replays a camera path on a container's view-dependent structure and reports,\n"
            "per frame, the refinement operations, fronts, triangles and adapt time.\n"
            "Mode vhier (default): BASE + VHIE + RFIN from lodbake-hierarchy; the vertex\n"
            "front is refined while a node's bounding sphere meets the view frustum, its\n"
            "normal cone is not entirely back-facing and its deviation projects to more than\n"
            "--tolerance pixels, and coarsened where none holds (Hoppe 1997).\n"
            "Mode dag: BASE + VSPL + DAGE from lodbake-hierarchy; MANAGE-TRAVERSAL (Zheng &\n"
            "Chan 2006) with the priority-oriented traversal in budget mode: splits by\n"
            "projected error over --tolerance within --budget triangles, at most --changes\n"
            "splits + collapses per frame.\n"
            "Mode fan: BASE + FANH from lodbake-fan; from the coarsest mesh, the active\n"
            "nodes are scanned each frame and each fan moves toward its target merge\n"
            "pointer (error projected at its vertex against --tolerance, all merged out of\n"
            "view) by one fan-merge / fan-split when the target is an end of its fine path\n"
            "at least --coarse x its children away, else by edge collapses / vertex splits\n"
            "(Livny, Sokolovsky & El-Sana 2007).\n"
            "Paths: 'scan' (180 frames: approach the model, then rise from its bottom to its\n"
            "top), 'orbit' (194 frames: approach, then circle it twice, speeding up), both\n"
            "relative to the bounding sphere, or a CSV FILE with one row per frame:\n"
            "eye x,y,z, target x,y,z, up x,y,z, vertical fov in degrees ('#' comments).");
  Request request;
  uint32_t width = 1024, height = 768;
  float near_fraction = 0.01f;
  tool.options().add_options()("mode", po::value<std::string>(&request.mode)->value_name("M"),
                               "the structure replayed: vhier (default), dag or fan")(
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
      "after every frame, check that the mesh is an edge-manifold, consistently oriented\n"
      "triangulation without duplicate triangles and the counters agree (exit 7 naming\n"
      "the frame otherwise)")(
      "csv", po::value<std::string>(&request.csv)->value_name("FILE"),
      "write per-frame rows to FILE (vhier: frame, splits, collapses, passes, front, "
      "triangles, adapt_ms; dag: frame, splits, collapses, fs, fc, triangles, traversal_ms; "
      "fan: frame, fan_merges, fan_splits, collapses, splits, active, triangles, adapt_ms)");
  tool.options().add_options()("budget",
                               po::value<size_t>(&request.dag.triangle_budget)->value_name("T"),
                               "dag: triangle budget (default 60000)")(
      "changes", po::value<size_t>(&request.dag.max_changes)->value_name("N"),
      "dag: at most N splits + collapses per frame (default 300)")(
      "coarse", po::value<float>(&request.fan.coarse_fraction)->value_name("F"),
      "fan: one fan-merge / fan-split when the target is an end of the fine path at "
      "least max(1, ceil(F x children)) steps away, else merge-pointer steps (default "
      "0.5; 0: always, > 1: never)");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("input", "FILE.lbk", &request.input))
    return *code;
  if (request.mode != "vhier" && request.mode != "dag" && request.mode != "fan") {
    return tool.usage_error("--mode '" + request.mode +
                            "' is not available (modes: vhier, dag, fan)");
  }
  if (!(request.fan.coarse_fraction >= 0 && std::isfinite(request.fan.coarse_fraction)))
    return tool.usage_error("--coarse takes a fraction >= 0");
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
  request.fan.viewport = request.options.viewport;
  request.fan.tolerance_pixels = request.options.tolerance_pixels;
  if (!request.csv.empty() && same_file(request.input, request.csv))
    return tool.usage_error("the --csv output '" + request.csv + "' is the input itself");
  return tool.run([&] { return run(tool, request); });
}
