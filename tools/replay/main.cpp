// lodbake-replay: replays a camera path on a container's view-dependent
// structure and measures it (issue 8). Mode vhier: BASE + VHIE + RFIN, the
// SelectiveRefiner adapted per frame (lib/replay/vhier_replay.h). Thin:
// decoding lives in formats/, the runtime in lib/replay.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "formats/container/container_reader.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/support/file_io.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/vhier_replay.h"
#include "tools/common/cli.h"

namespace lodbake::cli {
namespace {

constexpr const char* kReplaySchema = "lodbake.replay/1";
constexpr int kValidationFailed = 7;

struct Request {
  std::string input;
  std::string mode = "vhier";
  std::string path = "scan";
  std::string csv;
  float fov_degrees = 60;
  bool validate = false;
  VhierReplayOptions options;
};

struct Loaded {
  VertexHierarchy h;
  std::vector<NodeRefinement> data;
};

Result<Loaded> load(const Bytes& bytes) {
  LODBAKE_ASSIGN_OR_RETURN(Container container, read_container(bytes.data(), bytes.size()));
  LODBAKE_ASSIGN_OR_RETURN(const Section* base, container.require(kBaseTag));
  const Section* vhie = container.find(kVhieTag);
  const Section* rfin = container.find(kRfinTag);
  if (vhie == nullptr || rfin == nullptr) {
    return invalid_input(std::string("container has no ") + (vhie == nullptr ? "VHIE" : "RFIN") +
                         " section; mode vhier needs BASE + VHIE + RFIN (lodbake-hierarchy "
                         "--sections vhie)");
  }
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh base_mesh, decode_base(base->data, base->size));
  Loaded loaded;
  LODBAKE_ASSIGN_OR_RETURN(loaded.h, decode_vhie(vhie->data, vhie->size, std::move(base_mesh)));
  LODBAKE_ASSIGN_OR_RETURN(loaded.data, decode_rfin(rfin->data, rfin->size, loaded.h));
  return loaded;
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
  Result<Loaded> loaded = load(bytes.value());
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  const VertexHierarchy& h = loaded.value().h;
  const BoundingSphere sphere = bounding_sphere(h.position);

  std::vector<CameraFrame> path;
  if (request.path == "scan" || request.path == "orbit") {
    path = builtin_path(request.path, sphere, request.fov_degrees).value();
  } else {
    Result<Bytes> path_bytes = read_file(request.path, uint64_t{1} << 30);
    if (!path_bytes.is_ok()) return tool.fail(request.path, path_bytes.status());
    Result<std::vector<CameraFrame>> parsed =
        parse_camera_path_csv(path_bytes.value().data(), path_bytes.value().size());
    if (!parsed.is_ok()) return tool.fail(request.path, parsed.status());
    path = std::move(parsed).value();
  }

  Result<SelectiveRefiner> refiner = SelectiveRefiner::create(h);
  if (!refiner.is_ok()) return tool.fail(request.input, refiner.status());
  std::vector<VhierFrameStats> frames;
  frames.reserve(path.size());
  Progress progress(tool, "replaying");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<VhierFrameStats> stats = adapt_vhier_frame(&refiner.value(), h, loaded.value().data,
                                                      sphere, path[i], request.options);
    if (!stats.is_ok()) {
      return tool.fail(request.input,
                       Status(stats.status().kind(),
                              "frame " + std::to_string(i) + ": " + stats.status().message()));
    }
    frames.push_back(stats.value());
    if (request.validate) {
      const std::vector<std::string> problems = check_vhier_mesh(refiner.value());
      if (!problems.empty()) {
        std::string message = "frame " + std::to_string(i) + ": invalid mesh: " + problems[0];
        for (size_t k = 1; k < problems.size(); ++k)
          message += "; " + problems[k];
        tool.fail(request.input, invalid_input(message));
        return kValidationFailed;
      }
    }
    progress.update(static_cast<double>(i + 1) / path.size());
  }

