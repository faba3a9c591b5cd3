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

struct Request {
  std::string input;
  std::string output;
  std::string sections = "vhie,dage,vtre";
  bool vhie = false;  // the parsed --sections
  bool dage = false;
  bool vtre = false;
  bool repair = false;
  bool strict = false;
  BalancedBuildOptions options;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One section to write: its tag, payload and what its bytes-per-item figure
// divides by (the required flag is the registry's, as for every writer).
struct Written {
  const char* tag;
  Bytes bytes;
  const char* per_what;  // "node", "split" or nullptr
  uint64_t per_count;
};

// The input mesh and what META says about it.
struct Input {
  TriangleMesh mesh;
  MetaInput meta;
  std::string source = "mesh";  // or "progressive mesh"
  nlohmann::json repairs;       // of a mesh input
};

// What one build made, besides its sections: for the reports.
struct Built {
  std::vector<Written> sections;  // BASE first (META is the caller's)
  HierarchyShape shape;
  BalancedBuildStats stats;
  TriangleMesh base;
  std::vector<std::pair<std::string, double>> build_seconds;  // in build order
  nlohmann::json dag_report, vtre_report;
  std::map<std::string, uint64_t> counts;  // META's
  ProgressiveMesh pm;                      // the hierarchy's own, when DAGE or VTRE are built
};

// The hierarchy and the sections --sections asks for, from one mesh.
Result<Built> build_structures(const Request& request, const TriangleMesh& mesh) {
  using Clock = std::chrono::steady_clock;
  Built out;
  Clock::time_point start = Clock::now();
  LODBAKE_ASSIGN_OR_RETURN(BalancedHierarchy built,
                           build_balanced_hierarchy(mesh, request.options));
  out.build_seconds.emplace_back("hierarchy", seconds_since(start));
  const VertexHierarchy& h = built.hierarchy;
  out.shape = hierarchy_shape(h);
  out.stats = built.stats;
  const HierarchyShape& shape = out.shape;
  std::vector<Written>& sections = out.sections;
  if (request.vhie) {
    start = Clock::now();
    LODBAKE_ASSIGN_OR_RETURN(std::vector<NodeRefinement> refinement,
                             compute_refinement_data(h, mesh));
    out.build_seconds.emplace_back("refinement", seconds_since(start));
    LODBAKE_ASSIGN_OR_RETURN(Bytes vhie, encode_vhie(h));
    LODBAKE_ASSIGN_OR_RETURN(Bytes rfin, encode_rfin(h, refinement));
    sections.push_back({kVhieTag, std::move(vhie), "node", shape.nodes});
    sections.push_back({kRfinTag, std::move(rfin), "split", shape.splits});
  }
  // DAGE and VTRE describe a progressive mesh: the hierarchy's own, so they
  // share BASE with VHIE (a greedy PM given as input has another base mesh).
  ProgressiveMesh& pm = out.pm;
  if (request.dage || request.vtre) {
    start = Clock::now();
    LODBAKE_ASSIGN_OR_RETURN(pm, hierarchy_to_progressive_mesh(h));
    out.build_seconds.emplace_back("progressive_mesh", seconds_since(start));
    LODBAKE_ASSIGN_OR_RETURN(Bytes vspl, encode_vspl(pm, VsplEncodeOptions()));
    sections.push_back({kVsplTag, std::move(vspl), "split", pm.splits.size()});
  }
  if (request.dage) {
    start = Clock::now();
    LODBAKE_ASSIGN_OR_RETURN(VsplitDag dag, build_vsplit_dag(pm));
    out.build_seconds.emplace_back("dag", seconds_since(start));
    LODBAKE_ASSIGN_OR_RETURN(Bytes dage, encode_dage(dag));
    LODBAKE_ASSIGN_OR_RETURN(DageSummary summary, read_dage_summary(dage.data(), dage.size()));
    out.dag_report = {{"nodes", summary.node_count},
                      {"edges", summary.edge_count},
                      {"roots", summary.root_count},
                      {"leaves", summary.leaf_count}};
    sections.push_back({kDageTag, std::move(dage), "node", dag.node_count()});
  }
  if (request.vtre) {
    start = Clock::now();
    LODBAKE_ASSIGN_OR_RETURN(VertexTrees trees, build_vertex_trees(pm));
    out.build_seconds.emplace_back("vertex_trees", seconds_since(start));
    LODBAKE_ASSIGN_OR_RETURN(Bytes vtre, encode_vtre(trees));
    const VtreRecordSizes rec = vtre_record_sizes(trees);
    auto bytes_per = [](uint64_t bits, uint64_t count) {
      return count == 0 ? nlohmann::json(nullptr)
                        : nlohmann::json(static_cast<double>(bits) / 8.0 / count);
    };
    out.vtre_report = {{"nodes", trees.node_count()},
                       {"base_record_bytes", bytes_per(rec.base_bits, rec.base_records)},
                       {"left_record_bytes", bytes_per(rec.left_bits, rec.left_records)},
                       {"right_record_bytes", bytes_per(rec.right_bits, rec.right_records)}};
    sections.push_back({kVtreTag, std::move(vtre), "node", trees.node_count()});
  }
  out.counts = {
      {"vertices", h.base.vertex_count()},     {"triangles", h.base.triangle_count()},
      {"hierarchy_nodes", shape.nodes},        {"hierarchy_depth", shape.depth},
      {"input_vertices", mesh.vertex_count()}, {"input_triangles", mesh.triangle_count()}};
  if (request.dage || request.vtre) {
    out.counts["splits"] = pm.splits.size();
    out.counts["full_vertices"] = pm.full_vertex_count();
    out.counts["full_triangles"] = full_triangle_count(pm.base.triangle_count(), pm.splits);
  }
  LODBAKE_ASSIGN_OR_RETURN(Bytes base_bytes, encode_base(h.base, BaseEncodeOptions()));
  sections.insert(sections.begin(), {kBaseTag, std::move(base_bytes), nullptr, 0});
  out.base = std::move(built.hierarchy.base);
  return out;
}

nlohmann::json meta_options(const Request& request) {
  return {{"sections", request.sections},
          {"boundary_weight", request.options.boundary_weight},
          {"max_normal_change_degrees", request.options.max_normal_change_degrees},
          {"repair", request.repair}};
}

// The WEDG section of a mesh's hierarchy PM: the corners read from the
// scene must be over the very mesh the hierarchy was built on.
Result<Bytes> hierarchy_wedges(const std::map<uint32_t, MeshCornerWedges>& corners,
                               uint32_t scene_mesh, const TriangleMesh& mesh,
                               const ProgressiveMesh& pm) {
  auto found = corners.find(scene_mesh);
  if (found == corners.end() || found->second.topology.positions != mesh.positions ||
      found->second.topology.triangles != mesh.triangles)
    return runtime_error("the corners read from the scene are not over the mesh built");
  LODBAKE_ASSIGN_OR_RETURN(PmWedges wedges, wedges_of_pm(pm, found->second));
  return encode_wedg(wedges);
}

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
    run.on_scene = [&](const Scene& scene) {
      LoadOptions load;
      load.repair = request.repair;
      load.strict = request.strict;
      Result<std::vector<MeshCornerWedges>> all = scene_corner_wedges(scene, load);
      if (!all.is_ok()) {
        read_corners = all.status();
        return;
      }
      for (MeshCornerWedges& c : all.value())
        corners.emplace(c.mesh, std::move(c));
    };
  }
  MetaSection meta = make_meta("lodbake-hierarchy");
  meta.options = meta_options(request);
  return run_asset_build(
      tool, run, std::move(meta), bytes,
      [&](uint32_t scene_mesh, const TriangleMesh& mesh) -> Result<MeshSections> {
        LODBAKE_RETURN_IF_ERROR(read_corners);
        LODBAKE_ASSIGN_OR_RETURN(Built b, build_structures(request, mesh));
        MeshSections out;
        for (Written& w : b.sections) {
          const bool vspl = std::string(w.tag) == kVsplTag;
          out.sections.emplace_back(w.tag, std::move(w.bytes));
          if (!vspl) continue;
          LODBAKE_ASSIGN_OR_RETURN(Bytes wedg, hierarchy_wedges(corners, scene_mesh, mesh, b.pm));
          out.sections.emplace_back(kWedgTag, std::move(wedg));
        }
        out.counts = b.counts;
        out.report = {{"nodes", b.shape.nodes},
                      {"splits", b.shape.splits},
                      {"depth", b.shape.depth},
                      {"base_triangles", b.base.triangle_count()}};
        return out;
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
  Result<Built> made = build_structures(request, in.mesh);
  if (!made.is_ok()) return tool.fail(request.input, made.status());
  Built& b = made.value();
  const HierarchyShape& shape = b.shape;
  std::vector<Written>& sections = b.sections;
  const std::vector<std::pair<std::string, double>>& build_seconds = b.build_seconds;
  const nlohmann::json& dag_report = b.dag_report;
  const nlohmann::json& vtre_report = b.vtre_report;
  const TriangleMesh& base = b.base;

  MetaSection meta = make_meta("lodbake-hierarchy");
  meta.options = meta_options(request);
  meta.input = in.meta;
  meta.counts = b.counts;
  Result<Bytes> meta_bytes = encode_meta(meta);
  if (!meta_bytes.is_ok()) return tool.fail(request.output, meta_bytes.status());
  sections.insert(sections.begin(), {kMetaTag, std::move(meta_bytes).value(), nullptr, 0});

  nlohmann::json section_report = nlohmann::json::object();
  std::ostringstream per;
  per.precision(3);
  for (const Written& w : sections) {
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
  for (Written& w : sections) {
    Status added = writer.add_known_section(w.tag, std::move(w.bytes));
    if (!added.is_ok()) return tool.fail(request.output, added);
  }
  Result<Bytes> container = writer.finish();
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
      {"input_counts",
       {{"vertices", in.mesh.vertex_count()}, {"triangles", in.mesh.triangle_count()}}},
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
  std::cout << "input       " << request.input << " (" << in.source
            << "): " << in.mesh.vertex_count() << " vertices, " << in.mesh.triangle_count()
            << " triangles\n";
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
      "strict", po::bool_switch(&request.strict),
      "refuse a mesh that needs repairing (exit 3) instead of repairing it by default: "
      "non-manifold edges or vertices, degenerate or duplicate triangles, inconsistent "
      "orientation");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("input", "IN", &request.input)) return *code;
  if (request.output.empty()) return tool.usage_error("missing -o OUT.lbk");
  std::stringstream list(request.sections);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item == "vhie") {
      request.vhie = true;
    } else if (item == "dage") {
      request.dage = true;
    } else if (item == "vtre") {
      request.vtre = true;
    } else if (item != "meta" && item != "base") {
      return tool.usage_error("--sections: '" + item +
                              "' is not a section lodbake-hierarchy builds (vhie, dage, vtre)");
    }
  }
  if (!request.vhie && !request.dage && !request.vtre)
    return tool.usage_error("--sections must include vhie, dage or vtre");
  // As in lodbake-simplify, but for 0, which would refuse every collapse.
  if (!(request.options.max_normal_change_degrees > 0 &&
        request.options.max_normal_change_degrees <= 180))
    return tool.usage_error("--max-normal-change takes degrees in (0, 180]");
  if (!(request.options.boundary_weight >= 0 && std::isfinite(request.options.boundary_weight)))
    return tool.usage_error("--boundary-weight takes a finite value >= 0");
  if (same_file(request.input, request.output))
    return tool.usage_error("the output '" + request.output + "' is the input itself");
  if (std::optional<int> code = tool.check_outputs({request.output})) return *code;
  return tool.run([&] { return run(tool, request); });
}
