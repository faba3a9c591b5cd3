// lodbake-replay's camera-path modes: vhier (BASE + VHIE + RFIN, the
// SelectiveRefiner adapted per frame, lib/replay/vhier_replay.h), dag (BASE +
// VSPL + DAGE, MANAGE-TRAVERSAL with one or all three traversals and their
// accuracy against the priority-oriented one, lib/replay/dag_replay.h) and
// fan (BASE + FANH, the fan hierarchy's dual-path adapt,
// lib/replay/fan_replay.h). Each mode loads its structure into a Session
// stepped one camera at a time; run_camera_path() drives any of them along
// the path and writes the one report they share (--csv, --plot, JSON or
// text), with --validate's cross-structure check of the hierarchy against
// the split DAG.
#include <algorithm>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/dage.h"
#include "formats/sections/fanh.h"
#include "formats/sections/open_container.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/dag_replay.h"
#include "lib/replay/fan_replay.h"
#include "lib/replay/replay_check.h"
#include "lib/replay/structure_cross_check.h"
#include "lib/replay/structure_loading.h"
#include "lib/replay/vhier_replay.h"
#include "tools/replay/frame_support.h"
#include "tools/replay/plots.h"
#include "tools/replay/replay_request.h"
#include "tools/replay/report_support.h"

