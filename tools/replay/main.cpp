// lodbake-replay: replays a camera path on a container's view-dependent
// structure and measures it (issue 8), or runs the strip paper's
// LoD-recovery tests. This file is the tool's thin part: the options, their
// validation into one Request (tools/replay/replay_request.h) and the
// dispatch to the mode. The modes live one a file: vhier, dag and fan in
// camera_modes.cpp, sets in sets_mode.cpp, stream in stream_mode.cpp, vtrees
// in vtrees_mode.cpp; what their reports share in report_support.cpp, their
// per-frame pieces in frame_support.cpp, the streaming modes' --serve and
// labels in streaming_support.cpp, --plot in plots.cpp. Decoding lives in
// formats/, the runtime in lib/replay.
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "lib/replay/dag_replay.h"
#include "lib/replay/stream_transport.h"
#include "tools/common/cli.h"
#include "tools/replay/plots.h"
#include "tools/replay/replay_request.h"

namespace lodbake::cli::replay {
namespace {

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
}  // namespace lodbake::cli::replay

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  using namespace lodbake::cli::replay;
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
      "and coherent recovery equals fresh recovery, and over an asset that every corner has "
      "its wedge (exit 7 naming the LoD); vtrees: that the "
      "client's visible vertex list and triangles are the server's every frame, over an asset "
      "that every corner has the hierarchy front's wedge, and no record "
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
      "warm-start", po::bool_switch(&request.dag.warm_start),
      "dag: the first frame runs without the --changes limit (the mesh a client loads "
      "before the route starts); the limit holds from the second frame")(
      "no-back-face", po::bool_switch(&request.dag_no_back_face),
      "dag: no back-facing simplification (by default a node whose cone of normals "
      "faces away from the eye is not split, as in the paper's experiments)")(
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
  // A path file's rows carry their own field of view.
  if (tool.has("fov") && request.path != "scan" && request.path != "orbit")
    return tool.usage_error("--fov applies to the built-in paths; the rows of --path '" +
                            request.path + "' give their own fov");
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
  request.dag.back_face = !request.dag_no_back_face;
  if (request.mode != "dag") {
    if (request.dag.warm_start) return tool.usage_error("--warm-start applies to --mode dag only");
    if (request.dag_no_back_face)
      return tool.usage_error("--no-back-face applies to --mode dag only");
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
  if (std::optional<int> code = tool.check_outputs({request.csv})) return *code;
  if (!request.plot.empty()) {
    if (Status folder = check_plot_folder(request.plot); !folder.is_ok())
      return tool.fail(request.plot, folder);
  }
  return tool.run([&] { return run(tool, request); });
}
