// lodbake-replay: replays a camera path on a container's view-dependent
// structure and measures it (issue 8). Mode vhier: BASE + VHIE + RFIN, the
// SelectiveRefiner adapted per frame (lib/replay/vhier_replay.h); mode dag:
// BASE + VSPL + DAGE, MANAGE-TRAVERSAL with one or all three traversals and
// their accuracy against the priority-oriented one (lib/replay/dag_replay.h);
// mode fan: BASE + FANH, the fan hierarchy's dual-path adapt
// (lib/replay/fan_replay.h). Mode sets is not camera-driven: BASE + VSPL +
// SETS, the strip paper's LoD-recovery tests (lib/replay/sets_replay.h), one
// step per LoD recovered; it runs through run_sets(), the camera modes
// through run_camera_path(). Mode stream: BASE + VHIE + RFIN served to a
// client over an in-memory channel (lib/replay/stream_session.h), through
// run_stream(). Mode vtrees: BASE + VHIE + RFIN + VTRE, vertex-tree
// transmission over an in-memory channel (lib/replay/vtrees_session.h),
// through run_vtrees(). Both streaming modes also run over TCP on loopback
// (--serve / --connect), sharing start_serving() and the client's frame
// loop helpers.
// Thin: decoding lives in formats/, the runtime in lib/replay.
#include <algorithm>
#include <charconv>
#include <chrono>
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
#include "formats/sections/fanh.h"
#include "formats/sections/rfin.h"
#include "formats/sections/sets.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vtre.h"
#include "formats/support/file_io.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/dag_replay.h"
#include "lib/replay/fan_replay.h"
#include "lib/replay/replay_check.h"
#include "lib/replay/sets_replay.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_transport.h"
#include "lib/replay/structure_cross_check.h"
#include "lib/replay/vhier_replay.h"
#include "lib/replay/vtrees_session.h"
#include "tools/common/cli.h"
#include "tools/replay/plots.h"

