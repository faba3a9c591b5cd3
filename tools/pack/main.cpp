// lodbake-pack: imports a mesh, checks it (optionally repairs it) and writes
// a container with META and BASE. Later stages add their sections to the
// same kind of file. Thin: import, check, repair and encoding live in lib/
// and formats/.
#include <iostream>
#include <nlohmann/json.hpp>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "lib/ingest/load_mesh.h"
#include "tools/common/cli.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {
namespace {

constexpr const char* kPackSchema = "lodbake.pack/1";

struct PackOptions {
  std::string output;
  bool repair = false;
  int quantize_bits = 0;  // 0: float32 positions
};

int pack(const Tool& tool, const std::string& input, const PackOptions& options) {
  LoadOptions load;
  load.repair = options.repair;
  load.drop_unreferenced = true;
  LoadedMesh loaded;
  if (int code = load_input(tool, input, load, &loaded); code != 0) return code;

  MetaSection meta = make_meta("lodbake-pack");
  meta.options = {
      {"repair", options.repair},
      {"quantize_bits", options.quantize_bits == 0 ? nlohmann::json(nullptr)
                                                   : nlohmann::json(options.quantize_bits)}};
  meta.input = meta_input(input, loaded);
  meta.counts = {{"vertices", loaded.mesh.vertex_count()},
                 {"triangles", loaded.mesh.triangle_count()}};
  Result<Bytes> meta_bytes = encode_meta(meta);
  if (!meta_bytes.is_ok()) return tool.fail(input, meta_bytes.status());

  BaseEncodeOptions encoding;
  encoding.quantize = options.quantize_bits != 0;
  if (encoding.quantize) encoding.bits = options.quantize_bits;
  Result<Bytes> base_bytes = encode_base(loaded.mesh, encoding);
  if (!base_bytes.is_ok()) return tool.fail(input, base_bytes.status());
  nlohmann::json report = {{"schema", kPackSchema},
                           {"input", input},
                           {"output", options.output},
                           {"import", to_json(loaded.import)},
                           {"check", to_json(loaded.check)}};
  if (loaded.repair) report["repair"] = to_json(*loaded.repair);
  report["dropped_unreferenced_vertices"] = loaded.dropped_unreferenced;
  if (encoding.quantize) {
    Result<QuantizationReport> q = measure_quantization(loaded.mesh.positions, encoding.bits);
    if (!q.is_ok()) return tool.fail(input, q.status());
    report["quantization"] = {{"bits", encoding.bits},
                              {"max_error", q.value().max_error},
                              {"error_bound", q.value().error_bound}};
  }

  ContainerWriter writer;
  size_t meta_size = meta_bytes.value().size();
  size_t base_size = base_bytes.value().size();
  Status added = writer.add_section(kMetaTag, std::move(meta_bytes).value(), false);
  if (added.is_ok()) added = writer.add_section(kBaseTag, std::move(base_bytes).value(), true);
  if (!added.is_ok()) return tool.fail(options.output, added);
  Result<Bytes> file = writer.finish();
  if (!file.is_ok()) return tool.fail(options.output, file.status());
  Status written = write_file_atomic(options.output, file.value());
  if (!written.is_ok()) return tool.fail(options.output, written);

  report["bytes"] = file.value().size();
  report["sections"] = {{"META", meta_size}, {"BASE", base_size}};
  report["counts"] = {{"vertices", loaded.mesh.vertex_count()},
                      {"triangles", loaded.mesh.triangle_count()}};
  if (tool.json()) {
    tool.print_json(report);
  } else {
    std::cout << "wrote " << options.output << ": " << loaded.mesh.vertex_count() << " vertices, "
              << loaded.mesh.triangle_count() << " triangles, " << file.value().size()
              << " bytes (META " << meta_size << ", BASE " << base_size << ")\n";
    if (report.contains("quantization"))
      std::cout << "quantized positions to " << encoding.bits << " bits, largest error "
                << report["quantization"]["max_error"].get<double>() << "\n";
  }
  return 0;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  Tool tool("lodbake-pack", "MESH -o OUT.lbk [options]",
            "Imports a mesh (.obj .ply .off .stl .gltf .glb .drc, optionally .gz), checks it,\n"
            "optionally repairs it, and writes a lodbake container with a META section\n"
            "(tool, options, input name and SHA-256, counts) and a BASE section (the mesh).\n"
            "Meshes with non-finite coordinates or edges shared by more than two triangles\n"
            "are refused unless --repair fixes them; other problems are kept with a warning.");
  PackOptions options;
  tool.options().add_options()("output,o",
                               po::value<std::string>(&options.output)->value_name("OUT"),
                               "the container to write (required)")(
      "repair", po::bool_switch(&options.repair),
      "fix what can be fixed first (CGAL Polygon Mesh Processing): drop non-finite, degenerate "
      "and duplicate triangles and unreferenced vertices, split non-manifold edges and "
      "vertices, orient consistently")(
      "quantize", po::value<int>(&options.quantize_bits)->value_name("BITS"),
      "store positions quantized to BITS (1..30) bits per coordinate instead of float32");
  tool.positional("mesh", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  std::string input;
  if (std::optional<int> code = tool.single_positional("mesh", "MESH", &input)) return *code;
  if (options.output.empty()) return tool.usage_error("missing -o OUT.lbk");
  if (same_file(input, options.output))
    return tool.usage_error("the output '" + options.output + "' is the input mesh itself");
  if (std::optional<int> code = check_quantize_bits(tool, options.quantize_bits)) return *code;
  return tool.run([&] { return pack(tool, input, options); });
}