  if (!request.csv.empty()) {
    std::ostringstream csv;
    csv << "frame,splits,collapses,passes,front,triangles,adapt_ms\n";
    for (size_t i = 0; i < frames.size(); ++i) {
      const VhierFrameStats& f = frames[i];
      csv << i << ',' << f.splits << ',' << f.collapses << ',' << f.passes << ',' << f.front_size
          << ',' << f.triangles << ',' << f.adapt_ms << '\n';
    }
    Status written = write_file_atomic(request.csv, csv.str());
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  size_t splits = 0, collapses = 0, max_front = 0, max_triangles = 0, pass_limited = 0;
  double front_sum = 0, triangle_sum = 0, ms_sum = 0, ms_max = 0;
  std::vector<double> ms;
  for (const VhierFrameStats& f : frames) {
    splits += f.splits;
    collapses += f.collapses;
    max_front = std::max(max_front, f.front_size);
    max_triangles = std::max(max_triangles, f.triangles);
    front_sum += static_cast<double>(f.front_size);
    triangle_sum += static_cast<double>(f.triangles);
    ms_sum += f.adapt_ms;
    ms_max = std::max(ms_max, f.adapt_ms);
    ms.push_back(f.adapt_ms);
    if (f.passes >= request.options.max_passes) ++pass_limited;
  }
  const double n = static_cast<double>(frames.size());
  const nlohmann::json report = {
      {"schema", kReplaySchema},
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
      {"hierarchy",
       {{"nodes", h.node_count()},
        {"roots", h.root_count()},
        {"base_triangles", h.base.triangle_count()}}},
      {"splits", splits},
      {"collapses", collapses},
      {"front_size", {{"mean", front_sum / n}, {"max", max_front}}},
      {"triangles", {{"mean", triangle_sum / n}, {"max", max_triangles}}},
      {"adapt_ms", {{"mean", ms_sum / n}, {"median", median(ms)}, {"max", ms_max}}},
      {"frames_at_pass_limit", pass_limited}};
  if (tool.json()) {
    tool.print_json(report);
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode " << request.mode << ", path "
            << request.path << ", " << frames.size() << " frames"
            << (request.validate ? ", every frame validated" : "") << "\n";
  std::cout << "hierarchy     " << h.node_count() << " nodes, " << h.root_count() << " roots, "
            << h.base.triangle_count() << " base triangles\n";
  std::cout << "view          " << request.options.viewport.width << "x"
            << request.options.viewport.height << ", fov " << request.fov_degrees
            << " deg, tolerance " << request.options.tolerance_pixels << " px\n";
  std::cout << "operations    " << splits << " splits, " << collapses << " collapses\n";
  std::cout << "front size    mean " << front_sum / n << ", max " << max_front << "\n";
  std::cout << "triangles     mean " << triangle_sum / n << ", max " << max_triangles << "\n";
  std::cout << "adapt time    mean " << ms_sum / n << " ms, median " << median(ms) << " ms, max "
            << ms_max << " ms per frame\n";
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
  Tool tool("lodbake-replay", "FILE.lbk [--mode vhier] [--path scan|orbit|FILE] [options]",
            "Replays a camera path on a container's view-dependent hierarchy and reports,\n"
            "per frame, the refinement operations, front size, triangles and adapt time.\n"
            "Mode vhier (the only mode so far): BASE + VHIE + RFIN from lodbake-hierarchy;\n"
            "the vertex front is refined while a node's bounding sphere meets the view\n"
            "frustum, its normal cone is not entirely back-facing and its deviation projects\n"
            "to more than --tolerance pixels, and coarsened where none holds (Hoppe 1997).\n"
            "Paths: 'scan' (180 frames: approach the model, then rise from its bottom to its\n"
            "top), 'orbit' (194 frames: approach, then circle it twice, speeding up), both\n"
            "relative to the bounding sphere, or a CSV FILE with one row per frame:\n"
            "eye x,y,z, target x,y,z, up x,y,z, vertical fov in degrees ('#' comments).");
  Request request;
  uint32_t width = 1024, height = 768;
  float near_fraction = 0.01f;
  tool.options().add_options()("mode", po::value<std::string>(&request.mode)->value_name("M"),
                               "the structure replayed: vhier (default)")(
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
      "the frame otherwise)")("csv", po::value<std::string>(&request.csv)->value_name("FILE"),
                              "write per-frame rows (frame, splits, collapses, passes, front,\n"
                              "triangles, adapt_ms) to FILE");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("input", "FILE.lbk", &request.input))
    return *code;
  if (request.mode != "vhier") {
    return tool.usage_error("--mode '" + request.mode + "' is not available (modes: vhier)");
  }
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
  if (!request.csv.empty() && same_file(request.input, request.csv))
    return tool.usage_error("the --csv output '" + request.csv + "' is the input itself");
  return tool.run([&] { return run(tool, request); });
}