namespace lodbake::cli {
namespace {

constexpr const char* kReplaySchema = "lodbake.replay/1";

struct Request {
  std::string input;
  std::string mode = "vhier";
  std::string path = "scan";
  std::string csv;
  std::string plot;  // --plot DIR
  std::string tolerance = "1";
  std::string traversal = "priority";
  std::string budget_mode = "auto";
  float fov_degrees = 60;
  bool validate = false;
  VhierReplayOptions options;
  DagReplayOptions dag;
  std::vector<DagTraversal> traversals;  // dag: the lanes replayed
  FanReplayOptions fan;
  // Mode sets.
  std::vector<double> percents = paper_recovery_percents();
  std::string spacing = "both";
  // Modes stream and vtrees over TCP: --serve PORT (a server for `clients`
  // connections) or --connect ADDRESS (a client, no FILE); mode stream:
  // --clients K without --serve runs K clients in one process.
  std::optional<LoopbackAddress> serve;
  std::optional<LoopbackAddress> connect;
  size_t clients = 1;
};

// One frame's measures of one lane (the vhier refiner, one DAG traversal,
// or the fan hierarchy): `front` is the vertex front (vhier), |Fs| (dag) or
// the active nodes (fan), `collapse_front` |Fc| (dag only), `accuracy` the
// share of the priority-oriented traversal's triangles (dag, when measured;
// else < 0); for fan, `splits` / `collapses` are the fine path's steps.
struct Row {
  size_t splits = 0;
  size_t collapses = 0;
  size_t fan_merges = 0;
  size_t fan_splits = 0;
  size_t refused = 0;
  size_t passes = 0;
  size_t visited = 0;
  bool budget_mode = false;
  size_t front = 0;
  size_t collapse_front = 0;
  size_t triangles = 0;
  double ms = 0;
  double accuracy = -1;
};

// --validate's cross-structure check: the hierarchy (VHIE) against the
// split DAG (VSPL + DAGE) of the same container, after every frame. It holds
// what the replayed mode does not decode itself; `unavailable` says why the
// check cannot run (the other structure is missing or not the same one).
struct CrossCheckState {
  std::string unavailable;
  VertexHierarchy h;
  ProgressiveMesh pm;
  VsplitDag dag;
  std::optional<StructureCrossCheck> check;
  size_t frames = 0;        // checks made (one per frame and lane)
  size_t on_own_front = 0;  // of which on the replay's own front
};

// Makes the check for the structures the mode decoded (`h`, or `pm` and
// `dag`), decoding the other one from the container; never fails: a
// container without it gets `unavailable` set.
std::shared_ptr<CrossCheckState> prepare_cross_check(const Container& container,
                                                     const Section& base, const VertexHierarchy* h,
                                                     const ProgressiveMesh* pm,
                                                     const VsplitDag* dag) {
  auto cross = std::make_shared<CrossCheckState>();
  auto fail = [&](const std::string& why) {
    cross->unavailable = why;
    return cross;
  };
  if (h == nullptr) {
    const Section* vhie = container.find(kVhieTag);
    if (vhie == nullptr) return fail("the container has no VHIE section");
    Result<TriangleMesh> base_mesh = decode_base(base.data, base.size);
    if (!base_mesh.is_ok()) return fail(base_mesh.status().message());
    Result<VertexHierarchy> decoded =
        decode_vhie(vhie->data, vhie->size, std::move(base_mesh).value());
    if (!decoded.is_ok()) return fail("VHIE: " + decoded.status().message());
    cross->h = std::move(decoded).value();
    h = &cross->h;
  } else {
    const Section* vspl = container.find(kVsplTag);
    const Section* dage = container.find(kDageTag);
    if (vspl == nullptr || dage == nullptr)
      return fail("the container has no VSPL + DAGE sections");
    Result<ProgressiveMesh> decoded_pm =
        decode_progressive_mesh(base.data, base.size, vspl->data, vspl->size);
    if (!decoded_pm.is_ok()) return fail("VSPL: " + decoded_pm.status().message());
    Result<VsplitDag> decoded_dag = decode_dage(dage->data, dage->size);
    if (!decoded_dag.is_ok()) return fail("DAGE: " + decoded_dag.status().message());
    cross->pm = std::move(decoded_pm).value();
    cross->dag = std::move(decoded_dag).value();
    pm = &cross->pm;
    dag = &cross->dag;
  }
  Result<StructureCrossCheck> check = StructureCrossCheck::create(*h, *pm, *dag);
  if (!check.is_ok()) return fail(check.status().message());
  cross->check.emplace(std::move(check).value());
  return cross;
}

// A loaded structure, stepped one camera at a time; one Row per lane.
struct Session {
  BoundingSphere sphere;
  nlohmann::json structure;
  std::string structure_text;
  std::vector<std::string> lanes;
  std::function<Result<std::vector<Row>>(const CameraFrame&)> step;
  std::function<std::vector<std::string>()> check;
  std::shared_ptr<CrossCheckState> cross;  // with --validate in modes vhier and dag
};

struct VhierState {
  VertexHierarchy h;
  std::vector<NodeRefinement> data;
  std::optional<SelectiveRefiner> refiner;
};

// The DAG's lanes, and the priority-oriented reference their accuracy is
// measured against when no lane is priority-oriented.
struct DagState {
  ProgressiveMesh pm;
  VsplitDag dag;
  std::vector<DagReplay> lanes;
  std::optional<DagReplay> reference;
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
  session.lanes = {"vhier"};
  session.step = [state, options, sphere](const CameraFrame& frame) -> Result<std::vector<Row>> {
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
    return std::vector<Row>{row};
  };
  if (request.validate)
    session.cross = prepare_cross_check(container, base, &state->h, nullptr, nullptr);
  std::shared_ptr<CrossCheckState> cross = session.cross;
  session.check = [state, cross] {
    std::vector<std::string> problems = check_vhier_mesh(*state->refiner);
    if (cross && cross->check) {
      std::vector<uint8_t> flags = cross->check->refiner_splits(*state->refiner);
      const bool own = cross->check->close(&flags);
      ++cross->frames;
      cross->on_own_front += own;
      for (std::string& p : cross->check->compare(flags, own ? &*state->refiner : nullptr, nullptr))
        problems.push_back(std::move(p));
    }
    return problems;
  };
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
  const std::vector<DagTraversal>& traversals = request.traversals;
  for (size_t i = 0; i < traversals.size(); ++i) {
    LODBAKE_ASSIGN_OR_RETURN(DagReplay replay, DagReplay::create(state->pm, state->dag));
    state->lanes.push_back(std::move(replay));
  }
  const bool has_priority =
      std::find(traversals.begin(), traversals.end(), DagTraversal::kPriority) != traversals.end();
  if (!has_priority) {
    LODBAKE_ASSIGN_OR_RETURN(DagReplay replay, DagReplay::create(state->pm, state->dag));
    state->reference.emplace(std::move(replay));
  }
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
  for (DagTraversal t : traversals)
    session.lanes.push_back(dag_traversal_name(t));
  const DagReplayOptions options = request.dag;
  const BoundingSphere sphere = session.sphere;
  session.step = [state, options, sphere,
                  traversals](const CameraFrame& frame) -> Result<std::vector<Row>> {
    std::vector<Row> rows;
    const DagReplay* reference = nullptr;
    for (size_t i = 0; i < traversals.size(); ++i) {
      DagReplayOptions lane = options;
      lane.traversal = traversals[i];
      LODBAKE_ASSIGN_OR_RETURN(DagFrameStats f, state->lanes[i].adapt(sphere, frame, lane));
      if (traversals[i] == DagTraversal::kPriority && reference == nullptr)
        reference = &state->lanes[i];
      Row row;
      row.splits = f.splits;
      row.collapses = f.collapses;
      row.visited = f.visited;
      row.budget_mode = f.budget_mode;
      row.front = f.split_front;
      row.collapse_front = f.collapse_front;
      row.triangles = f.triangles;
      row.ms = f.traversal_ms;
      rows.push_back(row);
    }
    if (state->reference) {
      DagReplayOptions lane = options;
      lane.traversal = DagTraversal::kPriority;
      LODBAKE_RETURN_IF_ERROR(state->reference->adapt(sphere, frame, lane).status());
      reference = &*state->reference;
    }
    std::vector<Triangle> expected;
    for (size_t i = 0; i < traversals.size(); ++i) {
      if (traversals[i] == DagTraversal::kPriority) continue;
      if (expected.empty()) expected = reference->cut_triangles();
      rows[i].accuracy = cut_accuracy(expected, state->lanes[i].cut_triangles());
    }
    return rows;
  };
  if (request.validate)
    session.cross = prepare_cross_check(container, base, nullptr, &state->pm, &state->dag);
  std::shared_ptr<CrossCheckState> cross = session.cross;
  session.check = [state, traversals, cross] {
    std::vector<std::string> problems;
    for (size_t i = 0; i < traversals.size(); ++i) {
      const std::string lane = std::string(dag_traversal_name(traversals[i])) + " traversal: ";
      for (const std::string& p : state->lanes[i].check())
        problems.push_back(lane + p);
      if (cross && cross->check) {
        std::vector<uint8_t> flags = cross->check->dag_splits(state->lanes[i].fronts());
        const bool own = cross->check->close(&flags);
        ++cross->frames;
        cross->on_own_front += own;
        const std::vector<Triangle> cut =
            own ? state->lanes[i].cut_triangles() : std::vector<Triangle>();
        for (const std::string& p : cross->check->compare(flags, nullptr, own ? &cut : nullptr))
          problems.push_back(lane + p);
      }
    }
    return problems;
  };
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
  session.lanes = {"fan"};
  const FanReplayOptions options = request.fan;
  const BoundingSphere sphere = session.sphere;
  session.step = [state, options, sphere](const CameraFrame& frame) -> Result<std::vector<Row>> {
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
    return std::vector<Row>{row};
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

// "elephant.lbk, mode dag, path scan": the charts' heading.
std::string plot_title(const Request& request) {
  const size_t slash = request.input.find_last_of('/');
  std::string title = slash == std::string::npos ? request.input : request.input.substr(slash + 1);
  title += ", mode " + request.mode;
  if (request.mode != "sets") {
    const size_t path_slash = request.path.find_last_of('/');
    title += ", path " +
             (path_slash == std::string::npos ? request.path : request.path.substr(path_slash + 1));
  }
  return title;
}

// The --plot files as paths, for the reports.
std::vector<std::string> plot_paths(const Request& request, const std::vector<std::string>& files) {
  std::vector<std::string> paths;
  for (const std::string& f : files)
    paths.push_back(request.plot + "/" + f);
  return paths;
}

void print_plots(const Request& request, const std::vector<std::string>& files) {
  if (files.empty()) return;
  std::cout << "plots         " << request.plot << ":";
  for (size_t i = 0; i < files.size(); ++i)
    std::cout << (i == 0 ? " " : ", ") << files[i];
  std::cout << "\n";
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One lane's figures over the whole path.
struct LaneSummary {
  size_t splits = 0, collapses = 0, visited = 0, budget_frames = 0, pass_limited = 0;
  size_t fan_merges = 0, fan_splits = 0, refused = 0;
  size_t max_front = 0, max_fc = 0, max_triangles = 0;
  double front_mean = 0, fc_mean = 0, triangle_mean = 0, fronts_per_triangle = 0;
  double ms_mean = 0, ms_median = 0, ms_max = 0;
  size_t accuracy_frames = 0;
  double accuracy_mean = 0, accuracy_min = 1;
};

LaneSummary summarize(const std::vector<std::vector<Row>>& frames, size_t lane, size_t max_passes) {
  LaneSummary s;
  std::vector<double> ms;
  double ratio_sum = 0;
  for (const std::vector<Row>& rows : frames) {
    const Row& f = rows[lane];
    s.splits += f.splits;
    s.collapses += f.collapses;
    s.fan_merges += f.fan_merges;
    s.fan_splits += f.fan_splits;
    s.refused += f.refused;
    s.visited += f.visited;
    s.budget_frames += f.budget_mode;
    s.max_front = std::max(s.max_front, f.front);
    s.max_fc = std::max(s.max_fc, f.collapse_front);
    s.max_triangles = std::max(s.max_triangles, f.triangles);
    s.front_mean += static_cast<double>(f.front);
    s.fc_mean += static_cast<double>(f.collapse_front);
    s.triangle_mean += static_cast<double>(f.triangles);
    if (f.triangles != 0)
      ratio_sum +=
          static_cast<double>(f.front + f.collapse_front) / static_cast<double>(f.triangles);
    s.ms_mean += f.ms;
    s.ms_max = std::max(s.ms_max, f.ms);
    ms.push_back(f.ms);
    if (f.passes >= max_passes) ++s.pass_limited;
    if (f.accuracy >= 0) {
      ++s.accuracy_frames;
      s.accuracy_mean += f.accuracy;
      s.accuracy_min = std::min(s.accuracy_min, f.accuracy);
    }
  }
  const double n = static_cast<double>(std::max<size_t>(frames.size(), 1));
  s.front_mean /= n;
  s.fc_mean /= n;
  s.triangle_mean /= n;
  s.fronts_per_triangle = ratio_sum / n;
  s.ms_mean /= n;
  s.ms_median = median(ms);
  if (s.accuracy_frames != 0) s.accuracy_mean /= static_cast<double>(s.accuracy_frames);
  return s;
}

std::string traversal_text(const std::string& lane) {
  if (lane == "priority") return "priority-oriented";
  if (lane == "constant") return "constant-time";
  return lane;
}

Result<std::vector<CameraFrame>> read_path(const Request& request, const Session& session,
                                           std::string* failed_file) {
  if (request.path == "scan" || request.path == "orbit")
    return builtin_path(request.path, session.sphere, request.fov_degrees);
  *failed_file = request.path;
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(request.path, uint64_t{1} << 30));
  return parse_camera_path(bytes.data(), bytes.size());
}

int run_camera_path(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<Session> loaded = load(bytes, request);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  const Session& session = loaded.value();
  const bool dag = request.mode == "dag";
  const bool fan = request.mode == "fan";

  std::string path_file;
  Result<std::vector<CameraFrame>> read = read_path(request, session, &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();

  std::vector<std::vector<Row>> frames;
  frames.reserve(path.size());
  Progress progress(tool, "replaying");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<std::vector<Row>> rows = session.step(path[i]);
    if (!rows.is_ok()) {
      return tool.fail(request.input,
                       Status(rows.status().kind(),
                              "frame " + std::to_string(i) + ": " + rows.status().message()));
    }
    frames.push_back(std::move(rows).value());
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

  std::vector<std::string> plots;
  if (!request.csv.empty() || !request.plot.empty()) {
    std::ostringstream csv;
    csv << (dag   ? "frame,traversal,splits,collapses,visited,budget_mode,fs,fc,triangles,"
                    "traversal_ms,accuracy\n"
            : fan ? "frame,fan_merges,fan_splits,collapses,splits,active,triangles,adapt_ms\n"
                  : "frame,splits,collapses,passes,front,triangles,adapt_ms\n");
    for (size_t i = 0; i < frames.size(); ++i) {
      for (size_t lane = 0; lane < session.lanes.size(); ++lane) {
        const Row& f = frames[i][lane];
        if (dag) {
          csv << i << ',' << session.lanes[lane] << ',' << f.splits << ',' << f.collapses << ','
              << f.visited << ',' << (f.budget_mode ? 1 : 0) << ',' << f.front << ','
              << f.collapse_front << ',' << f.triangles << ',' << f.ms << ',';
          if (f.accuracy >= 0) csv << f.accuracy;
          csv << '\n';
        } else if (fan) {
          csv << i << ',' << f.fan_merges << ',' << f.fan_splits << ',' << f.collapses << ','
              << f.splits << ',' << f.front << ',' << f.triangles << ',' << f.ms << '\n';
        } else {
          csv << i << ',' << f.splits << ',' << f.collapses << ',' << f.passes << ',' << f.front
              << ',' << f.triangles << ',' << f.ms << '\n';
        }
      }
    }
    if (!request.plot.empty()) {
      std::string lanes;
      for (const std::string& lane : session.lanes)
        lanes += (lanes.empty() ? "" : " ") + lane;
      const Status plotted =
          write_plots({request.plot, request.mode, lanes, plot_title(request), csv.str()}, &plots);
      if (!plotted.is_ok()) return tool.fail(request.plot, plotted);
    }
    if (!request.csv.empty()) {
      Status written = write_file_atomic(request.csv, csv.str());
      if (!written.is_ok()) return tool.fail(request.csv, written);
    }
  }

  std::vector<LaneSummary> lanes;
  for (size_t lane = 0; lane < session.lanes.size(); ++lane)
    lanes.push_back(summarize(frames, lane, request.options.max_passes));
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
                           {"tolerance", request.tolerance},
                           {"tolerance_pixels", request.options.tolerance_pixels},
                           {dag   ? "dag"
                            : fan ? "fan_hierarchy"
                                  : "hierarchy",
                            session.structure}};
  auto timing = [](const LaneSummary& l) {
    return nlohmann::json{{"mean", l.ms_mean}, {"median", l.ms_median}, {"max", l.ms_max}};
  };
  if (dag) {
    report["budget_mode"] = request.budget_mode;
    report["max_changes"] = request.dag.max_changes;
    report["triangle_budget"] = request.dag.triangle_budget;
    nlohmann::json list = nlohmann::json::array();
    for (size_t lane = 0; lane < lanes.size(); ++lane) {
      const LaneSummary& l = lanes[lane];
      nlohmann::json t = {{"traversal", session.lanes[lane]},
                          {"splits", l.splits},
                          {"collapses", l.collapses},
                          {"visited", l.visited},
                          {"budget_mode_frames", l.budget_frames},
                          {"split_front", {{"mean", l.front_mean}, {"max", l.max_front}}},
                          {"collapse_front", {{"mean", l.fc_mean}, {"max", l.max_fc}}},
                          {"fronts_per_triangle", l.fronts_per_triangle},
                          {"triangles", {{"mean", l.triangle_mean}, {"max", l.max_triangles}}},
                          {"traversal_ms", timing(l)}};
      t["accuracy"] = l.accuracy_frames == 0
                          ? nlohmann::json(nullptr)
                          : nlohmann::json{{"mean", l.accuracy_mean}, {"min", l.accuracy_min}};
      list.push_back(t);
    }
    report["traversals"] = list;
  } else if (fan) {
    const LaneSummary& l = lanes[0];
    const size_t operations = l.fan_merges + l.fan_splits + l.collapses + l.splits;
    report["splits"] = l.splits;
    report["collapses"] = l.collapses;
    report["fan_merges"] = l.fan_merges;
    report["fan_splits"] = l.fan_splits;
    report["adapt_operations"] = {
        {"total", operations},
        {"per_frame", static_cast<double>(operations) / static_cast<double>(frames.size())}};
    report["refused"] = l.refused;
    report["coarse_fraction"] = request.fan.coarse_fraction;
    report["triangles"] = {{"mean", l.triangle_mean}, {"max", l.max_triangles}};
    report["active_nodes"] = {{"mean", l.front_mean}, {"max", l.max_front}};
    report["adapt_ms"] = timing(l);
  } else {
    const LaneSummary& l = lanes[0];
    report["splits"] = l.splits;
    report["collapses"] = l.collapses;
    report["triangles"] = {{"mean", l.triangle_mean}, {"max", l.max_triangles}};
    report["front_size"] = {{"mean", l.front_mean}, {"max", l.max_front}};
    report["adapt_ms"] = timing(l);
    report["frames_at_pass_limit"] = l.pass_limited;
  }
  if (!plots.empty()) report["plots"] = plot_paths(request, plots);
  if (const CrossCheckState* cross = session.cross.get()) {
    report["cross_check"] = cross->check ? nlohmann::json{{"checks", cross->frames},
                                                          {"on_own_front", cross->on_own_front}}
                                         : nlohmann::json{{"unavailable", cross->unavailable}};
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
            << " deg, tolerance " << request.options.tolerance_pixels << " px";
  if (request.tolerance.back() == '%') std::cout << " (" << request.tolerance << " of the height)";
  std::cout << "\n";
  print_plots(request, plots);
  if (const CrossCheckState* cross = session.cross.get()) {
    if (cross->check) {
      std::cout << "cross-check   " << (dag ? "every DAG cut gives" : "every front gives")
                << " the same triangles in the " << (dag ? "hierarchy" : "split DAG") << " ("
                << cross->frames << " checks, " << cross->on_own_front
                << " on the replay's own front, the others on the smallest front closed under "
                   "both)\n";
    } else {
      std::cout << "cross-check   not made: " << cross->unavailable << "\n";
    }
  }
  if (fan) {
    const LaneSummary& l = lanes[0];
    const size_t operations = l.fan_merges + l.fan_splits + l.collapses + l.splits;
    std::cout << "dual path     fan-merge / fan-split when the target is an end of the fine "
                 "path at least "
              << request.fan.coarse_fraction << " x children away, else merge-pointer steps\n";
    std::cout << "operations    " << l.fan_merges << " fan-merges, " << l.fan_splits
              << " fan-splits, " << l.collapses << " edge collapses, " << l.splits
              << " vertex splits ("
              << static_cast<double>(operations) / static_cast<double>(frames.size())
              << " per frame)\n";
    if (l.refused != 0) {
      std::cout << "refused       " << l.refused << " nodes left short of their target\n";
    }
    std::cout << "active nodes  mean " << l.front_mean << ", max " << l.max_front << "\n";
    std::cout << "triangles     mean " << l.triangle_mean << ", max " << l.max_triangles << "\n";
    std::cout << "adapt time    mean " << l.ms_mean << " ms, median " << l.ms_median << " ms, max "
              << l.ms_max << " ms per frame\n";
    return 0;
  }
  if (!dag) {
    const LaneSummary& l = lanes[0];
    std::cout << "operations    " << l.splits << " splits, " << l.collapses << " collapses\n";
    std::cout << "front size    mean " << l.front_mean << ", max " << l.max_front << "\n";
    std::cout << "triangles     mean " << l.triangle_mean << ", max " << l.max_triangles << "\n";
    std::cout << "adapt time    mean " << l.ms_mean << " ms, median " << l.ms_median << " ms, max "
              << l.ms_max << " ms per frame\n";
    if (l.pass_limited != 0) {
      std::cout << "pass limit    " << l.pass_limited << " frames stopped at "
                << request.options.max_passes << " passes\n";
    }
    return 0;
  }
  for (size_t lane = 0; lane < lanes.size(); ++lane) {
    const LaneSummary& l = lanes[lane];
    const bool constant = session.lanes[lane] == "constant";
    std::cout << "traversal     " << traversal_text(session.lanes[lane]) << ", ";
    if (request.budget_mode == "free") {
      std::cout << "FREE-MODE (no budget)";
    } else {
      std::cout << "budget " << request.dag.triangle_budget << " triangles (BUDGET-MODE in "
                << l.budget_frames << " of " << frames.size() << " frames)";
    }
    std::cout << ", at most " << request.dag.max_changes
              << (constant ? " nodes visited per traversal\n" : " changes per traversal\n");
    std::cout << "operations    " << l.splits << " splits, " << l.collapses << " collapses, "
              << l.visited << " nodes evaluated\n";
    std::cout << "fronts        |Fs| mean " << l.front_mean << ", max " << l.max_front
              << "; |Fc| mean " << l.fc_mean << ", max " << l.max_fc
              << "; (|Fs| + |Fc|) / triangles mean " << l.fronts_per_triangle << "\n";
    std::cout << "triangles     mean " << l.triangle_mean << ", max " << l.max_triangles << "\n";
    std::cout << "frame time    mean " << l.ms_mean << " ms, median " << l.ms_median << " ms, max "
              << l.ms_max << " ms per frame\n";
    if (l.accuracy_frames != 0) {
      std::cout << "accuracy      mean " << 100 * l.accuracy_mean << "%, min "
                << 100 * l.accuracy_min << "% of the priority-oriented traversal's triangles\n";
    }
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
      if (!request.csv.empty() || !request.plot.empty()) {
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
  std::vector<std::string> plots;
  if (!request.plot.empty()) {
    const Status plotted =
        write_plots({request.plot, request.mode, "", plot_title(request), csv.str()}, &plots);
    if (!plotted.is_ok()) return tool.fail(request.plot, plotted);
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
    nlohmann::json report = {{"schema", kReplaySchema},
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
                             {"tests", rows}};
    if (!plots.empty()) report["plots"] = plot_paths(request, plots);
    tool.print_json(report);
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode sets, " << summaries.size()
            << " recovery tests, " << recovered << " LoDs recovered"
            << (request.validate ? ", every LoD validated" : "") << "\n";
  std::cout << "sets          " << graph.strip_count() << " strips, " << graph.node_count()
            << " nodes over " << graph.lod_count << " LoDs, " << data.pm.base.triangle_count()
            << " base triangles\n";
  print_plots(request, plots);
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

// Mode stream's database: the container's hierarchy and RFIN records.
struct StreamDb {
  std::unique_ptr<VertexHierarchy> h;  // StreamHierarchy points at it
  std::unique_ptr<StreamHierarchy> db;
};

Result<StreamDb> load_stream_db(const Bytes& bytes) {
  LODBAKE_ASSIGN_OR_RETURN(Container container, read_container(bytes.data(), bytes.size()));
  const Section* base = container.find(kBaseTag);
  const Section* vhie = container.find(kVhieTag);
  const Section* rfin = container.find(kRfinTag);
  if (base == nullptr || vhie == nullptr || rfin == nullptr) {
    return invalid_input(std::string("container has no ") +
                         (base == nullptr   ? "BASE"
                          : vhie == nullptr ? "VHIE"
                                            : "RFIN") +
                         " section; mode stream needs BASE + VHIE + RFIN "
                         "(lodbake-hierarchy --sections vhie)");
  }
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh base_mesh, decode_base(base->data, base->size));
  LODBAKE_ASSIGN_OR_RETURN(VertexHierarchy h,
                           decode_vhie(vhie->data, vhie->size, std::move(base_mesh)));
  StreamDb out;
  out.h = std::make_unique<VertexHierarchy>(std::move(h));
  LODBAKE_ASSIGN_OR_RETURN(std::vector<RfinRecord> records,
                           decode_rfin_records(rfin->data, rfin->size, *out.h));
  LODBAKE_ASSIGN_OR_RETURN(StreamHierarchy db, StreamHierarchy::create(*out.h, std::move(records)));
  out.db = std::make_unique<StreamHierarchy>(std::move(db));
  return out;
}

StreamReplayOptions stream_options(const Request& request) {
  StreamReplayOptions options;
  options.viewport = request.options.viewport;
  options.tolerance_pixels = request.options.tolerance_pixels;
  options.max_passes = request.options.max_passes;
  return options;
}

// --validate's check of one streamed frame: a valid mesh, one request at
// most and nothing missing.
Status stream_frame_check(const StreamClient& client, const StreamFrameStats& f, size_t i) {
  std::vector<std::string> problems = check_vhier_mesh(client.refiner());
  if (f.missing != 0 || f.requests > 1) {
    problems.push_back(std::to_string(f.missing) + " needed splits missing after " +
                       std::to_string(f.requests) + " requests");
  }
  if (problems.empty()) return Status::ok();
  std::string message = "frame " + std::to_string(i) + ": invalid mesh: " + problems[0];
  for (size_t k = 1; k < problems.size(); ++k)
    message += "; " + problems[k];
  return Status(ErrorKind::kValidation, message);
}

// One client's frames added up (the opening exchange included).
struct StreamTotals {
  uint64_t up = 0, down = 0;
  size_t frames = 0, requests = 0, request_frames = 0, packets = 0, splits = 0, collapses = 0;
  size_t max_triangles = 0;
  double mean_triangles = 0;
};

StreamTotals stream_totals(const std::vector<StreamFrameStats>& frames, uint64_t start_up,
                           uint64_t start_down) {
  StreamTotals t;
  t.up = start_up;
  t.down = start_down;
  t.frames = frames.size();
  for (const StreamFrameStats& f : frames) {
    t.up += f.uplink_bytes;
    t.down += f.downlink_bytes;
    t.requests += f.requests;
    t.request_frames += f.requests != 0;
    t.packets += f.packets;
    t.splits += f.splits;
    t.collapses += f.collapses;
    t.mean_triangles += static_cast<double>(f.triangles);
    t.max_triangles = std::max(t.max_triangles, f.triangles);
  }
  t.mean_triangles /= static_cast<double>(std::max<size_t>(frames.size(), 1));
  return t;
}

// A camera path turned about the vertical axis through the sphere's centre.
std::vector<CameraFrame> turned_path(std::vector<CameraFrame> path, const BoundingSphere& sphere,
                                     float degrees) {
  const float a = degrees * 3.14159265f / 180, c = std::cos(a), s = std::sin(a);
  for (CameraFrame& f : path) {
    for (Vec3f* p : {&f.eye, &f.target}) {
      const float x = (*p)[0] - sphere.center[0], z = (*p)[2] - sphere.center[2];
      (*p)[0] = sphere.center[0] + c * x + s * z;
      (*p)[2] = sphere.center[2] - s * x + c * z;
    }
  }
  return path;
}

// ---- shared by the streaming modes over TCP ----

std::string address_text(const LoopbackAddress& a) {
  return a.host + ":" + std::to_string(a.port);
}

// A client's failed frame, numbered.
Status frame_failure(size_t i, const Status& status) {
  return Status(status.kind(), "frame " + std::to_string(i) + ": " + status.message());
}

// "client 3      ": a served connection's line label.
std::string client_label(size_t k) {
  char label[32];
  std::snprintf(label, sizeof label, "client %-6zu", k);
  return label;
}

// --serve's opening: the listener on the requested port, its address as
// stdout's first line (flushed: a script waits for it), and the server's
// timeouts (a minute: clients start when they like).
struct Serving {
  std::optional<TcpListener> listener;
  std::string address;
  TcpOptions tcp;
  std::chrono::steady_clock::time_point start;
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

// Empty when listening; else the exit code (the failure reported).
std::optional<int> start_serving(const Tool& tool, const Request& request, Serving* out) {
  Result<TcpListener> listener = TcpListener::listen(*request.serve);
  if (!listener.is_ok()) return tool.fail(address_text(*request.serve), listener.status());
  out->listener.emplace(std::move(listener).value());
  out->address = out->listener->host() + ":" + std::to_string(out->listener->port());
  std::cout << out->address << std::endl;
  out->tcp.connect_timeout_ms = 60000;
  out->tcp.io_timeout_ms = 60000;
  out->start = std::chrono::steady_clock::now();
  return std::nullopt;
}

// --connect's camera path, around the sphere the server sent.
Result<std::vector<CameraFrame>> path_around(const Request& request, const BoundingSphere& sphere,
                                             std::string* path_file) {
  Session view_session;
  view_session.sphere = sphere;
  return read_path(request, view_session, path_file);
}

// --clients K (K > 1) in one process: K sessions on one database, client k
// on the scan (even k) or orbit (odd k) path, or on --path, turned by
// 360 k / K degrees; their frames interleaved, as simultaneous clients.
int run_stream_clients(const Tool& tool, const Request& request, const StreamDb& loaded) {
  const StreamHierarchy& db = *loaded.db;
  const StreamReplayOptions options = stream_options(request);
  const size_t k_count = request.clients;
  std::vector<StreamSession> sessions;
  std::vector<std::vector<CameraFrame>> paths;
  std::vector<std::string> names;
  std::vector<float> degrees;
  Session view_session;
  view_session.sphere = db.sphere;
  for (size_t k = 0; k < k_count; ++k) {
    Result<StreamSession> created = StreamSession::create(db, options);
    if (!created.is_ok()) return tool.fail(request.input, created.status());
    sessions.push_back(std::move(created).value());
    Request lane = request;
    if (!tool.has("path")) lane.path = k % 2 == 0 ? "scan" : "orbit";
    std::string path_file;
    Result<std::vector<CameraFrame>> read = read_path(lane, view_session, &path_file);
    if (!read.is_ok()) return tool.fail(path_file, read.status());
    degrees.push_back(360.0f * static_cast<float>(k) / static_cast<float>(k_count));
    paths.push_back(turned_path(std::move(read).value(), db.sphere, degrees.back()));
    names.push_back(lane.path);
  }
  std::vector<std::vector<StreamFrameStats>> frames(k_count);
  size_t longest = 0;
  for (const std::vector<CameraFrame>& p : paths)
    longest = std::max(longest, p.size());
  Progress progress(tool, "streaming");
  for (size_t i = 0; i < longest; ++i) {
    for (size_t k = 0; k < k_count; ++k) {
      if (i >= paths[k].size()) continue;
      Result<StreamFrameStats> f = sessions[k].frame(paths[k][i], db.sphere);
      if (!f.is_ok()) {
        return tool.fail(
            request.input,
            Status(f.status().kind(), "client " + std::to_string(k) + ", frame " +
                                          std::to_string(i) + ": " + f.status().message()));
      }
      if (request.validate) {
        Status checked = stream_frame_check(sessions[k].client(), f.value(), i);
        if (!checked.is_ok()) {
          return tool.fail(request.input, Status(checked.kind(), "client " + std::to_string(k) +
                                                                     ", " + checked.message()));
        }
      }
      frames[k].push_back(f.value());
    }
    progress.update(static_cast<double>(i + 1) / static_cast<double>(longest));
  }
  if (request.validate) {
    for (size_t k = 0; k < k_count; ++k) {
      std::vector<uint32_t> sent = sessions[k].server().sent();
      std::sort(sent.begin(), sent.end());
      if (std::adjacent_find(sent.begin(), sent.end()) != sent.end()) {
        return tool.fail(request.input,
                         Status(ErrorKind::kValidation, "client " + std::to_string(k) +
                                                            ": a vsplit packet was sent twice"));
      }
    }
  }
  StreamTotals all;
  size_t window = 0, buffer = 0, front = 0;
  nlohmann::json lanes = nlohmann::json::array();
  std::ostringstream text;
  for (size_t k = 0; k < k_count; ++k) {
    const StreamTotals t = stream_totals(frames[k], sessions[k].start_uplink_bytes(),
                                         sessions[k].start_downlink_bytes());
    const StreamServerMemory m = sessions[k].server().memory();
    all.up += t.up;
    all.down += t.down;
    all.requests += t.requests;
    all.packets += t.packets;
    all.frames += t.frames;
    window += m.window_bytes;
    buffer += m.buffer_bytes;
    front += m.front_bytes;
    lanes.push_back({{"client", k},
                     {"path", names[k]},
                     {"turned_degrees", degrees[k]},
                     {"frames", t.frames},
                     {"uplink_bytes", t.up},
                     {"requests", t.requests},
                     {"downlink_bytes", t.down},
                     {"packets", t.packets},
                     {"triangles", {{"mean", t.mean_triangles}, {"max", t.max_triangles}}},
                     {"server_memory",
                      {{"window_bytes", m.window_bytes},
                       {"buffer_bytes", m.buffer_bytes},
                       {"front_nodes", m.front_nodes},
                       {"front_bytes", m.front_bytes}}}});
    char label[32];
    std::snprintf(label, sizeof label, "client %-6zu", k);
    text << label << " path " << names[k] << " turned " << degrees[k] << " deg, " << t.frames
         << " frames: uplink " << t.up << " bytes (" << t.requests << " requests), downlink "
         << t.down << " bytes (" << t.packets << " packets); server window " << m.window_bytes
         << " bytes (buffer " << m.buffer_bytes << ") vs a stored front " << m.front_bytes
         << " bytes\n";
  }
  if (tool.json()) {
    tool.print_json({{"schema", kReplaySchema},
                     {"input", request.input},
                     {"mode", request.mode},
                     {"clients", lanes},
                     {"validated", request.validate},
                     {"tolerance_pixels", request.options.tolerance_pixels},
                     {"total",
                      {{"uplink_bytes", all.up},
                       {"downlink_bytes", all.down},
                       {"requests", all.requests},
                       {"packets", all.packets},
                       {"server_window_bytes", window},
                       {"server_buffer_bytes", buffer},
                       {"stored_front_bytes", front}}}});
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode stream, " << k_count
            << " clients on one server in one process, " << all.frames << " frames"
            << (request.validate ? ", every frame validated" : "") << "\n";
  std::cout << "hierarchy     " << db.h->node_count() << " nodes, " << db.h->root_count()
            << " roots, <tree-id, node-id> <" << db.widths.tree_bits << ", " << db.widths.node_bits
            << ">\n";
  std::cout << text.str();
  std::cout << "total         uplink " << all.up << " bytes, downlink " << all.down << " bytes, "
            << all.packets << " packets; server memory " << window << " bytes of windows ("
            << window / k_count << " per client, buffers " << buffer << ") vs stored fronts "
            << front << " bytes\n";
  return 0;
}

// --serve: a TCP server on loopback for --clients connections, each on its
// own thread with its own session; the address on stdout's first line.
int run_stream_serve(const Tool& tool, const Request& request, const StreamDb& loaded) {
  const StreamHierarchy& db = *loaded.db;
  Serving serving;
  if (std::optional<int> failed = start_serving(tool, request, &serving)) return *failed;
  const std::string& address = serving.address;
  Result<std::vector<StreamServedClient>> served = serve_stream_clients(
      db, &*serving.listener, request.clients, StreamServerOptions(), serving.tcp);
  const double seconds = serving.seconds();
  if (!served.is_ok()) return tool.fail(address, served.status());
  uint64_t up = 0, down = 0;
  size_t packets = 0, window = 0, front = 0;
  const StreamServedClient* failed = nullptr;
  nlohmann::json lanes = nlohmann::json::array();
  std::ostringstream text;
  for (size_t k = 0; k < served.value().size(); ++k) {
    const StreamServedClient& c = served.value()[k];
    up += c.uplink_bytes;
    down += c.downlink_bytes;
    packets += c.packets;
    window += c.memory.window_bytes;
    front += c.memory.front_bytes;
    if (!c.status.is_ok() && failed == nullptr) failed = &c;
    lanes.push_back({{"client", k},
                     {"ok", c.status.is_ok()},
                     {"error", c.status.message()},
                     {"uplink_bytes", c.uplink_bytes},
                     {"downlink_bytes", c.downlink_bytes},
                     {"requests", c.requests},
                     {"packets", c.packets},
                     {"resumed_splits", c.resumed},
                     {"server_memory",
                      {{"window_bytes", c.memory.window_bytes},
                       {"buffer_bytes", c.memory.buffer_bytes},
                       {"front_nodes", c.memory.front_nodes},
                       {"front_bytes", c.memory.front_bytes}}}});
    text << client_label(k) << " uplink " << c.uplink_bytes << " bytes (" << c.requests
         << " requests), downlink " << c.downlink_bytes << " bytes (" << c.packets << " packets"
         << (c.resumed != 0 ? ", resumed holding " + std::to_string(c.resumed) + " splits" : "")
         << "); server window " << c.memory.window_bytes << " bytes (buffer "
         << c.memory.buffer_bytes << ") vs a stored front " << c.memory.front_bytes << " bytes"
         << (c.status.is_ok() ? "" : "; ended: " + c.status.message()) << "\n";
  }
  if (tool.json()) {
    tool.print_json({{"schema", kReplaySchema},
                     {"input", request.input},
                     {"mode", request.mode},
                     {"served", address},
                     {"seconds", seconds},
                     {"clients", lanes},
                     {"total",
                      {{"uplink_bytes", up},
                       {"downlink_bytes", down},
                       {"packets", packets},
                       {"server_window_bytes", window},
                       {"stored_front_bytes", front}}}});
  } else {
    std::cout << "served        " << request.input << ": mode stream on " << address << ", "
              << served.value().size() << " clients in " << seconds << " s\n";
    std::cout << text.str();
    std::cout << "total         uplink " << up << " bytes, downlink " << down << " bytes, "
              << packets << " packets; server memory " << window
              << " bytes of windows vs stored fronts " << front << " bytes\n";
  }
  if (failed != nullptr) return tool.fail(address, failed->status);
  return 0;
}

// --connect: a client on its camera path against a server; the base and
// scene messages give it everything, so no FILE.
int run_stream_connect(const Tool& tool, const Request& request) {
  const std::string address = address_text(*request.connect);
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(*request.connect);
  if (!t.is_ok()) return tool.fail(address, t.status());
  Result<StreamClientSession> started =
      StreamClientSession::start(t.value().get(), stream_options(request));
  if (!started.is_ok()) return tool.fail(address, started.status());
  StreamClientSession& session = started.value();
  std::string path_file;
  Result<std::vector<CameraFrame>> read = path_around(request, session.sphere(), &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();
  std::vector<StreamFrameStats> frames;
  Progress progress(tool, "streaming");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<StreamFrameStats> f = session.frame(path[i]);
    if (!f.is_ok()) return tool.fail(address, frame_failure(i, f.status()));
    if (request.validate) {
      Status checked = stream_frame_check(session.client(), f.value(), i);
      if (!checked.is_ok()) return tool.fail(address, checked);
    }
    frames.push_back(f.value());
    progress.update(static_cast<double>(i + 1) / static_cast<double>(path.size()));
  }
  t.value()->close();
  if (!request.csv.empty()) {
    std::ostringstream csv;
    csv << "frame,uplink_bytes,downlink_bytes,requests,packets,splits,collapses,triangles,front\n";
    for (size_t i = 0; i < frames.size(); ++i) {
      const StreamFrameStats& f = frames[i];
      csv << i << ',' << f.uplink_bytes << ',' << f.downlink_bytes << ',' << f.requests << ','
          << f.packets << ',' << f.splits << ',' << f.collapses << ',' << f.triangles << ','
          << f.front_size << '\n';
    }
    Status written = write_file_atomic(request.csv, csv.str());
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }
  const StreamTotals tot =
      stream_totals(frames, session.start_uplink_bytes(), session.start_downlink_bytes());
  const StreamIdWidths& widths = session.client().widths();
  if (tool.json()) {
    tool.print_json(
        {{"schema", kReplaySchema},
         {"connect", address},
         {"mode", request.mode},
         {"path", request.path},
         {"frames", tot.frames},
         {"validated", request.validate},
         {"tolerance_pixels", request.options.tolerance_pixels},
         {"uplink", {{"bytes", tot.up}, {"requests", tot.requests}}},
         {"downlink",
          {{"bytes", tot.down}, {"base_bytes", session.base_bytes()}, {"packets", tot.packets}}},
         {"packet", {{"topology_bits", 3 * widths.id_bits()}}},
         {"client",
          {{"splits", tot.splits},
           {"collapses", tot.collapses},
           {"triangles", {{"mean", tot.mean_triangles}, {"max", tot.max_triangles}}}}}});
    return 0;
  }
  std::cout << "replay        " << address << ": mode stream over TCP, path " << request.path
            << ", " << tot.frames << " frames"
            << (request.validate ? ", every frame validated" : "") << "\n";
  std::cout << "uplink        " << tot.up << " bytes, " << tot.requests << " view requests in "
            << tot.request_frames << " of " << tot.frames << " frames\n";
  std::cout << "downlink      " << tot.down << " bytes: base " << session.base_bytes() << ", "
            << tot.packets << " vsplit packets\n";
  std::cout << "packet        topology " << 3 * widths.id_bits() << " bits (3 x "
            << widths.id_bits() << "; the paper 96)\n";
  std::cout << "client        " << tot.splits << " splits, " << tot.collapses
            << " collapses, triangles mean " << tot.mean_triangles << ", max " << tot.max_triangles
            << "\n";
  return 0;
}

// Mode stream: the hierarchy served frame by frame to a client that starts
// from the base mesh (Kim, Lee and Kobbelt 2005), bytes counted both ways,
// and the view-independent baseline of section 8.
int run_stream(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<StreamDb> loaded = load_stream_db(bytes);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  if (request.serve) return run_stream_serve(tool, request, loaded.value());
  if (request.clients > 1) return run_stream_clients(tool, request, loaded.value());
  const StreamHierarchy& stream_db = *loaded.value().db;
  const VertexHierarchy& hierarchy = *loaded.value().h;
  Result<StreamSession> created = StreamSession::create(stream_db, stream_options(request));
  if (!created.is_ok()) return tool.fail(request.input, created.status());
  StreamSession& session = created.value();

  Session view_session;
  view_session.sphere = stream_db.sphere;
  std::string path_file;
  Result<std::vector<CameraFrame>> read = read_path(request, view_session, &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();

  std::vector<StreamFrameStats> frames;
  Progress progress(tool, "streaming");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<StreamFrameStats> f = session.frame(path[i], view_session.sphere);
    if (!f.is_ok()) {
      return tool.fail(request.input, Status(f.status().kind(), "frame " + std::to_string(i) +
                                                                    ": " + f.status().message()));
    }
    frames.push_back(f.value());
    if (request.validate) {
      Status checked = stream_frame_check(session.client(), f.value(), i);
      if (!checked.is_ok()) return tool.fail(request.input, checked);
    }
    progress.update(static_cast<double>(i + 1) / path.size());
  }
  std::vector<uint32_t> sent = session.server().sent();
  if (request.validate) {
    std::sort(sent.begin(), sent.end());
    if (std::adjacent_find(sent.begin(), sent.end()) != sent.end()) {
      return tool.fail(request.input,
                       Status(ErrorKind::kValidation, "a vsplit packet was sent twice"));
    }
  }
  Result<StreamBaseline> baseline =
      view_independent_baseline(stream_db, session.server().sent(), session.start_downlink_bytes());
  if (!baseline.is_ok()) return tool.fail(request.input, baseline.status());
  const StreamBaseline& vi = baseline.value();

  if (!request.csv.empty()) {
    std::ostringstream csv;
    csv << "frame,uplink_bytes,downlink_bytes,requests,packets,splits,collapses,triangles,"
           "front,window_bytes,buffer_bytes,front_bytes\n";
    for (size_t i = 0; i < frames.size(); ++i) {
      const StreamFrameStats& f = frames[i];
      csv << i << ',' << f.uplink_bytes << ',' << f.downlink_bytes << ',' << f.requests << ','
          << f.packets << ',' << f.splits << ',' << f.collapses << ',' << f.triangles << ','
          << f.front_size << ',' << f.server.window_bytes << ',' << f.server.buffer_bytes << ','
          << f.server.front_bytes << '\n';
    }
    Status written = write_file_atomic(request.csv, csv.str());
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  uint64_t up = session.start_uplink_bytes(), down = session.start_downlink_bytes();
  size_t requests = 0, packets = 0, splits = 0, collapses = 0, max_triangles = 0;
  size_t max_window = 0, max_buffer = 0, max_front_bytes = 0, request_frames = 0;
  double triangles = 0;
  for (const StreamFrameStats& f : frames) {
    up += f.uplink_bytes;
    down += f.downlink_bytes;
    requests += f.requests;
    request_frames += f.requests != 0;
    packets += f.packets;
    splits += f.splits;
    collapses += f.collapses;
    triangles += static_cast<double>(f.triangles);
    max_triangles = std::max(max_triangles, f.triangles);
    max_window = std::max(max_window, f.server.window_bytes);
    max_buffer = std::max(max_buffer, f.server.buffer_bytes);
    max_front_bytes = std::max(max_front_bytes, f.server.front_bytes);
  }
  triangles /= static_cast<double>(std::max<size_t>(frames.size(), 1));
  const StreamServerMemory memory = session.server().memory();
  const StreamIdWidths widths = stream_db.widths;
  const int topology_bits = 3 * widths.id_bits();
  const double ratio = static_cast<double>(down) / static_cast<double>(vi.bytes);
  const double window_share =
      static_cast<double>(memory.window_bytes) / static_cast<double>(memory.front_bytes);
  const double buffer_share =
      static_cast<double>(memory.buffer_bytes) / static_cast<double>(memory.front_bytes);
  if (tool.json()) {
    tool.print_json(
        {{"schema", kReplaySchema},
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
         {"tolerance", request.tolerance},
         {"tolerance_pixels", request.options.tolerance_pixels},
         {"hierarchy",
          {{"nodes", hierarchy.node_count()},
           {"roots", hierarchy.root_count()},
           {"splits", vi.pm_splits},
           {"tree_bits", widths.tree_bits},
           {"node_bits", widths.node_bits}}},
         {"uplink",
          {{"bytes", up}, {"requests", requests}, {"frames_with_requests", request_frames}}},
         {"downlink",
          {{"bytes", down}, {"base_bytes", session.base_bytes()}, {"packets", packets}}},
         {"packet",
          {{"topology_bits", topology_bits},
           {"paper_topology_bits", 96},
           {"earlier_topology_bits", {192, 256}},
           {"mean_bits", packets == 0
                             ? 0.0
                             : static_cast<double>(vi.sent_bits) / static_cast<double>(packets)}}},
         {"client",
          {{"splits", splits},
           {"collapses", collapses},
           {"triangles", {{"mean", triangles}, {"max", max_triangles}}}}},
         {"server_memory",
          {{"window_bytes", memory.window_bytes},
           {"buffer_bytes", memory.buffer_bytes},
           {"front_nodes", memory.front_nodes},
           {"front_bytes", memory.front_bytes},
           {"max_window_bytes", max_window},
           {"max_buffer_bytes", max_buffer},
           {"max_front_bytes", max_front_bytes}}},
         {"view_independent",
          {{"prefix_splits", vi.prefix},
           {"pm_splits", vi.pm_splits},
           {"bytes", vi.bytes},
           {"full_bytes", vi.full_bytes},
           {"view_dependent_share", ratio}}}});
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode stream, path " << request.path << ", "
            << frames.size() << " frames" << (request.validate ? ", every frame validated" : "")
            << "\n";
  std::cout << "hierarchy     " << hierarchy.node_count() << " nodes, " << hierarchy.root_count()
            << " roots, " << vi.pm_splits << " splits, <tree-id, node-id> <" << widths.tree_bits
            << ", " << widths.node_bits << ">\n";
  std::cout << "view          " << request.options.viewport.width << "x"
            << request.options.viewport.height << ", fov " << request.fov_degrees
            << " deg, tolerance " << request.options.tolerance_pixels << " px\n";
  std::cout << "uplink        " << up << " bytes, " << requests << " view requests in "
            << request_frames << " of " << frames.size() << " frames\n";
  std::cout << "downlink      " << down << " bytes: base " << session.base_bytes() << ", "
            << packets << " vsplit packets of " << vi.pm_splits << "\n";
  std::cout << "packet        topology " << topology_bits << " bits (3 x " << widths.id_bits()
            << "; the paper 96, earlier schemes 192-256), mean "
            << (packets == 0 ? 0.0
                             : static_cast<double>(vi.sent_bits) / static_cast<double>(packets))
            << " bits with geometry and refinement data\n";
  std::cout << "client        " << splits << " splits, " << collapses
            << " collapses, triangles mean " << triangles << ", max " << max_triangles << "\n";
  std::cout << "server memory window " << memory.window_bytes << " bytes (buffer "
            << memory.buffer_bytes << ") vs a stored vertex front " << memory.front_bytes
            << " bytes (" << memory.front_nodes << " nodes): " << 100 * window_share << "% ("
            << 100 * buffer_share << "%)\n";
  std::cout << "vs view-indep " << down << " vs " << vi.bytes << " bytes (" << 100 * ratio
            << "%): the PM's fixed order needs a prefix of " << vi.prefix << " of " << vi.pm_splits
            << " splits to hold the " << packets << " sent; the whole PM is " << vi.full_bytes
            << " bytes (the paper: bunny 177,120 vs 827,688, dragon 946,400 vs 3,816,384)\n";
  return 0;
}

// Mode vtrees' database: the container's hierarchy, refinement data and
// vertex trees.
struct VtreesDb {
  std::unique_ptr<VertexHierarchy> h;
  std::unique_ptr<VertexTrees> trees;  // VtreesDatabase points at it
  std::unique_ptr<VtreesDatabase> db;
};

Result<VtreesDb> load_vtrees_db(const Bytes& bytes) {
  LODBAKE_ASSIGN_OR_RETURN(Container container, read_container(bytes.data(), bytes.size()));
  for (const char* tag : {kBaseTag, kVhieTag, kRfinTag, kVtreTag}) {
    if (container.find(tag) == nullptr) {
      return invalid_input(std::string("container has no ") + tag +
                           " section; mode vtrees needs BASE + VHIE + RFIN + VTRE "
                           "(lodbake-hierarchy --sections vhie,vtre)");
    }
  }
  const Section* base = container.find(kBaseTag);
  const Section* vhie = container.find(kVhieTag);
  const Section* rfin = container.find(kRfinTag);
  const Section* vtre = container.find(kVtreTag);
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh base_mesh, decode_base(base->data, base->size));
  LODBAKE_ASSIGN_OR_RETURN(VertexHierarchy h,
                           decode_vhie(vhie->data, vhie->size, std::move(base_mesh)));
  VtreesDb out;
  out.h = std::make_unique<VertexHierarchy>(std::move(h));
  LODBAKE_ASSIGN_OR_RETURN(std::vector<RfinRecord> records,
                           decode_rfin_records(rfin->data, rfin->size, *out.h));
  // The same dequantized refinement data as mode stream's server.
  LODBAKE_ASSIGN_OR_RETURN(StreamHierarchy refinement,
                           StreamHierarchy::create(*out.h, std::move(records)));
  LODBAKE_ASSIGN_OR_RETURN(VertexTrees trees, decode_vtre(vtre->data, vtre->size));
  out.trees = std::make_unique<VertexTrees>(std::move(trees));
  LODBAKE_ASSIGN_OR_RETURN(VtreesDatabase db,
                           VtreesDatabase::create(*out.trees, *out.h, refinement.data));
  out.db = std::make_unique<VtreesDatabase>(std::move(db));
  return out;
}

VtreesReplayOptions vtrees_options(const Request& request) {
  VtreesReplayOptions options;
  options.viewport = request.options.viewport;
  options.tolerance_pixels = request.options.tolerance_pixels;
  return options;
}

// --csv rows of mode vtrees, in process or over TCP.
Status write_vtrees_csv(const std::string& file, const std::vector<VtreesFrameStats>& frames) {
  std::ostringstream csv;
  csv << "frame,uplink_bytes,downlink_bytes,left_records,right_records,traces,trace_updates,"
         "downs,ups,visible,triangles,reconstruct_ms,select_ms\n";
  for (size_t i = 0; i < frames.size(); ++i) {
    const VtreesFrameStats& f = frames[i];
    csv << i << ',' << f.uplink_bytes << ',' << f.downlink_bytes << ',' << f.left_records << ','
        << f.right_records << ',' << f.traces << ',' << f.trace_updates << ',' << f.downs << ','
        << f.ups << ',' << f.visible << ',' << f.triangles << ',' << f.reconstruct_ms << ','
        << f.select_ms << '\n';
  }
  return write_file_atomic(file, csv.str());
}

// One vtrees client's frames and records added up (the opening included):
// what the in-process report and the --connect report share.
struct VtreesTotals {
  uint64_t up = 0, down = 0;
  size_t max_triangles = 0;
  double triangles = 0, reconstruct_ms = 0, select_ms = 0;
  double base_b = 0, left_b = 0, right_b = 0, child_b = 0;  // mean record bytes
  uint64_t record_bits = 0;
  double per_node_us = 0;
};

VtreesTotals vtrees_totals(const VtreesReceived& got, const std::vector<VtreesFrameStats>& frames,
                           uint64_t start_down, double start_ms) {
  VtreesTotals t;
  t.down = start_down;
  t.reconstruct_ms = start_ms;
  for (const VtreesFrameStats& f : frames) {
    t.up += f.uplink_bytes;
    t.down += f.downlink_bytes;
    t.triangles += static_cast<double>(f.triangles);
    t.max_triangles = std::max(t.max_triangles, f.triangles);
    t.reconstruct_ms += f.reconstruct_ms;
    t.select_ms += f.select_ms;
  }
  t.triangles /= static_cast<double>(std::max<size_t>(frames.size(), 1));
  auto mean_bytes = [](uint64_t bits, size_t count) {
    return count == 0 ? 0.0 : static_cast<double>(bits) / 8 / static_cast<double>(count);
  };
  t.base_b = mean_bytes(got.base_bits, got.base_records);
  t.left_b = mean_bytes(got.left_bits, got.left_records);
  t.right_b = mean_bytes(got.right_bits, got.right_records);
  t.child_b = mean_bytes(got.left_bits + got.right_bits, got.left_records + got.right_records);
  t.record_bits = got.base_bits + got.left_bits + got.right_bits;
  t.per_node_us =
      got.left_records == 0
          ? 0.0
          : 1000 * t.reconstruct_ms / static_cast<double>(got.base_records + 2 * got.left_records);
  return t;
}

// The report's "records", "moves" and "client" parts (JSON and text).
nlohmann::json vtrees_records_json(const VtreesReceived& got, const VtreesTotals& t) {
  return {{"base", {{"count", got.base_records}, {"mean_bytes", t.base_b}, {"paper_bytes", 22}}},
          {"left", {{"count", got.left_records}, {"mean_bytes", t.left_b}}},
          {"right", {{"count", got.right_records}, {"mean_bytes", t.right_b}}},
          {"child_mean_bytes", t.child_b},
          {"paper_child_bytes", 20},
          {"traces", got.traces},
          {"trace_bytes", static_cast<double>(got.trace_bits) / 8},
          {"trace_updates", got.trace_updates}};
}

nlohmann::json vtrees_client_json(const VtreesClient& client, const VtreesTotals& t) {
  return {{"nodes_held", client.nodes_held()},
          {"triangles", {{"mean", t.triangles}, {"max", t.max_triangles}}},
          {"reconstruct_ms", t.reconstruct_ms},
          {"reconstruct_us_per_node", t.per_node_us},
          {"select_ms", t.select_ms}};
}

// From "downlink" to "reconstruct".
void print_vtrees_lines(const VtreesClient& client, const VtreesTotals& t, size_t node_count) {
  const VtreesReceived& got = client.received();
  std::cout << "uplink        " << t.up << " bytes, one view per frame\n";
  std::cout << "downlink      " << t.down << " bytes in " << got.messages << " messages, "
            << (t.record_bits + 7) / 8 << " of them node records\n";
  std::cout << "records       base " << got.base_records << " x " << t.base_b
            << " B (the paper 22), "
            << "left " << got.left_records << " x " << t.left_b << " B, right " << got.right_records
            << " x " << t.right_b << " B: child mean " << t.child_b << " B (the paper 20)\n";
  std::cout << "trace-up      " << got.traces << " first transmitted parents in records ("
            << static_cast<double>(got.trace_bits) / 8 << " B), " << got.trace_updates
            << " updates\n";
  std::cout << "list moves    " << got.left_records << " down at new nodes, " << got.downs
            << " down and " << got.ups << " up over held nodes\n";
  std::cout << "client        " << client.nodes_held() << " of " << node_count
            << " nodes held, triangles mean " << t.triangles << ", max " << t.max_triangles << "\n";
  std::cout << "reconstruct   " << t.reconstruct_ms << " ms in all (" << t.per_node_us
            << " us per node), triangle selection " << t.select_ms << " ms in all\n";
}

// Whether the client's triangles over its own positions overlap or leave
// holes (fronts the trees allow and the split DAG does not).
bool vtrees_overlap(const VtreesClient& client, const std::vector<Triangle>& triangles) {
  TriangleMesh mesh;
  mesh.positions = client.positions();
  mesh.triangles = triangles;
  return !triangulation_problems(check_mesh(mesh)).empty();
}

// --serve: a TCP server on loopback for --clients connections, each on its
// own thread with its own session (visible vertex list); the address on
// stdout's first line. A record sent twice to one client is a validation
// failure (exit 7).
int run_vtrees_serve(const Tool& tool, const Request& request, const VtreesDb& loaded) {
  Serving serving;
  if (std::optional<int> failed = start_serving(tool, request, &serving)) return *failed;
  const std::string& address = serving.address;
  Result<std::vector<VtreesServedClient>> served = serve_vtrees_clients(
      *loaded.db, &*serving.listener, request.clients, kMaxVtreesItems, serving.tcp);
  const double seconds = serving.seconds();
  if (!served.is_ok()) return tool.fail(address, served.status());
  uint64_t up = 0, down = 0;
  size_t records = 0, state = 0;
  bool any_twice = false;
  Status failed;
  nlohmann::json lanes = nlohmann::json::array();
  std::ostringstream text;
  for (size_t k = 0; k < served.value().size(); ++k) {
    const VtreesServedClient& c = served.value()[k];
    std::vector<uint32_t> sent = c.sent_nodes;
    std::sort(sent.begin(), sent.end());
    const bool twice = std::adjacent_find(sent.begin(), sent.end()) != sent.end();
    any_twice = any_twice || twice;
    up += c.uplink_bytes;
    down += c.downlink_bytes;
    records += c.sent_nodes.size();
    state += c.state_bytes;
    if (failed.is_ok() && !c.status.is_ok()) failed = c.status;
    if (failed.is_ok() && twice) {
      failed = Status(ErrorKind::kValidation,
                      "client " + std::to_string(k) + ": a node record was sent twice");
    }
    lanes.push_back({{"client", k},
                     {"ok", c.status.is_ok()},
                     {"error", c.status.message()},
                     {"uplink_bytes", c.uplink_bytes},
                     {"downlink_bytes", c.downlink_bytes},
                     {"views", c.requests},
                     {"messages", c.messages},
                     {"records", c.sent_nodes.size()},
                     {"visible", c.visible},
                     {"server_state_bytes", c.state_bytes}});
    text << client_label(k) << " uplink " << c.uplink_bytes << " bytes (" << c.requests
         << " views), downlink " << c.downlink_bytes << " bytes (" << c.messages
         << " frame messages, " << c.sent_nodes.size() << " node records); server state "
         << c.state_bytes << " bytes, " << c.visible << " visible vertices"
         << (c.status.is_ok() ? "" : "; ended: " + c.status.message()) << "\n";
  }
  if (tool.json()) {
    tool.print_json({{"schema", kReplaySchema},
                     {"input", request.input},
                     {"mode", request.mode},
                     {"served", address},
                     {"seconds", seconds},
                     {"clients", lanes},
                     {"total",
                      {{"uplink_bytes", up},
                       {"downlink_bytes", down},
                       {"records", records},
                       {"server_state_bytes", state}}}});
  } else {
    std::cout << "served        " << request.input << ": mode vtrees on " << address << ", "
              << served.value().size() << " clients in " << seconds << " s\n";
    std::cout << text.str();
    std::cout << "total         uplink " << up << " bytes, downlink " << down << " bytes, "
              << records << " node records, "
              << (any_twice ? "some sent twice" : "none sent twice to a client")
              << "; server state " << state << " bytes\n";
  }
  if (!failed.is_ok()) return tool.fail(address, failed);
  return 0;
}

// --connect: a vtrees client on its camera path against a server; the
// trees and scene messages give it everything, so no FILE. --validate
// checks what a client can alone: every answer complete and applied (the
// client refuses a record twice or a move it cannot make) and counts the
// frames whose triangles overlap.
int run_vtrees_connect(const Tool& tool, const Request& request) {
  const std::string address = address_text(*request.connect);
  Result<std::unique_ptr<StreamTransport>> t =
      tcp_connect(*request.connect, TcpOptions(), kVtreesMessages);
  if (!t.is_ok()) return tool.fail(address, t.status());
  Result<VtreesClientSession> started =
      VtreesClientSession::start(t.value().get(), vtrees_options(request));
  if (!started.is_ok()) return tool.fail(address, started.status());
  VtreesClientSession& session = started.value();
  std::string path_file;
  Result<std::vector<CameraFrame>> read = path_around(request, session.sphere(), &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();
  std::vector<VtreesFrameStats> frames;
  size_t overlap_frames = 0;
  Progress progress(tool, "transmitting");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<VtreesFrameStats> f = session.frame(path[i]);
    if (!f.is_ok()) return tool.fail(address, frame_failure(i, f.status()));
    frames.push_back(f.value());
    if (request.validate && vtrees_overlap(session.client(), session.triangles())) ++overlap_frames;
    progress.update(static_cast<double>(i + 1) / static_cast<double>(path.size()));
  }
  t.value()->close();
  if (!request.csv.empty()) {
    Status written = write_vtrees_csv(request.csv, frames);
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }
  const VtreesClient& client = session.client();
  const VtreesWidths& w = client.widths();
  const size_t node_count = size_t{w.base_count} + 2 * size_t{w.split_count};
  const VtreesTotals tot = vtrees_totals(client.received(), frames, session.start_downlink_bytes(),
                                         session.trees_reconstruct_ms());
  if (tool.json()) {
    tool.print_json(
        {{"schema", kReplaySchema},
         {"connect", address},
         {"mode", request.mode},
         {"path", request.path},
         {"frames", frames.size()},
         {"validated", request.validate},
         {"tolerance_pixels", request.options.tolerance_pixels},
         {"trees",
          {{"nodes", node_count},
           {"base_nodes", w.base_count},
           {"splits", w.split_count},
           {"id_bits", w.id_bits()}}},
         {"uplink", {{"bytes", tot.up}, {"views", frames.size()}}},
         {"downlink",
          {{"bytes", tot.down},
           {"trees_message_bytes", session.trees_bytes()},
           {"record_bytes", (tot.record_bits + 7) / 8},
           {"messages", client.received().messages}}},
         {"records", vtrees_records_json(client.received(), tot)},
         {"moves", {{"down", client.received().downs}, {"up", client.received().ups}}},
         {"client", vtrees_client_json(client, tot)},
         {"overlap_frames", request.validate ? nlohmann::json(overlap_frames) : nlohmann::json()}});
    return 0;
  }
  std::cout << "replay        " << address << ": mode vtrees over TCP, path " << request.path
            << ", " << frames.size() << " frames"
            << (request.validate ? ", every answer validated" : "") << "\n";
  std::cout << "trees         " << node_count << " nodes: " << w.base_count << " base, "
            << w.split_count << " splits, " << w.id_bits() << "-bit ids\n";
  print_vtrees_lines(client, tot, node_count);
  if (request.validate) {
    std::cout << "validate      every answer complete and applied, no record received twice; "
              << overlap_frames << " of " << frames.size()
              << " frames had overlapping or missing triangles (the server's list is checked "
                 "in process only)\n";
  }
  return 0;
}

// Mode vtrees: vertex-tree transmission (To, Lau & Green 2001, section 5):
// the server's visible vertex list moves along the camera path, the client
// rebuilds the trees from the node records and selects its triangles.
int run_vtrees(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<VtreesDb> loaded = load_vtrees_db(bytes);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  if (request.serve) return run_vtrees_serve(tool, request, loaded.value());
  const VertexTrees& trees = *loaded.value().trees;
  const VtreesDatabase& db = *loaded.value().db;
  Result<VtreesSession> created = VtreesSession::create(db, vtrees_options(request));
  if (!created.is_ok()) return tool.fail(request.input, created.status());
  VtreesSession& session = created.value();

  Session view_session;
  view_session.sphere = db.sphere;
  std::string path_file;
  Result<std::vector<CameraFrame>> read = read_path(request, view_session, &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();

  std::vector<VtreesFrameStats> frames;
  size_t overlap_frames = 0;  // --validate: lists whose triangles are no clean triangulation
  Progress progress(tool, "transmitting");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<VtreesFrameStats> f = session.frame(path[i], view_session.sphere);
    if (!f.is_ok()) return tool.fail(request.input, frame_failure(i, f.status()));
    frames.push_back(f.value());
    if (request.validate) {
      // The client's reconstruction must be exact: its list is the server's
      // and its triangles are VisibleVertexList's on the full trees.
      const VisibleVertexList& list = session.server().list();
      std::string problem;
      for (uint32_t v = 0; problem.empty() && v < trees.positions.size(); ++v) {
        if (session.client().visible_node(v) != list.visible_node(v))
          problem =
              "the client's visible node of vertex " + std::to_string(v) + " is not the server's";
      }
      if (problem.empty() &&
          sorted_canonical(session.triangles()) != sorted_canonical(list.triangles())) {
        problem = "the client's triangles are not the trees' own selection for its list";
      }
      if (!problem.empty()) {
        return tool.fail(request.input, Status(ErrorKind::kValidation,
                                               "frame " + std::to_string(i) + ": " + problem));
      }
      if (vtrees_overlap(session.client(), session.triangles())) ++overlap_frames;
    }
    progress.update(static_cast<double>(i + 1) / path.size());
  }
  if (request.validate) {
    std::vector<uint32_t> sent = session.server().sent_nodes();
    std::sort(sent.begin(), sent.end());
    if (std::adjacent_find(sent.begin(), sent.end()) != sent.end() ||
        sent.size() != session.client().nodes_held()) {
      return tool.fail(request.input,
                       Status(ErrorKind::kValidation, "a node record was sent twice"));
    }
  }

  if (!request.csv.empty()) {
    Status written = write_vtrees_csv(request.csv, frames);
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  const VtreesReceived& got = session.client().received();
  const VtreesTotals tot =
      vtrees_totals(got, frames, session.trees_bytes(), session.trees_reconstruct_ms());
  const size_t splits = trees.split_count();
  if (tool.json()) {
    tool.print_json(
        {{"schema", kReplaySchema},
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
         {"tolerance", request.tolerance},
         {"tolerance_pixels", request.options.tolerance_pixels},
         {"trees",
          {{"nodes", trees.node_count()},
           {"base_nodes", trees.base_vertex_count},
           {"splits", splits},
           {"id_bits", db.widths.id_bits()}}},
         {"uplink", {{"bytes", tot.up}, {"views", frames.size()}}},
         {"downlink",
          {{"bytes", tot.down},
           {"trees_message_bytes", session.trees_bytes()},
           {"record_bytes", (tot.record_bits + 7) / 8},
           {"messages", got.messages}}},
         {"records", vtrees_records_json(got, tot)},
         {"moves", {{"down", got.downs}, {"up", got.ups}}},
         {"client", vtrees_client_json(session.client(), tot)},
         {"server_state_bytes", session.server().state_bytes()},
         {"overlap_frames", request.validate ? nlohmann::json(overlap_frames) : nlohmann::json()}});
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode vtrees, path " << request.path << ", "
            << frames.size() << " frames" << (request.validate ? ", every frame validated" : "")
            << "\n";
  std::cout << "trees         " << trees.node_count() << " nodes: " << trees.base_vertex_count
            << " base, " << splits << " splits, " << db.widths.id_bits() << "-bit ids\n";
  std::cout << "view          " << request.options.viewport.width << "x"
            << request.options.viewport.height << ", fov " << request.fov_degrees
            << " deg, tolerance " << request.options.tolerance_pixels << " px\n";
  print_vtrees_lines(session.client(), tot, trees.node_count());
  if (request.validate) {
    std::cout << "validate      the client's list and triangles were the server's every frame, "
                 "no record sent twice; "
              << overlap_frames << " of " << frames.size()
              << " frames had overlapping or missing triangles (fronts the trees allow and the "
                 "split DAG does not)\n";
  }
  return 0;
}

int run(const Tool& tool, const Request& request) {
  if (request.connect) {
    return request.mode == "vtrees" ? run_vtrees_connect(tool, request)
                                    : run_stream_connect(tool, request);
  }
  Result<Bytes> bytes = read_file(request.input);
  if (!bytes.is_ok()) return tool.fail(request.input, bytes.status());
  if (request.mode == "sets") return run_sets(tool, request, bytes.value());
  if (request.mode == "stream") return run_stream(tool, request, bytes.value());
  if (request.mode == "vtrees") return run_vtrees(tool, request, bytes.value());
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

// "1.5" pixels or "0.1%" of the viewport height; nothing when malformed or
// negative. 0 asks for every split the view allows (modes stream and vtrees:
// every split).
std::optional<float> tolerance_pixels(const std::string& text, uint32_t height) {
  const bool percent = !text.empty() && text.back() == '%';
  const std::string number = percent ? text.substr(0, text.size() - 1) : text;
  float value = 0;
  const auto parsed = std::from_chars(number.data(), number.data() + number.size(), value);
  if (number.empty() || parsed.ec != std::errc() || parsed.ptr != number.data() + number.size() ||
      !(value >= 0) || !std::isfinite(value)) {
    return std::nullopt;
  }
  if (percent) {
    if (value > 100) return std::nullopt;
    value = value / 100 * static_cast<float>(height);
  }
  return value;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  Tool tool(
      "lodbake-replay",
      "FILE.lbk [--mode vhier|dag|fan|sets|stream|vtrees] [--path scan|orbit|FILE] [options]\n"
      "       lodbake-replay --mode stream|vtrees --connect 127.0.0.1:PORT [--path ...] "
      "[options]",
      "Replays a camera path on a container's view-dependent structure and reports,\n"
      "per frame, the refinement operations, fronts, triangles and adapt time; or\n"
      "(mode sets) runs the SETS strip paper's LoD-recovery tests.\n"
      "Mode vhier (default): BASE + VHIE + RFIN from lodbake-hierarchy; the vertex\n"
      "front is refined while a node's bounding sphere meets the view frustum, its\n"
      "normal cone is not entirely back-facing and its deviation projects to more than\n"
      "--tolerance pixels, and coarsened where none holds (Hoppe 1997).\n"
      "Mode dag: BASE + VSPL + DAGE from lodbake-hierarchy; MANAGE-TRAVERSAL (Zheng &\n"
      "Chan 2006): collapses of Fc whose projected error is under --tolerance, then\n"
      "splits of Fs over it, at most --changes of each per frame, within --budget\n"
      "triangles in BUDGET-MODE; with the priority-oriented, linear (FIFO kept across\n"
      "frames) or constant-time (--changes nodes visited) traversal, or all three side\n"
      "by side; the linear and constant-time ones report their accuracy, the share of\n"
      "the priority-oriented traversal's triangles they also have.\n"
      "Mode fan: BASE + FANH from lodbake-fan; from the coarsest mesh, the active\n"
      "nodes are scanned each frame and each fan moves toward its target merge\n"
      "pointer (error projected at its vertex against --tolerance, all merged out of\n"
      "view) by one fan-merge / fan-split when the target is an end of its fine path\n"
      "at least --coarse x its children away, else by edge collapses / vertex splits\n"
      "(Livny, Sokolovsky & El-Sana 2007).\n"
      "Mode sets: BASE + VSPL + SETS from lodbake-strips; not camera-driven (no --path\n"
      "or view options): each test recovers --percent of all LoDs, spaced linearly or\n"
      "exponentially (--spacing), from LoD 0 (the full mesh) to the coarsest and back,\n"
      "each LoD with a fresh and a coherent recovery timed alone (Belmonte et al. 2006).\n"
      "Mode stream: BASE + VHIE + RFIN; a server session and a client in one process\n"
      "(Kim, Lee and Kobbelt 2005): the client starts from the base mesh, refines and\n"
      "coarsens as mode vhier on the hierarchy it has received and sends its view when\n"
      "it needs a split it lacks; the server answers with vsplit packets chosen by\n"
      "qrefine over its windowed active tags. Reports the bytes both ways per frame\n"
      "(--csv), packet bits, server memory against a stored vertex front, and the bytes\n"
      "of streaming the same progressive mesh in its fixed order instead. Over TCP on\n"
      "loopback: FILE --serve PORT [--clients K] serves K connections (port 0: any\n"
      "free port; the address is stdout's first line) and --connect 127.0.0.1:PORT\n"
      "(no FILE) runs a client on its camera path; --clients K without --serve runs K\n"
      "clients on turned scan / orbit paths against one server in one process.\n"
      "Mode vtrees: BASE + VHIE + RFIN + VTRE; vertex-tree transmission (To, Lau and\n"
      "Green 2001): the server moves its visible vertex list down and up the trees\n"
      "with mode vhier's view criteria and sends the base, left and right node records\n"
      "of newly visible nodes with the trace-up of fan vertices the client lacks; the\n"
      "client rebuilds the trees and selects triangles by vertex states. Reports the\n"
      "records per kind and their bytes against the paper's, and the client's\n"
      "reconstruct time. Over TCP on loopback as mode stream: FILE --serve PORT\n"
      "[--clients K] serves K connections, each with its own visible vertex list, and\n"
      "--connect 127.0.0.1:PORT (no FILE) runs a client on its camera path.\n"
      "Paths: 'scan' (180 frames: approach the model, then rise from its bottom to its\n"
      "top), 'orbit' (194 frames: approach, then circle it twice, speeding up), both\n"
      "relative to the bounding sphere, or a FILE: CSV with one row per frame (eye\n"
      "x,y,z, target x,y,z, up x,y,z, vertical fov in degrees; '#' comments) or JSON\n"
      "(an array of {\"eye\": [x,y,z], \"target\": [x,y,z], \"up\": [x,y,z], \"fov\": deg},\n"
      "bare or as {\"frames\": [...]}).");
  Request request;
  uint32_t width = 1024, height = 768;
  float near_fraction = 0.01f;
  tool.options().add_options()(
      "mode", po::value<std::string>(&request.mode)->value_name("M"),
      "the structure replayed: vhier (default), dag, fan, sets, stream or vtrees")(
      "path", po::value<std::string>(&request.path)->value_name("P"),
      "scan (default), orbit, or a CSV or JSON camera path FILE")(
      "tolerance", po::value<std::string>(&request.tolerance)->value_name("T"),
      "screen-space error tolerance: pixels of the viewport height (default 1), "
      "or a percentage of it such as 0.1% (the DAG paper's setting); 0 asks for every "
      "split the view allows")("width", po::value<uint32_t>(&width)->value_name("W"),
                               "viewport width (default 1024)")(
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
      "and coherent recovery equals fresh recovery (exit 7 naming the LoD); vtrees: that the "
      "client's visible vertex list and triangles are the server's every frame and no record "
      "is sent twice (exit 7 naming the frame)")(
      "plot", po::value<std::string>(&request.plot)->value_name("DIR"),
      "draw the paper-style charts as SVG in DIR (made when missing) with gnuplot "
      "(Debian's gnuplot-nox): dag: traversal time, accuracy, fronts against the mesh, "
      "operations per frame; vhier and fan: adapt time, front or active nodes against "
      "the mesh, operations per frame; sets: recovery time per LoD. DIR also gets the "
      "rows (frames.csv) and the script (replay.gp) to re-run")(
      "csv", po::value<std::string>(&request.csv)->value_name("FILE"),
      "write per-frame rows to FILE (vhier: frame, splits, collapses, "
      "passes, front, triangles, adapt_ms; dag: one row per frame and "
      "traversal: frame, traversal, splits, collapses, visited, "
      "budget_mode, fs, fc, triangles, traversal_ms, accuracy; fan: "
      "frame, fan_merges, fan_splits, collapses, splits, active, "
      "triangles, adapt_ms; sets: one row per LoD: spacing, "
      "percent, step, lod, strips, indices, triangles, fresh_us, "
      "coherent_us; stream: frame, uplink_bytes, downlink_bytes, requests, packets, "
      "splits, collapses, triangles, front, window_bytes, buffer_bytes, front_bytes; vtrees: "
      "frame, uplink_bytes, downlink_bytes, left_records, right_records, traces, "
      "trace_updates, downs, ups, visible, triangles, reconstruct_ms, select_ms)");
  tool.options().add_options()(
      "traversal", po::value<std::string>(&request.traversal)->value_name("T"),
      "dag: priority (default), linear, constant, or all (the three side by side)")(
      "budget-mode", po::value<std::string>(&request.budget_mode)->value_name("M"),
      "dag: auto (default: FREE-MODE while --changes splits cannot reach the budget, "
      "BUDGET-MODE once they could), budget, or free (no triangle budget)")(
      "budget", po::value<size_t>(&request.dag.triangle_budget)->value_name("T"),
      "dag: triangle budget (default 60000)")(
      "changes", po::value<size_t>(&request.dag.max_changes)->value_name("N"),
      "dag: at most N collapses and N splits per frame; constant-time: N nodes visited "
      "by each (default 300)")(
      "coarse", po::value<float>(&request.fan.coarse_fraction)->value_name("F"),
      "fan: one fan-merge / fan-split when the target is an end of the fine path at "
      "least max(1, ceil(F x children)) steps away, else merge-pointer steps (default "
      "0.5; 0: always, > 1: never)");
  std::string percents;
  tool.options().add_options()("percent", po::value<std::string>(&percents)->value_name("LIST"),
                               "sets: percentages of all LoDs each test recovers (default "
                               "1,3,6,10,15,20, the paper's)")(
      "spacing", po::value<std::string>(&request.spacing)->value_name("S"),
      "sets: linear, exponential or both (default)");
  std::string serve, connect;
  tool.options().add_options()(
      "serve", po::value<std::string>(&serve)->value_name("PORT"),
      "stream, vtrees: serve --clients connections over TCP on 127.0.0.1:PORT, then exit "
      "(0: a free port; stdout's first line is the address)")(
      "connect", po::value<std::string>(&connect)->value_name("ADDR"),
      "stream, vtrees: run a client on its path against the server at 127.0.0.1:PORT (no "
      "FILE: the server sends the base mesh or base records and the bounding sphere)")(
      "clients", po::value<size_t>(&request.clients)->value_name("K"),
      "stream, vtrees: with --serve, the connections served (default 1); stream: else K "
      "clients on one server in one process (1 .. 256)");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (tool.has("connect")) {
    if (!tool.positionals("input").empty()) {
      return tool.usage_error(
          "--connect takes no FILE: the client gets everything from the server");
    }
  } else if (std::optional<int> code =
                 tool.single_positional("input", "FILE.lbk", &request.input)) {
    return *code;
  }
  if ((tool.has("serve") || tool.has("connect") || tool.has("clients")) &&
      request.mode != "stream" && request.mode != "vtrees") {
    return tool.usage_error(std::string("--") +
                            (tool.has("serve")     ? "serve"
                             : tool.has("connect") ? "connect"
                                                   : "clients") +
                            " applies to --mode stream or vtrees only");
  }
  if (request.mode == "vtrees" && tool.has("clients") && !tool.has("serve") &&
      !tool.has("connect")) {
    return tool.usage_error(
        "--mode vtrees takes --clients with --serve only (K clients in one process: mode "
        "stream)");
  }
  if (tool.has("serve") && tool.has("connect"))
    return tool.usage_error("--serve and --connect exclude each other");
  if (request.clients < 1 || request.clients > 256)
    return tool.usage_error("--clients takes K in 1 .. 256");
  if (tool.has("connect")) {
    if (tool.has("clients")) return tool.usage_error("--clients does not apply to --connect");
    Result<LoopbackAddress> a = parse_loopback_address(connect);
    if (!a.is_ok()) return tool.usage_error("--connect: " + a.status().message());
    request.connect = a.value();
  }
  if (tool.has("serve")) {
    Result<LoopbackAddress> a = parse_loopback_address("127.0.0.1:" + serve);
    if (!a.is_ok()) return tool.usage_error("--serve takes a port 0 .. 65535, not '" + serve + "'");
    request.serve = a.value();
    for (const char* option :
         {"path", "tolerance", "width", "height", "fov", "near", "csv", "validate"}) {
      if (tool.has(option) && !(std::string(option) == "validate" && !request.validate)) {
        return tool.usage_error("--" + std::string(option) +
                                " does not apply to --serve (it is the client's)");
      }
    }
  }
  if (request.clients > 1 && !request.serve && !request.csv.empty())
    return tool.usage_error("--csv takes one client's rows, not --clients " +
                            std::to_string(request.clients));
  if (request.mode != "vhier" && request.mode != "dag" && request.mode != "fan" &&
      request.mode != "sets" && request.mode != "stream" && request.mode != "vtrees") {
    return tool.usage_error("--mode '" + request.mode +
                            "' is not available (modes: vhier, dag, fan, sets, stream, vtrees)");
  }
  if ((request.mode == "stream" || request.mode == "vtrees") && tool.has("plot"))
    return tool.usage_error("--plot does not apply to --mode " + request.mode);
  // Each option belongs to the camera modes or to mode sets; one given to
  // the other kind is refused rather than silently ignored.
  const bool sets = request.mode == "sets";
  for (const char* option : {"path", "tolerance", "width", "height", "fov", "near", "traversal",
                             "budget-mode", "budget", "changes", "coarse", "percent", "spacing"}) {
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
  if (!(request.fan.coarse_fraction >= 0 && std::isfinite(request.fan.coarse_fraction)))
    return tool.usage_error("--coarse takes a fraction >= 0");
  if (request.dag.max_changes == 0) return tool.usage_error("--changes takes N >= 1");
  if (width == 0 || height == 0 || width > 65536 || height > 65536)
    return tool.usage_error("--width and --height take 1 .. 65536 pixels");
  const std::optional<float> tolerance = tolerance_pixels(request.tolerance, height);
  if (!tolerance) {
    return tool.usage_error(
        "--tolerance takes pixels >= 0 or a percentage in [0, 100] such as "
        "0.1%, not '" +
        request.tolerance + "'");
  }
  request.options.tolerance_pixels = *tolerance;
  if (!(request.fov_degrees > 0 && request.fov_degrees < 180))
    return tool.usage_error("--fov takes degrees in (0, 180)");
  if (!(near_fraction > 0 && near_fraction < 1))
    return tool.usage_error("--near takes a fraction in (0, 1)");
  if (request.traversal == "all") {
    request.traversals = {DagTraversal::kPriority, DagTraversal::kLinear,
                          DagTraversal::kConstantTime};
  } else if (request.traversal == "priority") {
    request.traversals = {DagTraversal::kPriority};
  } else if (request.traversal == "linear") {
    request.traversals = {DagTraversal::kLinear};
  } else if (request.traversal == "constant") {
    request.traversals = {DagTraversal::kConstantTime};
  } else {
    return tool.usage_error("--traversal '" + request.traversal +
                            "' is not one of priority, linear, constant, all");
  }
  if (request.budget_mode == "auto") {
    request.dag.budget_mode = DagBudgetMode::kAuto;
  } else if (request.budget_mode == "budget") {
    request.dag.budget_mode = DagBudgetMode::kBudget;
  } else if (request.budget_mode == "free") {
    request.dag.budget_mode = DagBudgetMode::kFree;
  } else {
    return tool.usage_error("--budget-mode '" + request.budget_mode +
                            "' is not one of auto, budget, free");
  }
  if (request.mode != "dag") {
    for (const char* option : {"traversal", "budget-mode", "budget", "changes"}) {
      if (tool.has(option))
        return tool.usage_error(std::string("--") + option + " applies to --mode dag only");
    }
  }
  if (request.mode != "fan" && tool.has("coarse"))
    return tool.usage_error("--coarse applies to --mode fan only");
  request.options.viewport.width = width;
  request.options.viewport.height = height;
  request.options.viewport.near_fraction = near_fraction;
  request.dag.viewport = request.options.viewport;
  request.dag.tolerance_pixels = request.options.tolerance_pixels;
  request.fan.viewport = request.options.viewport;
  request.fan.tolerance_pixels = request.options.tolerance_pixels;
  if (tool.has("plot") && request.plot.empty()) return tool.usage_error("--plot takes a folder");
  if (!request.csv.empty() && same_file(request.input, request.csv))
    return tool.usage_error("the --csv output '" + request.csv + "' is the input itself");
  return tool.run([&] { return run(tool, request); });
}
