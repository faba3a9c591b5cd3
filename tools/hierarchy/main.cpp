// lodbake-hierarchy: builds the balanced vertex hierarchy (lib/hierarchy) of
// a mesh, or of the fully refined mesh of a progressive-mesh container, and
// writes the sections asked for: VHIE + RFIN (the hierarchy), DAGE (the split
// DAG) and VTRE (the vertex trees). DAGE and VTRE are built from the
// hierarchy's own progressive mesh (hierarchy_to_progressive_mesh), written
// as VSPL next to them, so one BASE serves VHIE and VSPL alike. Thin: import,
// builds and encoding live in lib/ and formats/.
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/dage.h"
#include "formats/sections/meta.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vtre.h"
#include "formats/sections/wedg.h"
#include "formats/support/file_io.h"
#include "lib/bake/hierarchy_step.h"
#include "lib/core/sha256.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/ingest/load_mesh.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_lods.h"
#include "lib/simplify/pm_replay.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "tools/common/asset_report.h"
#include "tools/common/cli.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {
namespace {

constexpr const char* kHierarchySchema = "lodbake.hierarchy/1";

struct Request : HierarchyStepOptions {
  std::string input;
  std::string output;
};

// The input mesh and what META says about it.
struct Input {
  TriangleMesh mesh;
  MetaInput meta;
  std::string source = "mesh";  // or "progressive mesh"
  nlohmann::json repairs;       // of a mesh input
};

// An asset (is_asset(): glTF, an OBJ with materials, a container with
// SCNE, ...): the hierarchy of every mesh, each in its group, beside the
// scene.
int run_asset(const Tool& tool, const Request& request, const Bytes& bytes) {
  AssetRun run = asset_run(request, kHierarchySchema, "building the hierarchies");
  // The hierarchy's progressive mesh (VSPL, written with DAGE or VTRE)
  // carries the asset's wedges (WEDG): each mesh's corners, read once.
  std::map<uint32_t, MeshCornerWedges> corners;
  Status read_corners = Status::ok();
  if (request.dage || request.vtre) {
    run.partial_note = kHierarchyPmOnly;
    read_on_scene(
        &run, [&](const Scene& scene) { return asset_corner_wedges(request, scene); }, &corners,
        &read_corners);
  }
  MetaSection meta = make_meta("lodbake-hierarchy");
  meta.options = hierarchy_meta_options(request);
  return run_asset_build(
      tool, run, std::move(meta), bytes,
      [&](uint32_t scene_mesh, const TriangleMesh& mesh) -> Result<MeshSections> {
        LODBAKE_RETURN_IF_ERROR(read_corners);
        LODBAKE_ASSIGN_OR_RETURN(HierarchyBuilt b, build_hierarchy_sections(request, mesh));
        return hierarchy_mesh_sections(std::move(b), corners, scene_mesh, mesh);
      });
}

int run(const Tool& tool, const Request& request) {
  {
    Result<Bytes> bytes = read_file(request.input);
    if (bytes.is_ok() && is_asset(request.input, bytes.value()))
      return run_asset(tool, request, bytes.value());
  }
  Input in;
  // A container is read as the mesh it stands for (a progressive mesh's
  // greedy collapse order is not balanced: the hierarchy is rebuilt from its
  // fully refined mesh).
  const bool from_container = is_container_input(request.input);
  if (from_container) {
    // As lodbake-pack: a container's progressive mesh is not repaired.
    if (request.repair) return tool.usage_error("--repair applies to a mesh input");
    if (request.strict) return tool.usage_error("--strict applies to a mesh input");
  }
  LoadOptions load;
  load.repair = request.repair;
  load.strict = request.strict;
  load.drop_unreferenced = true;
  load.threads = request.options.threads;
  LoadedMesh loaded;
  if (int code = load_input(tool, request.input, load, &loaded); code != 0) return code;
  in.mesh = std::move(loaded.mesh);
  in.mesh.normals = MeshAttribute();
  in.mesh.texcoords = MeshAttribute();
  in.meta = meta_input(request.input, loaded);
  if (from_container) {
    in.source = loaded.container_source;
    if (in.source == "progressive mesh") {
      tool.info(request.input,
                "a progressive mesh's greedy collapse order is not balanced: rebuilding the "
                "hierarchy from its fully refined mesh (" +
                    std::to_string(in.mesh.vertex_count()) + " vertices)");
    }
  } else {
    in.repairs = repairs_json(load, loaded);
  }

  Progress progress(tool, "building the hierarchy");
  Result<HierarchyBuilt> made = build_hierarchy_sections(request, in.mesh);
  if (!made.is_ok()) return tool.fail(request.input, made.status());
  HierarchyBuilt& b = made.value();
  // Neither the input mesh nor the hierarchy's progressive mesh (kept for an
  // asset's wedges) is read again: freed before the container is assembled,
  // the largest block of the run's end.
  const size_t input_vertices = in.mesh.vertex_count();
  const size_t input_triangles = in.mesh.triangle_count();
  in.mesh = TriangleMesh();
  b.pm = ProgressiveMesh();
  const HierarchyShape& shape = b.shape;
  std::vector<HierarchySection>& sections = b.sections;
  const std::vector<std::pair<std::string, double>>& build_seconds = b.build_seconds;
  const nlohmann::json& dag_report = b.dag_report;
  const nlohmann::json& vtre_report = b.vtre_report;
  const TriangleMesh& base = b.base;

  MetaSection meta = make_meta("lodbake-hierarchy");
  meta.options = hierarchy_meta_options(request);
  meta.input = in.meta;
  meta.counts = b.counts;
  Result<Bytes> meta_bytes = encode_meta(meta);
  if (!meta_bytes.is_ok()) return tool.fail(request.output, meta_bytes.status());
  sections.insert(sections.begin(), {kMetaTag, std::move(meta_bytes).value(), nullptr, 0});

  nlohmann::json section_report = nlohmann::json::object();
  std::ostringstream per;
  per.precision(3);
  for (const HierarchySection& w : sections) {
    nlohmann::json entry = {{"bytes", w.bytes.size()}};
    if (w.per_what != nullptr) {
      // Per-item figures are null (JSON) / omitted (text) without items.
      const std::string key = std::string("bytes_per_") + w.per_what;
      const double each = w.per_count > 0 ? static_cast<double>(w.bytes.size()) / w.per_count : 0;
      entry[key] = w.per_count > 0 ? nlohmann::json(each) : nlohmann::json(nullptr);
      per << (per.tellp() > 0 ? ", " : "") << w.tag << " " << w.bytes.size();
      if (w.per_count > 0) per << " (" << each << " per " << w.per_what << ")";
    } else {
      per << (per.tellp() > 0 ? ", " : "") << w.tag << " " << w.bytes.size();
    }
    if (std::strcmp(w.tag, kDageTag) == 0) entry["dag"] = dag_report;
    if (std::strcmp(w.tag, kVtreTag) == 0) entry["trees"] = vtre_report;
    section_report[w.tag] = entry;
  }
  ContainerWriter writer;
  for (HierarchySection& w : sections) {
    Status added = writer.add_known_section(w.tag, std::move(w.bytes));
    if (!added.is_ok()) return tool.fail(request.output, added);
  }
  Result<Bytes> container = writer.finish_and_clear();
  if (!container.is_ok()) return tool.fail(request.output, container.status());
  Status written = write_file_atomic(request.output, container.value());
  if (!written.is_ok()) return tool.fail(request.output, written);

  double seconds = 0;
  nlohmann::json build_report = nlohmann::json::object();
  for (const auto& [name, s] : build_seconds) {
    seconds += s;
    build_report[name] = s;
  }
  nlohmann::json report = {
      {"schema", kHierarchySchema},
      {"input", request.input},
      {"source", in.source},
      {"input_counts", {{"vertices", input_vertices}, {"triangles", input_triangles}}},
      {"base_counts", {{"vertices", base.vertex_count()}, {"triangles", base.triangle_count()}}},
      {"nodes", shape.nodes},
      {"roots", shape.roots},
      {"splits", shape.splits},
      {"depth", shape.depth},
      {"levels_built", b.stats.levels_built},
      {"vertices_after_level", b.stats.vertices_after_level},
      {"tree_id_bits", shape.tree_bits},
      {"node_id_bits", shape.depth},
      {"id_bits", shape.id_bits},
      {"id_bytes", shape.id_bytes},
      {"seconds", seconds},
      {"build_seconds", build_report},
      {"output", request.output},
      {"bytes", container.value().size()},
      {"sections", section_report}};
  if (in.source == "mesh") report["repairs"] = in.repairs;
  if (tool.json()) {
    tool.print_json(report);
    return 0;
  }
  std::cout << "input       " << request.input << " (" << in.source << "): " << input_vertices
            << " vertices, " << input_triangles << " triangles\n";
  std::cout << "hierarchy   " << shape.nodes << " nodes, " << shape.roots << " roots, "
            << shape.splits << " splits, depth " << shape.depth << "\n";
  std::cout << "ids         <tree-id, node-id> = <" << shape.tree_bits << ", " << shape.depth
            << "> = " << shape.id_bits << " bits (" << shape.id_bytes << "-byte ids)\n";
  std::cout << "base        " << base.vertex_count() << " vertices, " << base.triangle_count()
            << " triangles\n";
  if (request.dage) {
    std::cout << "dag         " << dag_report["nodes"] << " nodes, " << dag_report["edges"]
              << " edges, " << dag_report["roots"] << " roots, " << dag_report["leaves"]
              << " leaves\n";
  }
  if (request.vtre) {
    std::ostringstream rec;
    rec.precision(3);
    rec << "vtrees      " << vtre_report["nodes"] << " nodes; record bytes";
    for (const char* kind : {"base", "left", "right"}) {
      const nlohmann::json& v = vtre_report[std::string(kind) + "_record_bytes"];
      if (!v.is_null()) rec << " " << kind << " " << v.get<double>();
    }
    std::cout << rec.str() << "\n";
  }
  std::ostringstream times;
  times.precision(3);
  for (const auto& [name, s] : build_seconds)
    times << (times.tellp() > 0 ? ", " : "") << name << " " << s << " s";
  std::cout << "build time  " << times.str() << "\n";
  std::cout << "wrote       " << request.output << ": " << container.value().size() << " bytes; "
            << per.str() << "\n";
  return 0;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
#if defined(__GLIBC__)
  // One malloc arena: with one per thread, what the import and the
  // hierarchy free on one thread is not reused by the next step's
  // allocations on another, and the peak grew with --threads (the dragon:
  // 397 MB with 1 thread, 487 MB with 2; 397 MB for both with one arena).
  // The parallel parts allocate little, so the shared lock costs little.
  mallopt(M_ARENA_MAX, 1);
#endif
  Tool tool("lodbake-hierarchy", "IN.{mesh,lbk} -o OUT.lbk [options]",
            "Builds the balanced vertex hierarchy of a mesh for truly selective refinement\n"
            "and view-dependent streaming (Kim, Lee and Kobbelt): half-edge collapses in\n"
            "levels of independent sets, ordered by subtree height then quadric error, with\n"
            "<tree-id, node-id> heap ids and fundamental cut vertices. From it, the split\n"
            "DAG (Zheng and Chan) and the vertex trees (To, Lau and Green) of the\n"
            "hierarchy's own progressive mesh. Writes META and BASE, then VHIE + RFIN\n"
            "(vhie), VSPL + DAGE (dage), VSPL + VTRE (vtre); one BASE serves them all.\n"
            "Given a container with a progressive mesh (BASE + VSPL), it rebuilds the\n"
            "hierarchy from that PM's fully refined mesh (the PM's greedy collapse order\n"
            "is not balanced), and DAGE and VTRE describe the rebuilt PM, not the input's.");
  Request request;
  tool.options().add_options()("output,o",
                               po::value<std::string>(&request.output)->value_name("OUT.lbk"),
                               "the container to write")(
      "sections", po::value<std::string>(&request.sections)->value_name("LIST"),
      "sections to build, any of vhie (VHIE + RFIN), dage (DAGE), vtre (VTRE) separated by "
      "commas (default vhie,dage,vtre); dage and vtre add the VSPL they index. META and BASE "
      "are always written")("boundary-weight",
                            po::value<double>(&request.options.boundary_weight)->value_name("W"),
                            "weight of the boundary-preserving quadrics (default 10)")(
      "max-normal-change",
      po::value<double>(&request.options.max_normal_change_degrees)->value_name("DEG"),
      "refuse collapses that turn a face normal by more than DEG degrees (default 150)")(
      "repair", po::bool_switch(&request.repair), "repair an input mesh first (see lodbake-pack)")(
      "threads", po::value<unsigned>(&request.options.threads)->value_name("N"),
      "threads for the parallel steps (oneTBB): 0 (default) every core, or any count up to "
      "4096; the output is the same bytes for every count")(
      "strict", po::bool_switch(&request.strict),
      "refuse a mesh that needs repairing (exit 3) instead of repairing it by default: "
      "non-manifold edges or vertices, degenerate or duplicate triangles, inconsistent "
      "orientation");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("input", "IN", &request.input)) return *code;
  if (request.output.empty()) return tool.usage_error("missing -o OUT.lbk");
  if (Status parsed = parse_hierarchy_sections(&request); !parsed.is_ok())
    return tool.usage_error(parsed.message());
  // As in lodbake-simplify, but for 0, which would refuse every collapse.
  if (!(request.options.max_normal_change_degrees > 0 &&
        request.options.max_normal_change_degrees <= 180))
    return tool.usage_error("--max-normal-change takes degrees in (0, 180]");
  if (!(request.options.boundary_weight >= 0 && std::isfinite(request.options.boundary_weight)))
    return tool.usage_error("--boundary-weight takes a finite value >= 0");
  // More is surely a typo (and tbb::task_arena takes an int).
  if (request.options.threads > 4096)
    return tool.usage_error("--threads takes a count from 0 (every core) to 4096");
  if (same_file(request.input, request.output))
    return tool.usage_error("the output '" + request.output + "' is the input itself");
  if (std::optional<int> code = tool.check_outputs({request.output})) return *code;
  return tool.run([&] { return run(tool, request); });
}
