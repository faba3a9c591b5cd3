// lodbake-hierarchy: builds the balanced vertex hierarchy (lib/hierarchy) of
// a mesh, or of the fully refined mesh of a progressive-mesh container, and
// writes it as META + BASE + VHIE + RFIN. Thin: import, build, refinement
// data and encoding live in lib/ and formats/.
#include <chrono>
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "formats/container/container_layout.h"
#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/support/file_io.h"
#include "lib/core/sha256.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/ingest/load_mesh.h"
#include "lib/simplify/pm_replay.h"
#include "tools/common/cli.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {
namespace {

constexpr const char* kHierarchySchema = "lodbake.hierarchy/1";

struct Request {
  std::string input;
  std::string output;
  std::string sections = "vhie";
  bool repair = false;
  BalancedBuildOptions options;
};

// The input mesh and what META says about it.
struct Input {
  TriangleMesh mesh;
  MetaInput meta;
  std::string source = "mesh";  // or "progressive mesh"
};

bool looks_like_container(const Bytes& bytes) {
  return bytes.size() >= sizeof(kContainerMagic) &&
         std::memcmp(bytes.data(), kContainerMagic, sizeof(kContainerMagic)) == 0;
}

// A container with BASE + VSPL: the hierarchy is rebuilt from the PM's fully
// refined mesh, since the PM's greedy collapse order is not balanced.
int load_pm_input(const Tool& tool, const std::string& path, const Bytes& bytes, Input* in) {
  Result<Container> container = read_container(bytes.data(), bytes.size());
  if (!container.is_ok()) return tool.fail(path, container.status());
  Result<const Section*> base = container.value().require(kBaseTag);
  if (!base.is_ok()) return tool.fail(path, base.status());
  const Section* vspl = container.value().find(kVsplTag);
  if (vspl == nullptr) {
    return tool.fail(path,
                     invalid_input("container has no progressive mesh (VSPL section); give "
                                   "the mesh file or a container from lodbake-simplify --pm"));
  }
  Result<ProgressiveMesh> pm =
      decode_progressive_mesh(base.value()->data, base.value()->size, vspl->data, vspl->size);
  if (!pm.is_ok()) return tool.fail(path, pm.status());
  Result<TriangleMesh> full = mesh_at_lod(pm.value(), pm.value().full_vertex_count());
  if (!full.is_ok()) return tool.fail(path, full.status());
  Result<TriangleMesh> mapped = map_to_input(pm.value(), full.value());
  if (!mapped.is_ok()) return tool.fail(path, mapped.status());
  in->mesh = std::move(mapped).value();
  in->mesh.normals = MeshAttribute();
  in->mesh.texcoords = MeshAttribute();
  in->source = "progressive mesh";
  LoadedMesh loaded;
  loaded.file_bytes = bytes.size();
  loaded.sha256 = sha256_hex(bytes.data(), bytes.size());
  in->meta = meta_input(path, loaded);
  tool.info(path,
            "a progressive mesh's greedy collapse order is not balanced: rebuilding the hierarchy "
            "from its fully refined mesh (" +
                std::to_string(in->mesh.vertex_count()) + " vertices)");
  return 0;
}

int run(const Tool& tool, const Request& request) {
  Input in;
  Result<Bytes> bytes = read_file(request.input);
  if (!bytes.is_ok()) return tool.fail(request.input, bytes.status());
  if (looks_like_container(bytes.value())) {
    if (int code = load_pm_input(tool, request.input, bytes.value(), &in); code != 0) return code;
  } else {
    LoadOptions load;
    load.repair = request.repair;
    load.drop_unreferenced = true;
    LoadedMesh loaded;
    if (int code = load_input(tool, request.input, load, &loaded); code != 0) return code;
    in.mesh = std::move(loaded.mesh);
    in.mesh.normals = MeshAttribute();
    in.mesh.texcoords = MeshAttribute();
    in.meta = meta_input(request.input, loaded);
  }

  Progress progress(tool, "building the hierarchy");
  const auto start = std::chrono::steady_clock::now();
  Result<BalancedHierarchy> built = build_balanced_hierarchy(in.mesh, request.options);
  if (!built.is_ok()) return tool.fail(request.input, built.status());
  const VertexHierarchy& h = built.value().hierarchy;
  Result<std::vector<NodeRefinement>> refinement = compute_refinement_data(h, in.mesh);
  if (!refinement.is_ok()) return tool.fail(request.input, refinement.status());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const HierarchyShape shape = hierarchy_shape(h);

  MetaSection meta = make_meta("lodbake-hierarchy");
  meta.options = {{"sections", request.sections},
                  {"boundary_weight", request.options.boundary_weight},
                  {"max_normal_change_degrees", request.options.max_normal_change_degrees},
                  {"repair", request.repair}};
  meta.input = in.meta;
  meta.counts = {
      {"vertices", h.base.vertex_count()},        {"triangles", h.base.triangle_count()},
      {"hierarchy_nodes", shape.nodes},           {"hierarchy_depth", shape.depth},
      {"input_vertices", in.mesh.vertex_count()}, {"input_triangles", in.mesh.triangle_count()}};
  Result<Bytes> meta_bytes = encode_meta(meta);
  if (!meta_bytes.is_ok()) return tool.fail(request.output, meta_bytes.status());
  Result<Bytes> base_bytes = encode_base(h.base, BaseEncodeOptions());
  if (!base_bytes.is_ok()) return tool.fail(request.output, base_bytes.status());
  Result<Bytes> vhie_bytes = encode_vhie(h);
  if (!vhie_bytes.is_ok()) return tool.fail(request.output, vhie_bytes.status());
  Result<Bytes> rfin_bytes = encode_rfin(h, refinement.value());
  if (!rfin_bytes.is_ok()) return tool.fail(request.output, rfin_bytes.status());
  const size_t sizes[4] = {meta_bytes.value().size(), base_bytes.value().size(),
                           vhie_bytes.value().size(), rfin_bytes.value().size()};
  ContainerWriter writer;
  Status added = writer.add_section(kMetaTag, std::move(meta_bytes).value(), false);
  if (added.is_ok()) added = writer.add_section(kBaseTag, std::move(base_bytes).value(), true);
  if (added.is_ok()) added = writer.add_section(kVhieTag, std::move(vhie_bytes).value(), true);
  if (added.is_ok()) added = writer.add_section(kRfinTag, std::move(rfin_bytes).value(), false);
  if (!added.is_ok()) return tool.fail(request.output, added);
  Result<Bytes> container = writer.finish();
  if (!container.is_ok()) return tool.fail(request.output, container.status());
  Status written = write_file_atomic(request.output, container.value());
  if (!written.is_ok()) return tool.fail(request.output, written);

  const double nodes = shape.nodes > 0 ? static_cast<double>(shape.nodes) : 1.0;
  // Per-split figures are null (JSON) / omitted (text) without splits.
  const double splits = static_cast<double>(shape.splits);
  const nlohmann::json rfin_per_split =
      shape.splits > 0 ? nlohmann::json(sizes[3] / splits) : nlohmann::json(nullptr);
  nlohmann::json report = {
      {"schema", kHierarchySchema},
      {"input", request.input},
      {"source", in.source},
      {"input_counts",
       {{"vertices", in.mesh.vertex_count()}, {"triangles", in.mesh.triangle_count()}}},
      {"base_counts",
       {{"vertices", h.base.vertex_count()}, {"triangles", h.base.triangle_count()}}},
      {"nodes", shape.nodes},
      {"roots", shape.roots},
      {"splits", shape.splits},
      {"depth", shape.depth},
      {"levels_built", built.value().stats.levels_built},
      {"vertices_after_level", built.value().stats.vertices_after_level},
      {"tree_id_bits", shape.tree_bits},
      {"node_id_bits", shape.depth},
      {"id_bits", shape.id_bits},
      {"id_bytes", shape.id_bytes},
      {"seconds", seconds},
      {"output", request.output},
      {"bytes", container.value().size()},
      {"sections",
       {{"META", {{"bytes", sizes[0]}}},
        {"BASE", {{"bytes", sizes[1]}}},
        {"VHIE", {{"bytes", sizes[2]}, {"bytes_per_node", sizes[2] / nodes}}},
        {"RFIN", {{"bytes", sizes[3]}, {"bytes_per_split", rfin_per_split}}}}}};
  if (tool.json()) {
    tool.print_json(report);
    return 0;
  }
  std::cout << "input       " << request.input << " (" << in.source
            << "): " << in.mesh.vertex_count() << " vertices, " << in.mesh.triangle_count()
            << " triangles\n";
  std::cout << "hierarchy   " << shape.nodes << " nodes, " << shape.roots << " roots, "
            << shape.splits << " splits, depth " << shape.depth << " in " << seconds << " s\n";
  std::cout << "ids         <tree-id, node-id> = <" << shape.tree_bits << ", " << shape.depth
            << "> = " << shape.id_bits << " bits (" << shape.id_bytes << "-byte ids)\n";
  std::cout << "base        " << h.base.vertex_count() << " vertices, " << h.base.triangle_count()
            << " triangles\n";
  std::ostringstream per;
  per.precision(3);
  per << "VHIE " << sizes[2] << " bytes (" << sizes[2] / nodes << " per node), RFIN " << sizes[3]
      << " bytes";
  if (shape.splits > 0) per << " (" << sizes[3] / splits << " per split)";
  per << ", BASE " << sizes[1] << ", META " << sizes[0];
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
            "<tree-id, node-id> heap ids and fundamental cut vertices. Writes META, BASE,\n"
            "VHIE and RFIN. Given a container with a progressive mesh (BASE + VSPL), it\n"
            "rebuilds the hierarchy from that PM's fully refined mesh: the PM's own greedy\n"
            "collapse order is not balanced.");
  Request request;
  tool.options().add_options()("output,o",
                               po::value<std::string>(&request.output)->value_name("OUT.lbk"),
                               "the container to write")(
      "sections", po::value<std::string>(&request.sections)->value_name("LIST"),
      "sections to build, separated by commas; this build offers 'vhie' (VHIE + RFIN), "
      "the default. META and BASE are always written")(
      "boundary-weight", po::value<double>(&request.options.boundary_weight)->value_name("W"),
      "weight of the boundary-preserving quadrics (default 10)")(
      "max-normal-change",
      po::value<double>(&request.options.max_normal_change_degrees)->value_name("DEG"),
      "refuse collapses that turn a face normal by more than DEG degrees (default 150)")(
      "repair", po::bool_switch(&request.repair), "repair an input mesh first (see lodbake-pack)");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  if (std::optional<int> code = tool.single_positional("input", "IN", &request.input)) return *code;
  if (request.output.empty()) return tool.usage_error("missing -o OUT.lbk");
  std::stringstream list(request.sections);
  std::string item;
  bool any = false;
  while (std::getline(list, item, ',')) {
    if (item == "vhie" || item == "meta" || item == "base") {
      any = any || item == "vhie";
      continue;
    }
    return tool.usage_error("--sections: '" + item +
                            "' is not built by this lodbake-hierarchy (it offers vhie)");
  }
  if (!any) return tool.usage_error("--sections must include vhie");
  if (!(request.options.max_normal_change_degrees > 0))
    return tool.usage_error("--max-normal-change takes a positive angle");
  if (same_file(request.input, request.output))
    return tool.usage_error("the output '" + request.output + "' is the input itself");
  return tool.run([&] { return run(tool, request); });
}
