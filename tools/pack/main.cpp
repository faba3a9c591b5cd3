// lodbake-pack, two modes chosen by the inputs:
// - a mesh: imports it, checks it, repairs what the other tools could not
//   take, and writes a container with META and BASE;
// - containers (.lbk, told by their magic): merges their sections, drops or
//   keeps tags, rewrites META and recodes the other kinds lodbake defines
//   (compact by default, BASE with Draco on request), printing each
//   section's size before and after.
// Thin: import, check, repair, packing and encoding live in lib/ and formats/.
#include <algorithm>
#include <iostream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

#include "formats/container/container_writer.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/draco_codec.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/quantization.h"
#include "lib/bake/pack_step.h"
#include "lib/ingest/load_mesh.h"
#include "lib/pack/pack_containers.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_pack.h"
#include "tools/common/asset_report.h"
#include "tools/common/cli.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {
namespace {

constexpr const char* kPackSchema = "lodbake.pack/1";

constexpr const char* kRepackSchema = "lodbake.pack.containers/1";

constexpr const char* kAssetSchema = "lodbake.pack.asset/1";

struct PackOptions {
  std::string output;
  bool repair = false;
  bool strict = false;
  int quantize_bits = 0;  // 0: float32 positions (containers: keep the encoding)
  int error_bits = 0;     // 0: keep VSPL's errors as they are
  bool draco = false;
  int qp = 14;
  int cl = 7;
  bool raw = false;
  std::string drop;
  std::string keep;
  bool allow_outside = false;
  unsigned threads = 0;  // 0: every core
};

// "A,B" -> {"A", "B"}; every tag must be 4 printable characters.
bool parse_tags(const std::string& text, std::vector<std::string>* tags, std::string* bad) {
  std::stringstream in(text);
  std::string tag;
  while (std::getline(in, tag, ',')) {
    if (!is_valid_tag(tag)) {
      *bad = tag;
      return false;
    }
    tags->push_back(tag);
  }
  return true;
}

double per(uint64_t bytes, uint64_t count) {
  return count == 0 ? 0.0 : 8.0 * static_cast<double>(bytes) / static_cast<double>(count);
}

int repack(const Tool& tool, const std::vector<std::string>& paths, const PackOptions& options,
           const RepackOptions& repack_options) {
  std::vector<PackInput> inputs;
  for (const std::string& path : paths) {
    Result<Bytes> bytes = read_file(path);
    if (!bytes.is_ok()) return tool.fail(path, bytes.status());
    inputs.push_back({path, std::move(bytes).value()});
  }
  nlohmann::json meta_options = {
      {"draco", options.draco},
      {"compact", !options.raw},
      {"quantize_bits", options.quantize_bits == 0 ? nlohmann::json(nullptr)
                                                   : nlohmann::json(options.quantize_bits)},
      {"drop", repack_options.drop},
      {"keep", repack_options.keep}};
  if (options.draco) meta_options["draco_options"] = {{"qp", options.qp}, {"cl", options.cl}};
  // Only when given, so that the files of earlier versions stay the same.
  if (options.error_bits != 0) meta_options["error_bits"] = options.error_bits;
  size_t failed = inputs.size();
  Result<PackResult> packed =
      repack_containers(std::move(inputs), repack_options, meta_options, &failed);
  if (!packed.is_ok())
    return tool.fail(failed < paths.size() ? paths[failed] : options.output, packed.status());
  const PackResult& r = packed.value();
  Status written = write_file_atomic(options.output, r.file);
  if (!written.is_ok()) return tool.fail(options.output, written);
  if (options.error_bits != 0 && r.splits == 0)
    tool.warn(options.output, "--error-bits changed nothing: the output has no VSPL records");
  // A tag no input holds is most likely misspelt (tags are case-sensitive).
  for (const auto& [option, tags] :
       {std::pair{"--drop", &repack_options.drop}, std::pair{"--keep", &repack_options.keep}}) {
    for (const std::string& tag : *tags) {
      const bool found = std::any_of(r.sections.begin(), r.sections.end(),
                                     [&](const PackedSection& s) { return s.tag == tag; });
      if (!found)
        tool.warn("", std::string(option) + " " + tag +
                          ": no input has that section (tags are case-sensitive)");
    }
  }

  nlohmann::json sections = nlohmann::json::array();
  for (const PackedSection& s : r.sections) {
    nlohmann::json js = {{"tag", s.tag},
                         {"group", s.group},
                         {"source", s.source},
                         {"action", s.action},
                         {"codec_before", s.codec_before},
                         {"stored_before", s.stored_before}};
    if (s.action != "dropped") {
      js["codec_after"] = s.codec_after;
      js["stored_after"] = s.stored_after;
      js["decoded_after"] = s.decoded_after;
      js["bits_per_vertex"] = per(s.stored_after, r.vertices);
      if (s.tag == "VSPL" && s.group == 0) {
        js["bits_per_split"] = per(s.stored_after, r.splits);
        js["error_bits"] =
            options.error_bits == 0 ? nlohmann::json(nullptr) : nlohmann::json(options.error_bits);
      }
    }
    sections.push_back(std::move(js));
  }
  nlohmann::json report = {{"schema", kRepackSchema},
                           {"inputs", paths},
                           {"output", options.output},
                           {"input_bytes", r.input_bytes},
                           {"bytes", r.file.size()},
                           {"vertices", r.vertices},
                           {"triangles", r.triangles},
                           {"splits", r.splits},
                           {"bits_per_vertex", per(r.file.size(), r.vertices)},
                           {"bits_per_triangle", per(r.file.size(), r.triangles)},
                           {"sections", sections}};
  if (tool.json()) {
    tool.print_json(report);
    return 0;
  }
  std::cout << "  tag   action     codec            stored before -> after\n";
  for (const PackedSection& s : r.sections) {
    char row[240];
    std::snprintf(
        row, sizeof(row), "  %-5s %-10s %-16s %llu -> %llu%s\n", s.tag.c_str(), s.action.c_str(),
        (s.codec_before.empty()
             ? std::string("new")
             : s.codec_before + " -> " + (s.codec_after.empty() ? std::string("-") : s.codec_after))
            .c_str(),
        static_cast<unsigned long long>(s.stored_before),
        static_cast<unsigned long long>(s.stored_after),
        s.group == 0 ? "" : (" (group " + std::to_string(s.group) + ")").c_str());
    std::cout << row;
  }
  std::cout << "wrote " << options.output << ": " << r.file.size() << " bytes (inputs "
            << r.input_bytes << "), " << r.vertices << " vertices, " << r.triangles
            << " triangles, " << per(r.file.size(), r.vertices) << " bits per vertex, "
            << per(r.file.size(), r.triangles) << " bits per triangle\n";
  for (const PackedSection& s : r.sections) {
    if (s.tag == "VSPL" && s.group == 0 && s.action != "dropped" && r.splits > 0)
      std::cout << "VSPL: " << per(s.stored_after, r.splits) << " bits per vertex split ("
                << r.splits << " splits"
                << (options.error_bits != 0
                        ? ", errors rounded up to " + std::to_string(options.error_bits) +
                              " significant bits"
                        : std::string())
                << ")\n";
  }
  return 0;
}

int pack(const Tool& tool, const std::string& input, const PackOptions& options) {
  LoadOptions load;
  load.repair = options.repair;
  load.strict = options.strict;
  load.drop_unreferenced = true;
  load.threads = options.threads;
  LoadedMesh loaded;
  if (int code = load_input(tool, input, load, &loaded); code != 0) return code;

  BaseEncodeOptions encoding;
  encoding.quantize = options.quantize_bits != 0;
  if (encoding.quantize) encoding.bits = options.quantize_bits;
  nlohmann::json report = {{"schema", kPackSchema},
                           {"input", input},
                           {"output", options.output},
                           {"import", to_json(loaded.import)},
                           {"check", to_json(loaded.check)}};
  report["repairs"] = repairs_json(load, loaded);
  report["dropped_unreferenced_vertices"] = loaded.dropped_unreferenced;
  if (encoding.quantize) {
    Result<QuantizationReport> q = measure_quantization(loaded.mesh.positions, encoding.bits);
    if (!q.is_ok()) return tool.fail(input, q.status());
    report["quantization"] = {{"bits", encoding.bits},
                              {"max_error", q.value().max_error},
                              {"error_bound", q.value().error_bound}};
  }

  Result<PackedMesh> packed =
      pack_mesh(loaded.mesh, meta_input(input, loaded), options.repair, options.quantize_bits);
  if (!packed.is_ok()) return tool.fail(input, packed.status());
  const Bytes& file = packed.value().file;
  const uint64_t meta_size = packed.value().meta_bytes;
  const uint64_t base_size = packed.value().base_bytes;
  Status written = write_file_atomic(options.output, file);
  if (!written.is_ok()) return tool.fail(options.output, written);

  report["bytes"] = file.size();
  report["sections"] = {{"META", meta_size}, {"BASE", base_size}};
  report["counts"] = {{"vertices", loaded.mesh.vertex_count()},
                      {"triangles", loaded.mesh.triangle_count()}};
  if (tool.json()) {
    tool.print_json(report);
  } else {
    std::cout << "wrote " << options.output << ": " << loaded.mesh.vertex_count() << " vertices, "
              << loaded.mesh.triangle_count() << " triangles, " << file.size() << " bytes (META "
              << meta_size << ", BASE " << base_size << ")\n";
    if (report.contains("quantization"))
      std::cout << "quantized positions to " << encoding.bits << " bits, largest error "
                << report["quantization"]["max_error"].get<double>() << "\n";
  }
  return 0;
}

int pack_asset(const Tool& tool, const std::string& input, const Bytes& bytes,
               const PackOptions& options) {
  ImportReport report;
  SceneResources resources;
  resources.allow_outside = options.allow_outside;
  Result<Scene> scene = read_scene_bytes(input, bytes, resources, &report);
  if (!scene.is_ok()) return tool.fail(input, scene.status());
  for (const std::string& warning : report.warnings)
    tool.warn(input, warning);
  print_import_notes(tool, input, report);

  MetaSection meta = make_meta("lodbake-pack");
  meta.options = pack_meta_options(false, options.quantize_bits);
  meta.input = asset_meta_input(input, bytes);
  BaseEncodeOptions encoding;
  encoding.quantize = options.quantize_bits != 0;
  if (encoding.quantize) encoding.bits = options.quantize_bits;
  Result<ScenePackResult> packed = pack_scene(scene.value(), meta, encoding);
  if (!packed.is_ok()) return tool.fail(input, packed.status());
  const ScenePackResult& r = packed.value();
  for (const std::string& warning : r.warnings)
    tool.warn(options.output, warning);
  Status written = write_file_atomic(options.output, r.file);
  if (!written.is_ok()) return tool.fail(options.output, written);

  const nlohmann::json counts = scene_counts(scene.value());
  if (tool.json()) {
    nlohmann::json groups = nlohmann::json::array();
    for (size_t g = 0; g < r.base_bytes.size(); ++g)
      groups.push_back({{"group", g},
                        {"vertices", r.base_vertices[g]},
                        {"triangles", r.base_triangles[g]},
                        {"base_bytes", r.base_bytes[g]}});
    tool.print_json({{"schema", kAssetSchema},
                     {"input", input},
                     {"output", options.output},
                     {"import", to_json(report)},
                     {"scene", counts},
                     {"bytes", r.file.size()},
                     {"meta_bytes", r.meta_bytes},
                     {"scne_bytes", r.scne_bytes},
                     {"groups", groups}});
    return 0;
  }
  std::cout << "wrote " << options.output << ": " << counts["meshes"].get<uint64_t>() << " meshes ("
            << counts["primitives"].get<uint64_t>() << " primitives, "
            << counts["triangles"].get<uint64_t>() << " triangles) in " << r.base_bytes.size()
            << " groups, " << counts["nodes"].get<uint64_t>() << " nodes, "
            << counts["materials"].get<uint64_t>() << " materials, "
            << counts["images"].get<uint64_t>() << " images; " << r.file.size() << " bytes (META "
            << r.meta_bytes << ", SCNE " << r.scne_bytes << ")\n";
  return 0;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
#if defined(__GLIBC__)
  // A package decodes and codes sections of tens of megabytes one after the
  // other: kept in the heap (up to glibc's largest threshold, 32 MiB), the
  // memory one section frees serves the next instead of going back to the
  // kernel and faulting in again (about a tenth of the dragon's package).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
  Tool tool("lodbake-pack",
            "MESH -o OUT.lbk [options]\n       lodbake-pack A.lbk [B.lbk ...] -o OUT.lbk [options]",
            "With an asset (.gltf with its .bin and images beside it, or .glb; an OBJ with\n"
            "materials, read with its .mtl and images; a PLY with vertex colours): writes\n"
            "the whole asset (every node, mesh, primitive, material, texture, image, skin,\n"
            "animation and extension, in a SCNE section, which `lodbake-inspect --extract\n"
            "OUT.glb` gives back) and, in one group per mesh, a BASE section with that mesh's\n"
            "welded topology (its primitives share the positions along their borders).\n"
            "\n"
            "With a mesh (.obj .ply .off .stl .drc, optionally .gz; see docs/import.md for\n"
            "which OBJ and PLY files are assets): imports it,\n"
            "checks it, repairs it where needed, and writes a lodbake container with a META\n"
            "section (tool, options, input name and SHA-256, counts) and a BASE section.\n"
            "The stored mesh is what lodbake-simplify, -hierarchy, -fan and -strips take:\n"
            "non-manifold edges and vertices are split, degenerate and duplicate triangles\n"
            "dropped and the winding made consistent (positions unchanged; one line says\n"
            "what changed; --strict refuses instead). Non-finite coordinates are refused\n"
            "unless --repair drops the triangles around them.\n"
            "\n"
            "With containers (.lbk) baked from the same input (META input hash): merges\n"
            "their sections, drops or keeps tags, stores VSPL, VHIE, RFIN, DAGE, VTRE, FANH,\n"
            "STRP and SETS with their lossless compact codecs (or raw with --raw) and BASE\n"
            "with Draco on --draco, copies other sections byte for byte, and prints each\n"
            "section's size before and after. Same inputs and options give the same bytes;\n"
            "packing a packed file again changes nothing.");
  PackOptions options;
  tool.options().add_options()("output,o",
                               po::value<std::string>(&options.output)->value_name("OUT"),
                               "the container to write (required)")(
      "repair", po::bool_switch(&options.repair),
      "mesh input: fix what can be fixed first (CGAL Polygon Mesh Processing): drop "
      "non-finite, degenerate and duplicate triangles and unreferenced vertices, split "
      "non-manifold edges and vertices, orient consistently")(
      "strict", po::bool_switch(&options.strict),
      "mesh input: refuse a mesh that needs repairing (exit 3) instead of repairing it by "
      "default: non-manifold edges or vertices, degenerate or duplicate triangles, "
      "inconsistent orientation")(
      "quantize", po::value<int>(&options.quantize_bits)->value_name("BITS"),
      "store positions quantized to BITS (1..30) bits per coordinate instead of float32 "
      "(containers: BASE and VSPL positions not already at BITS)")(
      "error-bits", po::value<int>(&options.error_bits)->value_name("BITS"),
      "containers: round VSPL collapse errors up to BITS (1..24) significant bits, so "
      "that the compact codec stores fewer bits per error (lossy; 24 keeps float32's "
      "full precision)")(
      "draco", po::bool_switch(&options.draco),
      "containers: store BASE as a Draco bitstream (vertex ids kept); a float32 VSPL is "
      "quantized to --qp bits")("qp", po::value<int>(&options.qp)->value_name("BITS"),
                                "Draco position quantization, 1..24 bits (default 14; float32 "
                                "positions hold no more)")(
      "cl", po::value<int>(&options.cl)->value_name("LEVEL"),
      "Draco compression level, 0..10 (default 7)")(
      "raw", po::bool_switch(&options.raw),
      "containers: store every section raw instead of with its compact codec")(
      "drop", po::value<std::string>(&options.drop)->value_name("TAG,..."),
      "containers: leave out these sections")(
      "keep", po::value<std::string>(&options.keep)->value_name("TAG,..."),
      "containers: write only these sections (and META)")(
      "allow-outside", po::bool_switch(&options.allow_outside),
      "asset: let its URIs (glTF) or material libraries and maps (OBJ) name files outside "
      "its folder (refused by default)")(
      "threads", po::value<unsigned>(&options.threads)->value_name("N"),
      "threads for the mesh check and, with containers, for coding a group's sections "
      "after BASE side by side (oneTBB): 0 (default) every core, or 1 to 4096; the output "
      "is the same bytes for any N");
  tool.positional("input", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  const std::vector<std::string> inputs = tool.positionals("input");
  if (inputs.empty()) return tool.usage_error("missing MESH or A.lbk");
  if (options.output.empty()) return tool.usage_error("missing -o OUT.lbk");
  if (std::optional<int> code = check_quantize_bits(tool, options.quantize_bits)) return *code;
  if (!is_valid_draco_quantization_bits(options.qp))
    return tool.usage_error("--qp takes " + std::to_string(kMinDracoQuantizationBits) + " to " +
                            std::to_string(kMaxDracoQuantizationBits) + " bits, not " +
                            std::to_string(options.qp));
  if (options.cl < 0 || options.cl > 10)
    return tool.usage_error("--cl takes 0 to 10, not " + std::to_string(options.cl));
  if (options.threads > 4096)
    return tool.usage_error("--threads takes a count from 0 (every core) to 4096");
  if (tool.has("error-bits") &&
      (options.error_bits < kMinSignificantBits || options.error_bits > kMaxSignificantBits))
    return tool.usage_error("--error-bits takes 1 to 24 bits, not " +
                            std::to_string(options.error_bits));
  RepackOptions repack_options;
  std::string bad;
  if (!parse_tags(options.drop, &repack_options.drop, &bad) ||
      !parse_tags(options.keep, &repack_options.keep, &bad))
    return tool.usage_error("'" + bad + "' is not a section tag (4 printable characters)");

  bool containers = false;
  for (const std::string& input : inputs) {
    if (is_container_input(input)) containers = true;
  }
  for (const std::string& input : inputs) {
    if (same_file(input, options.output)) {
      return tool.usage_error("the output '" + options.output + "' is " +
                              (containers ? "also an input" : "the input mesh itself"));
    }
  }
  if (!containers) {
    if (inputs.size() != 1)
      return tool.usage_error("expected one MESH (or containers), got " +
                              std::to_string(inputs.size()));
    if (options.draco || options.raw || !options.drop.empty() || !options.keep.empty() ||
        options.error_bits != 0 || tool.has("qp") || tool.has("cl"))
      return tool.usage_error(
          "--draco, --qp, --cl, --raw, --error-bits, --drop and --keep apply to .lbk inputs");
    if (std::optional<int> code = tool.check_outputs({options.output})) return *code;
    return tool.run([&] {
      Result<Bytes> bytes = read_file(inputs.front());
      if (bytes.is_ok() && is_asset(inputs.front(), bytes.value())) {
        if (options.repair || options.strict)
          return tool.usage_error(
              "--repair and --strict apply to a mesh; an asset's meshes are stored as the "
              "file has them (a builder repairs what it must when it reads them)");
        return pack_asset(tool, inputs.front(), bytes.value(), options);
      }
      if (options.allow_outside)
        return tool.usage_error("--allow-outside applies to a glTF asset or an OBJ with materials");
      return pack(tool, inputs.front(), options);
    });
  }
  for (const std::string& input : inputs) {
    if (is_container_input(input)) continue;
    // A missing or unreadable input (or a folder) is an I/O error, not a
    // mesh given among containers.
    Result<Bytes> readable = read_file(input);
    if (!readable.is_ok()) return tool.fail(input, readable.status());
    return tool.usage_error("'" + input + "' is not a lodbake container (a mesh is packed alone)");
  }
  if (options.repair) return tool.usage_error("--repair applies to a mesh input");
  if (options.strict) return tool.usage_error("--strict applies to a mesh input");
  if (!options.draco && (tool.has("qp") || tool.has("cl")))
    return tool.usage_error("--qp and --cl apply with --draco");
  if (options.draco && !draco_codec_built())
    return tool.fail("", unsupported("--draco: this build has no Draco codec"));
  repack_options.quantize_bits = options.quantize_bits;
  repack_options.error_bits = options.error_bits;
  repack_options.compact = !options.raw;
  repack_options.draco = options.draco;
  repack_options.draco_options.quantization_bits = options.qp;
  repack_options.draco_options.compression_level = options.cl;
  repack_options.threads = options.threads;
  if (std::optional<int> code = tool.check_outputs({options.output})) return *code;
  return tool.run([&] { return repack(tool, inputs, options, repack_options); });
}