namespace lodbake::cli::replay {
namespace {

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
std::shared_ptr<CrossCheckState> prepare_cross_check(const OpenedContainer& file, uint32_t group,
                                                     const Section& base, const VertexHierarchy* h,
                                                     const ProgressiveMesh* pm,
                                                     const VsplitDag* dag) {
  auto cross = std::make_shared<CrossCheckState>();
  auto fail = [&](const std::string& why) {
    cross->unavailable = why;
    return cross;
  };
  if (h == nullptr) {
    const Section* vhie = file.find(kVhieTag, group);
    if (vhie == nullptr) return fail("the container has no VHIE section");
    Result<TriangleMesh> base_mesh = decode_base(base.data, base.size);
    if (!base_mesh.is_ok()) return fail(base_mesh.status().message());
    Result<VertexHierarchy> decoded =
        decode_vhie(vhie->data, vhie->size, std::move(base_mesh).value());
    if (!decoded.is_ok()) return fail("VHIE: " + decoded.status().message());
    cross->h = std::move(decoded).value();
    h = &cross->h;
  } else {
    const Section* vspl = file.find(kVsplTag, group);
    const Section* dage = file.find(kDageTag, group);
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

using VhierState = VhierStructure;

// The DAG's lanes, and the priority-oriented reference their accuracy is
// measured against when no lane is priority-oriented.
struct DagState {
  DagStructure loaded;
  std::vector<DagReplay> lanes;
  std::optional<DagReplay> reference;
};

struct FanState {
  std::optional<FanReplay> replay;
  std::unique_ptr<PmWedges> wedges;  // an asset's fan: every front's wedges
  std::optional<FanWedges> fronts;
};

// An asset's structure whose fronts carry wedges: the report says so (and
// --validate checks every corner).
void note_wedges(Session* session, const PmWedges& wedges) {
  session->structure["wedges"] = wedges.wedge_count();
  session->structure_text +=
      ", " + std::to_string(wedges.wedge_count()) + " wedges (every corner's checked)";
}

Result<Session> load_vhier(const OpenedContainer& file, const Request& request) {
  LODBAKE_ASSIGN_OR_RETURN(uint32_t group, structure_group(file, ReplayStructure::kVhier));
  const Section& base = *file.find(kBaseTag, group);
  LODBAKE_ASSIGN_OR_RETURN(VhierStructure loaded, load_vhier_structure(file.decoded(), group));
  auto state = std::make_shared<VhierState>(std::move(loaded));
  const VertexHierarchy& h = *state->h;
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
        adapt_vhier_frame(&*state->refiner, *state->h, state->data, sphere, frame, options));
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
    session.cross = prepare_cross_check(file, group, base, state->h.get(), nullptr, nullptr);
  std::shared_ptr<CrossCheckState> cross = session.cross;
  if (state->front) note_wedges(&session, *state->wedges);
  session.check = [state, cross] {
    std::vector<std::string> problems = check_vhier_mesh(*state->refiner);
    if (state->front) {
      for (std::string& p : check_vhier_wedges(*state->refiner, *state->front, *state->wedges))
        problems.push_back(std::move(p));
    }
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

Result<Session> load_dag(const OpenedContainer& file, const Request& request) {
  LODBAKE_ASSIGN_OR_RETURN(uint32_t group, structure_group(file, ReplayStructure::kDag));
  const Section& base = *file.find(kBaseTag, group);
  auto state = std::make_shared<DagState>();
  LODBAKE_ASSIGN_OR_RETURN(state->loaded, load_dag_structure(file.decoded(), group));
  const ProgressiveMesh& pm = *state->loaded.pm;
  const VsplitDag& dag = *state->loaded.dag;
  const std::vector<DagTraversal>& traversals = request.traversals;
  for (size_t i = 0; i < traversals.size(); ++i) {
    LODBAKE_ASSIGN_OR_RETURN(DagReplay replay, DagReplay::create(pm, dag));
    state->lanes.push_back(std::move(replay));
  }
  const bool has_priority =
      std::find(traversals.begin(), traversals.end(), DagTraversal::kPriority) != traversals.end();
  if (!has_priority) {
    LODBAKE_ASSIGN_OR_RETURN(DagReplay replay, DagReplay::create(pm, dag));
    state->reference.emplace(std::move(replay));
  }
  std::vector<Vec3f> points = pm.base.positions;
  for (const VertexSplit& split : pm.splits)
    points.push_back(split.vt_position);
  Session session;
  session.sphere = bounding_sphere(points);
  session.structure = {{"nodes", dag.node_count()},
                       {"edges", dag.edge_count()},
                       {"base_triangles", pm.base.triangle_count()}};
  session.structure_text = std::to_string(dag.node_count()) + " nodes, " +
                           std::to_string(dag.edge_count()) + " edges, " +
                           std::to_string(pm.base.triangle_count()) + " base triangles";
  if (state->loaded.lookup) note_wedges(&session, *state->loaded.wedges);
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
  if (request.validate) session.cross = prepare_cross_check(file, group, base, nullptr, &pm, &dag);
  std::shared_ptr<CrossCheckState> cross = session.cross;
  session.check = [state, traversals, cross] {
    std::vector<std::string> problems;
    for (size_t i = 0; i < traversals.size(); ++i) {
      const std::string lane = std::string(dag_traversal_name(traversals[i])) + " traversal: ";
      for (const std::string& p : state->lanes[i].check())
        problems.push_back(lane + p);
      if (state->loaded.lookup) {
        for (const std::string& p :
             check_dag_wedges(state->lanes[i], *state->loaded.lookup, *state->loaded.wedges))
          problems.push_back(lane + p);
      }
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

Result<Session> load_fan(const OpenedContainer& file, const Request& request) {
  LODBAKE_ASSIGN_OR_RETURN(uint32_t group, structure_group(file, ReplayStructure::kFan));
  auto state = std::make_shared<FanState>();
  LODBAKE_ASSIGN_OR_RETURN(FanStructure loaded, load_fan_structure(file.decoded(), group));
  state->replay.emplace(std::move(*loaded.replay));
  const TriangleMesh& input = loaded.input;
  const FanHierarchy& h = loaded.h;
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
  if (loaded.fronts) {
    state->wedges = std::move(loaded.wedges);
    state->fronts.emplace(std::move(*loaded.fronts));
    note_wedges(&session, *state->wedges);
  }
  session.check = [state] {
    std::vector<std::string> problems = state->replay->check();
    if (state->fronts) {
      for (std::string& p :
           check_fan_wedges(state->replay->runtime(), *state->fronts, *state->wedges))
        problems.push_back(std::move(p));
    }
    return problems;
  };
  return session;
}

Result<Session> load(const Bytes& bytes, const Request& request) {
  LODBAKE_ASSIGN_OR_RETURN(OpenedContainer file, open_container(bytes));
  try {
    if (request.mode == "dag") return load_dag(file, request);
    if (request.mode == "fan") return load_fan(file, request);
    return load_vhier(file, request);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory loading the container");
  }
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

}  // namespace

int run_camera_path(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<Session> loaded = load(bytes, request);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  const Session& session = loaded.value();
  const bool dag = request.mode == "dag";
  const bool fan = request.mode == "fan";

  std::string path_file;
  Result<std::vector<CameraFrame>> read = read_path(request, session.sphere, &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();

  std::vector<std::vector<Row>> frames;
  frames.reserve(path.size());
  Progress progress(tool, "replaying");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<std::vector<Row>> rows = session.step(path[i]);
    if (!rows.is_ok()) return tool.fail(request.input, frame_failure(i, rows.status()));
    frames.push_back(std::move(rows).value());
    if (request.validate) {
      const Status checked = invalid_mesh(i, session.check());
      if (!checked.is_ok()) return tool.fail(request.input, checked);
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
  nlohmann::json report = camera_report(request, frames.size());
  report[dag ? "dag" : fan ? "fan_hierarchy" : "hierarchy"] = session.structure;
  auto timing = [](const LaneSummary& l) {
    return nlohmann::json{{"mean", l.ms_mean}, {"median", l.ms_median}, {"max", l.ms_max}};
  };
  if (dag) {
    report["budget_mode"] = request.budget_mode;
    report["max_changes"] = request.dag.max_changes;
    report["warm_start"] = request.dag.warm_start;
    report["back_face"] = request.dag.back_face;
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
  print_replay_line(request, frames.size());
  std::cout << (dag   ? "dag           "
                : fan ? "fan hierarchy "
                      : "hierarchy     ")
            << session.structure_text << "\n";
  print_view(request);
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
              << (constant ? " nodes visited per traversal" : " changes per traversal")
              << (request.dag.warm_start ? " from the second frame (warm start)\n" : "\n");
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

}  // namespace lodbake::cli::replay
