// lodbake-strips: triangle strips over a mesh (lib/strips/stripify.h) and
// the SETS multiresolution strip graph over its progressive mesh
// (lib/strips/sets_build.h), written as a container. Thin: the algorithms
// live in lib/strips and lib/simplify, the codecs in formats/sections.
#include <chrono>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
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
#include "lib/bake/strips_step.h"
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

using Input = StripsInput;

constexpr const char* kStripsSchema = "lodbake.strips/1";

struct Request : StripsStepOptions {
  std::string input;
  std::string output;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

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
  in->pm = std::make_shared<const ProgressiveMesh>(std::move(pm).value());
  return 0;
}

int load_mesh_input(const Tool& tool, const Request& request, Input* in) {
  LoadOptions load;
  load.repair = request.repair;
  load.strict = request.strict;
  load.per_vertex_attributes = !request.strips_only;  // the simplification records a PM
  load.drop_unreferenced = true;
  load.threads = request.threads;
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
  Result<ProgressiveMesh> pm = record_pm(
      loaded.mesh, [&](double fraction) { progress.update(fraction); }, request.threads);
  if (!pm.is_ok()) return tool.fail(request.input, pm.status());
  in->report["simplify_seconds"] = seconds_since(start);
  in->pm = std::make_shared<const ProgressiveMesh>(std::move(pm).value());
  return 0;
}

// An asset (glTF, or a container with SCNE): every mesh's strips (and
// graph over its own progressive mesh), each in its group beside the scene.
// The progressive mesh carries the asset's wedges (WEDG): each mesh's
// corners, read once.
int run_asset(const Tool& tool, const Request& request, const Bytes& bytes) {
  AssetRun run = asset_run(request, kStripsSchema, "building the strips");
  AssetCorners corners;
  Status read_corners = Status::ok();
  if (!request.strips_only) {
    run.partial_note = kStripsPmOnly;
    read_on_scene(
        &run,
        [&](const Scene& scene) {
          return read_asset_corners(scene, request.repair, request.strict);
        },
        &corners, &read_corners);
  }
  return run_asset_build(
      tool, run, strips_meta(request), bytes,
      [&](uint32_t scene_mesh, const TriangleMesh& mesh) -> Result<MeshSections> {
        LODBAKE_RETURN_IF_ERROR(read_corners);
        return strips_mesh_sections(request, corners, scene_mesh, mesh);
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
  Result<Bytes> container = strips_container(request, in, std::move(built).value());
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
            "container, gets every mesh built in its own group, with WEDG (the asset's\n"
            "wedges through the progressive mesh, which every SETS level's corners take)\n"
            "after each VSPL.");
  Request request;
  tool.options().add_options()(
      "output,o", po::value<std::string>(&request.output)->value_name("OUT.lbk"),
      "the container to write")("strips-only", po::bool_switch(&request.strips_only),
                                "write only the strips of the full mesh (STRP), no graph")(
      "repair", po::bool_switch(&request.repair), "repair a mesh input first (see lodbake-pack)")(
      "strict", po::bool_switch(&request.strict),
      "refuse a mesh that needs repairing (exit 3) instead of repairing it by default: "
      "non-manifold edges or vertices, degenerate or duplicate triangles, inconsistent "
      "orientation")(
      "threads", po::value<unsigned>(&request.threads)->value_name("N"),
      "threads for the simplification and the SETS graph (oneTBB): 0 (default) every core, or "
      "any count up to 4096; the output is the same for any N");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("input", "IN", &request.input)) return *code;
  if (request.output.empty()) return tool.usage_error("nothing to write: give -o OUT.lbk");
  if (request.threads > 4096)
    return tool.usage_error("--threads takes a count from 0 (every core) to 4096");
  if (same_file(request.input, request.output))
    return tool.usage_error("the output '" + request.output + "' is the input itself");
  if (std::optional<int> code = tool.check_outputs({request.output})) return *code;
  return tool.run([&] { return run(tool, request); });
}
