// lodbake-inspect: looks inside a .lbk container (header, sections,
// checksums, counts; --validate, --extract) or lints a mesh file (the import
// check report; --strict). Thin: every check lives in formats/ and lib/.
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>

#include "formats/container/container_errors.h"
#include "formats/container/container_layout.h"
#include "formats/container/container_listing.h"
#include "formats/container/container_reader.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/dage.h"
#include "formats/sections/fanh.h"
#include "formats/sections/meta.h"
#include "formats/sections/open_container.h"
#include "formats/sections/rfin.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/section_validation.h"
#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vtre.h"
#include "formats/support/bit_packing.h"
#include "formats/support/file_io.h"
#include "lib/ingest/load_mesh.h"
#include "lib/meshio/mesh_import.h"
#include "lib/meshio/mesh_writers.h"
#include "lib/scene/scene_container.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_levels.h"
#include "lib/scene/scene_summary.h"
#include "lib/simplify/lod_chain.h"
#include "lib/simplify/pm_replay.h"
#include "lib/validate/structure_validation.h"
#include "tools/common/cli.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {
namespace {

constexpr const char* kContainerSchema = "lodbake.inspect.container/1";
constexpr const char* kMeshSchema = "lodbake.inspect.mesh/1";

struct InspectOptions {
  bool validate = false;
  bool strict = false;
  std::string extract;
  std::optional<LodRequest> lod;  // --lod: extract the PM at this level
  std::optional<uint32_t> group;  // --group: extract from this group
};

// The per mesh and primitive lines of an asset.
void print_scene(std::ostream& out, const SceneSummary& s) {
  out << "scene         " << s.nodes << " nodes, " << s.meshes.size() << " meshes (" << s.primitives
      << " primitives, " << s.triangles << " triangles, " << s.instanced_triangles << " drawn), "
      << s.materials << " materials, " << s.textures << " textures, " << s.images << " images";
  if (s.missing_images != 0) out << " (" << s.missing_images << " missing)";
  out << ", " << s.skins << " skins, " << s.animations << " animations\n";
  if (!s.extensions_used.empty()) {
    out << "extensions   ";
    for (const std::string& e : s.extensions_used)
      out << " " << e;
    out << "\n";
  }
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    const MeshSummary& mesh = s.meshes[m];
    out << "mesh " << m << (mesh.name.empty() ? "" : " '" + mesh.name + "'") << ": "
        << mesh.triangles << " triangles, " << mesh.points << " points, used by "
        << mesh.nodes.size() << (mesh.nodes.size() == 1 ? " node" : " nodes")
        << (mesh.skinned ? ", skinned" : "") << ", " << mesh.seam_points << " seam points, "
        << mesh.border_points << " material border points\n";
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const PrimitiveSummary& prim = mesh.primitives[p];
      out << "  primitive " << p << ": " << prim.mode << ", " << prim.triangles << " triangles, "
          << prim.vertices << " vertices, material ";
      if (prim.material < 0) {
        out << "none";
      } else {
        out << prim.material << (prim.material_name.empty() ? "" : " '" + prim.material_name + "'");
      }
      if (prim.targets != 0) out << ", " << prim.targets << " morph targets";
      out << ", " << prim.seam_points << " seam points\n";
      for (const std::string& a : prim.attributes)
        out << "    " << a << "\n";
    }
  }
}

std::string hex32(uint32_t value) {
  char text[9];
  std::snprintf(text, sizeof(text), "%08x", value);
  return text;
}

const char* binding_name(AttributeBinding binding) {
  switch (binding) {
    case AttributeBinding::kNone:
      return "none";
    case AttributeBinding::kPerVertex:
      return "per-vertex";
    case AttributeBinding::kPerCorner:
      return "per-corner";
  }
  return "?";
}

nlohmann::json listing_json(const ContainerListing& listing) {
  nlohmann::json j;
  j["file_bytes"] = listing.actual_size;
  j["magic_ok"] = listing.magic_ok;
  if (listing.header_read) {
    const ContainerHeader& h = listing.header;
    j["header"] = {{"version", std::to_string(h.major) + "." + std::to_string(h.minor)},
                   {"flags", h.flags},
                   {"file_size", h.file_size},
                   {"table_offset", h.table_offset},
                   {"section_count", h.section_count},
                   {"checksum_ok", listing.header_crc_ok}};
  }
  j["table_checksum_ok"] = listing.table_crc_ok;
  nlohmann::json sections = nlohmann::json::array();
  for (const SectionListing& s : listing.sections) {
    nlohmann::json js = {
        {"tag", s.display_tag},
        {"group", s.entry.group},
        {"codec", codec_name(s.entry.codec) != nullptr ? codec_name(s.entry.codec)
                                                       : std::to_string(s.entry.codec)},
        {"required", s.entry.required()},
        {"known", s.known},
        {"offset", s.entry.offset},
        {"stored_bytes", s.entry.stored_size},
        {"decoded_bytes", s.entry.decoded_size},
        {"crc32c", hex32(s.entry.crc32c)}};
    js["checksum_ok"] = s.crc_checked ? nlohmann::json(s.crc_ok) : nlohmann::json(nullptr);
    sections.push_back(std::move(js));
  }
  j["sections"] = std::move(sections);
  return j;
}

void print_listing(std::ostream& out, const std::string& path, const ContainerListing& listing) {
  out << "file          " << path << " (" << listing.actual_size << " bytes)\n";
  if (!listing.header_read) return;
  const ContainerHeader& h = listing.header;
  out << "format        lodbake container " << h.major << "." << h.minor << ", flags " << h.flags
      << ", header checksum " << (listing.header_crc_ok ? "ok" : "BAD") << "\n";
  out << "sections      " << h.section_count << " (table at byte " << h.table_offset
      << ", checksum " << (listing.table_crc_ok ? "ok" : "BAD") << ")\n";
  if (listing.sections.empty()) return;
  out << "  tag   codec   offset      stored     decoded     crc32c    checksum\n";
  for (const SectionListing& s : listing.sections) {
    char row[160];
    const std::string group =
        s.entry.group == 0 ? std::string() : " (group " + std::to_string(s.entry.group) + ")";
    std::snprintf(
        row, sizeof(row), "  %-5s %-7s %-11llu %-10llu %-11llu %s  %s%s%s\n", s.display_tag.c_str(),
        codec_name(s.entry.codec) != nullptr ? codec_name(s.entry.codec) : "?",
        static_cast<unsigned long long>(s.entry.offset),
        static_cast<unsigned long long>(s.entry.stored_size),
        static_cast<unsigned long long>(s.entry.decoded_size), hex32(s.entry.crc32c).c_str(),
        !s.crc_checked ? "-" : (s.crc_ok ? "ok" : "BAD"),
        s.known ? "" : (s.entry.required() ? " (unknown, required)" : " (unknown)"), group.c_str());
    out << row;
  }
}

// STRP's and SETS's fixed fields (O(1)), or the error through `keep`.
template <typename Keep>
nlohmann::json strips_contents(const Section& section, Keep keep) {
  if (section.tag() == kStrpTag) {
    Result<StrpSummary> strp = read_strp_summary(section.data, section.size);
    if (!strp.is_ok()) return keep(strp.status());
    return {{"strips", strp.value().strip_count},
            {"indices", strp.value().index_count},
            {"vertices", strp.value().vertex_count}};
  }
  Result<SetsSummary> sets = read_sets_summary(section.data, section.size);
  if (!sets.is_ok()) return keep(sets.status());
  const SetsSummary& g = sets.value();
  return {{"strips", g.strip_count},         {"lods", g.lod_count},   {"vertices", g.vertex_count},
          {"beginnings", g.beginning_count}, {"nodes", g.node_count}, {"arcs", g.arc_count},
          {"successors", g.successor_count}};
}

// What each known section holds, without decoding whole arrays. A section
// whose summary does not decode shows its error instead, and the first such
// error is kept in `first_error`.
nlohmann::json section_contents(const Container& container, Status* first_error) {
  nlohmann::json contents = nlohmann::json::object();
  auto keep = [&](const Status& status) {
    if (first_error->is_ok()) *first_error = status;
    return nlohmann::json(status.message());
  };
  for (const Section& section : container.sections) {
    if (section.tag() == kMetaTag) {
      Result<nlohmann::json> meta = decode_meta_json(section.data, section.size);
      contents[kMetaTag] = meta.is_ok() ? meta.value() : keep(meta.status());
    } else if (section.tag() == kBaseTag) {
      Result<BaseSummary> base = read_base_summary(section.data, section.size);
      if (!base.is_ok()) {
        contents[kBaseTag] = keep(base.status());
        continue;
      }
      const BaseSummary& b = base.value();
      nlohmann::json jb = {{"vertices", b.vertex_count},
                           {"triangles", b.triangle_count},
                           {"index_bits", b.index_bits},
                           {"normals", binding_name(b.normals_binding)},
                           {"texcoords", binding_name(b.texcoords_binding)}};
      if (b.position_encoding == PositionEncoding::kQuantized) {
        jb["positions"] = "quantized";
        jb["quantization_bits"] = b.quantization_bits;
        jb["box"] = {{"min", to_json(b.box_min)}, {"max", to_json(b.box_max)}};
      } else {
        jb["positions"] = "float32";
      }
      contents[kBaseTag] = std::move(jb);
    } else if (section.tag() == kVsplTag) {
      Result<VsplSummary> vspl = read_vspl_summary(section.data, section.size);
      if (!vspl.is_ok()) {
        contents[kVsplTag] = keep(vspl.status());
        continue;
      }
      const VsplSummary& v = vspl.value();
      nlohmann::json jv = {{"splits", v.split_count},
                           {"base_vertices", v.base_vertex_count},
                           {"full_vertices", v.full_vertex_count()},
                           {"error_range", {v.min_error, v.max_error}},
                           {"stores_vs_positions", (v.flags & kVsplStoresVsPositions) != 0},
                           {"stores_permutation", (v.flags & kVsplStoresPermutation) != 0}};
      jv["positions"] =
          v.position_encoding == PositionEncoding::kQuantized ? "quantized" : "float32";
      if (v.position_encoding == PositionEncoding::kQuantized)
        jv["quantization_bits"] = v.quantization_bits;
      contents[kVsplTag] = std::move(jv);
    } else if (section.tag() == kDageTag) {
      Result<DageSummary> dage = read_dage_summary(section.data, section.size);
      if (!dage.is_ok()) {
        contents[kDageTag] = keep(dage.status());
        continue;
      }
      const DageSummary& g = dage.value();
      contents[kDageTag] = {
          {"nodes", g.node_count},
          {"edges", g.edge_count},
          {"roots", g.root_count},
          {"leaves", g.leaf_count},
          {"parent_bits", g.parent_bits},
          {"degree_bits", g.degree_bits},
          {"bytes", section.size},
          {"bytes_per_node", g.node_count == 0 ? 0.0 : double(section.size) / g.node_count}};
    } else if (section.tag() == kVtreTag) {
      Result<VtreSummary> vtre = read_vtre_summary(section.data, section.size);
      if (!vtre.is_ok()) {
        contents[kVtreTag] = keep(vtre.status());
        continue;
      }
      const VtreSummary& t = vtre.value();
      contents[kVtreTag] = {
          {"base_nodes", t.base_vertex_count},
          {"splits", t.split_count},
          {"nodes", t.node_count()},
          {"fan_runs", t.run_count},
          {"fan_vertices", t.fan_vertex_count},
          {"id_bits", t.id_bits},
          {"bytes", section.size},
          {"bytes_per_node", t.node_count() == 0 ? 0.0 : double(section.size) / t.node_count()}};
    } else if (section.tag() == kVhieTag) {
      Result<VhieSummary> vhie = read_vhie_summary(section.data, section.size);
      if (!vhie.is_ok()) {
        contents[kVhieTag] = keep(vhie.status());
        continue;
      }
      const VhieSummary& v = vhie.value();
      const uint64_t splits = (uint64_t{v.node_count} - v.root_count) / 2;
      const int tree_bits = bits_for_count(v.root_count);
      contents[kVhieTag] = {
          {"nodes", v.node_count},     {"roots", v.root_count},
          {"splits", splits},          {"depth", v.depth},
          {"tree_id_bits", tree_bits}, {"id_bits", tree_bits + static_cast<int>(v.depth)}};
    } else if (section.tag() == kRfinTag) {
      Result<uint32_t> rfin = read_rfin_summary(section.data, section.size);
      contents[kRfinTag] =
          rfin.is_ok() ? nlohmann::json{{"records", rfin.value()}} : keep(rfin.status());
    } else if (section.tag() == kFanhTag) {
      // Depth and fan sizes need the whole forest; decoding is linear and cheap.
      Result<FanHierarchy> fanh = decode_fanh(section.data, section.size);
      if (!fanh.is_ok()) {
        contents[kFanhTag] = keep(fanh.status());
        continue;
      }
      const FanhStats f = fanh_stats(fanh.value());
      contents[kFanhTag] = {{"internal_nodes", f.internal_nodes},
                            {"leaves", f.leaves},
                            {"roots", f.roots},
                            {"depth", f.depth},
                            {"average_children", f.average_children},
                            {"removed_entries", f.removed_entries},
                            {"modified_entries", f.modified_entries},
                            {"bytes", section.size}};
    } else if (section.tag() == kStrpTag || section.tag() == kSetsTag) {
      contents[section.tag()] = strips_contents(section, keep);
    }
  }
  return contents;
}

void print_contents(std::ostream& out, const nlohmann::json& contents) {
  if (contents.contains(kMetaTag)) {
    const nlohmann::json& m = contents[kMetaTag];
    out << "META          ";
    if (m.is_object()) {
      out << m.value("tool", "?") << " " << m.value("version", "?");
      if (m.contains("input") && m["input"].is_object())
        out << ", input " << m["input"].value("file", "?") << " ("
            << m["input"].value("bytes", uint64_t{0}) << " bytes, sha256 "
            << m["input"].value("sha256", "?").substr(0, 16) << "...)";
      out << "\n";
    } else {
      out << m.get<std::string>() << "\n";
    }
  }
  if (contents.contains(kBaseTag)) {
    const nlohmann::json& b = contents[kBaseTag];
    out << "BASE          ";
    if (!b.is_object()) {
      out << b.get<std::string>() << "\n";
      return;
    }
    out << b["vertices"].get<uint64_t>() << " vertices, " << b["triangles"].get<uint64_t>()
        << " triangles, positions " << b["positions"].get<std::string>();
    if (b.contains("quantization_bits"))
      out << " (" << b["quantization_bits"].get<int>() << " bits)";
    out << ", indices " << b["index_bits"].get<int>() << " bits, normals "
        << b["normals"].get<std::string>() << ", texcoords " << b["texcoords"].get<std::string>()
        << "\n";
  }
  if (contents.contains(kVsplTag)) {
    const nlohmann::json& v = contents[kVsplTag];
    out << "VSPL          ";
    if (!v.is_object()) {
      out << v.get<std::string>() << "\n";
      return;
    }
    out << "progressive mesh: " << v["splits"].get<uint64_t>() << " vertex splits from "
        << v["base_vertices"].get<uint64_t>() << " to " << v["full_vertices"].get<uint64_t>()
        << " vertices, collapse errors " << v["error_range"][0].get<double>() << " .. "
        << v["error_range"][1].get<double>() << " (model units), positions "
        << v["positions"].get<std::string>() << "\n";
  }
  if (contents.contains(kDageTag)) {
    const nlohmann::json& g = contents[kDageTag];
    out << "DAGE          ";
    if (g.is_object()) {
      char line[200];
      std::snprintf(line, sizeof(line),
                    "split DAG: %llu nodes, %llu edges, %llu roots, %llu leaves, %.2f bytes/node\n",
                    g["nodes"].get<unsigned long long>(), g["edges"].get<unsigned long long>(),
                    g["roots"].get<unsigned long long>(), g["leaves"].get<unsigned long long>(),
                    g["bytes_per_node"].get<double>());
      out << line;
    } else {
      out << g.get<std::string>() << "\n";
    }
  }
  if (contents.contains(kVtreTag)) {
    const nlohmann::json& t = contents[kVtreTag];
    out << "VTRE          ";
    if (t.is_object()) {
      char line[200];
      std::snprintf(line, sizeof(line),
                    "vertex trees: %llu base nodes, %llu splits, %llu nodes, %llu fan vertices, "
                    "%.2f bytes/node\n",
                    t["base_nodes"].get<unsigned long long>(),
                    t["splits"].get<unsigned long long>(), t["nodes"].get<unsigned long long>(),
                    t["fan_vertices"].get<unsigned long long>(), t["bytes_per_node"].get<double>());
      out << line;
    } else {
      out << t.get<std::string>() << "\n";
    }
  }
  if (contents.contains(kVhieTag)) {
    const nlohmann::json& v = contents[kVhieTag];
    out << "VHIE          ";
    if (!v.is_object()) {
      out << v.get<std::string>() << "\n";
    } else {
      out << "balanced vertex hierarchy: " << v["nodes"].get<uint64_t>() << " nodes, "
          << v["roots"].get<uint64_t>() << " roots, " << v["splits"].get<uint64_t>()
          << " splits, depth " << v["depth"].get<uint64_t>() << ", <tree-id, node-id> = <"
          << v["tree_id_bits"].get<int>() << ", " << v["depth"].get<uint64_t>()
          << "> = " << v["id_bits"].get<int>() << " bits\n";
    }
  }
  if (contents.contains(kRfinTag)) {
    const nlohmann::json& r = contents[kRfinTag];
    out << "RFIN          ";
    if (!r.is_object()) {
      out << r.get<std::string>() << "\n";
    } else {
      out << "refinement data: " << r["records"].get<uint64_t>()
          << " split records (sphere, normal cone, mu^2, delta^2)\n";
    }
  }
  if (contents.contains(kFanhTag)) {
    const nlohmann::json& f = contents[kFanhTag];
    out << "FANH          ";
    if (!f.is_object()) {
      out << f.get<std::string>() << "\n";
    } else {
      out << "fan hierarchy: " << f["internal_nodes"].get<uint64_t>() << " internal nodes, "
          << f["leaves"].get<uint64_t>() << " leaves, " << f["roots"].get<uint64_t>()
          << " roots, depth " << f["depth"].get<uint64_t>() << ", "
          << f["average_children"].get<double>() << " children on average, "
          << f["bytes"].get<uint64_t>() << " bytes\n";
    }
  }
  if (contents.contains(kStrpTag)) {
    const nlohmann::json& t = contents[kStrpTag];
    out << "STRP          ";
    if (!t.is_object()) {
      out << t.get<std::string>() << "\n";
    } else {
      out << t["strips"].get<uint64_t>() << " triangle strips, " << t["indices"].get<uint64_t>()
          << " indices over " << t["vertices"].get<uint64_t>() << " vertices\n";
    }
  }
  if (contents.contains(kSetsTag)) {
    const nlohmann::json& g = contents[kSetsTag];
    out << "SETS          ";
    if (!g.is_object()) {
      out << g.get<std::string>() << "\n";
    } else {
      out << "strip graph: " << g["strips"].get<uint64_t>() << " strips over "
          << g["lods"].get<uint64_t>() << " LoDs, " << g["nodes"].get<uint64_t>() << " nodes, "
          << g["arcs"].get<uint64_t>() << " arcs, " << g["successors"].get<uint64_t>()
          << " successors, " << g["beginnings"].get<uint64_t>() << " beginnings\n";
    }
  }
}

// A failure and the file it concerns (the container or the output).
struct FileStatus {
  std::string file;
  Status status;
};

// The base mesh, or with a LoD request the PM's mesh at that level.
Result<TriangleMesh> mesh_to_extract(const OpenedContainer& file,
                                     const std::optional<LodRequest>& lod,
                                     std::optional<uint32_t> chosen, nlohmann::json* report) {
  // Without --group: group 0, or for a level the first progressive mesh.
  uint32_t group = chosen.value_or(0);
  if (!chosen && lod) {
    LODBAKE_ASSIGN_OR_RETURN(
        group, file.group_with({kBaseTag, kVsplTag}, "--lod", "lodbake-simplify --pm"));
  }
  if (group >= std::max<uint32_t>(file.group_count(), 1)) {
    return container_error(ContainerError::kMissingSection,
                           "the container has no group " + std::to_string(group) + " (it has " +
                               std::to_string(file.group_count()) + ")");
  }
  (*report)["group"] = group;
  const Container& container = file.decoded();
  LODBAKE_ASSIGN_OR_RETURN(const Section* base, container.require(kBaseTag, group));
  if (!lod && container.find(kStrpTag, group) != nullptr) {
    // Strips alone: their triangles, indexed over BASE's vertices.
    const Section* strp = container.find(kStrpTag, group);
    LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, decode_base(base->data, base->size));
    LODBAKE_ASSIGN_OR_RETURN(TriangleStrips strips, decode_strp(strp->data, strp->size));
    (*report)["from_strips"] = strips.strip_count();
    return mesh_from_strips(strips, mesh);
  }
  if (!lod) return decode_base(base->data, base->size);
  LODBAKE_ASSIGN_OR_RETURN(const Section* vspl, container.require(kVsplTag, group));
  LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh pm,
                           decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size));
  size_t vertices = lod_vertex_count(pm, *lod);
  (*report)["lod_vertices"] = vertices;
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, mesh_at_lod(pm, vertices));
  // The fully refined mesh is the input: give it the input's vertex order.
  if (vertices == pm.full_vertex_count()) return map_to_input(pm, mesh);
  return mesh;
}

FileStatus extract_base(const Tool& tool, const std::string& path, const OpenedContainer& file,
                        const InspectOptions& options, nlohmann::json* report) {
  const std::string& out_path = options.extract;
  nlohmann::json extracted;
  Result<TriangleMesh> mesh = mesh_to_extract(file, options.lod, options.group, &extracted);
  if (!mesh.is_ok()) return {path, mesh.status()};
  Result<Bytes> bytes = write_mesh_for_path(out_path, mesh.value());
  if (!bytes.is_ok()) return {out_path, bytes.status()};
  Status written = write_file_atomic(out_path, bytes.value());
  if (!written.is_ok()) return {out_path, written};
  // After the write: a failed run prints its error alone.
  if (drops_attributes(out_path, mesh.value()))
    tool.warn(out_path,
              "this format cannot store the mesh's normals or texture coordinates; "
              "they are not written");
  extracted["file"] = out_path;
  extracted["bytes"] = bytes.value().size();
  extracted["vertices"] = mesh.value().vertex_count();
  extracted["triangles"] = mesh.value().triangle_count();
  (*report)["extracted"] = std::move(extracted);
  return {};
}

FileStatus extract_asset(const Tool& tool, const Scene& scene, const std::string& out_path,
                         nlohmann::json* report) {
  SceneWriteReport written;
  Status status = write_scene_file(out_path, scene, &written);
  if (!status.is_ok()) return {out_path, status};
  for (const std::string& warning : written.warnings)
    tool.warn(out_path, warning);
  const SceneSummary s = summarize_scene(scene);
  (*report)["extracted"] = {{"file", out_path},          {"asset", true},
                            {"meshes", s.meshes.size()}, {"primitives", s.primitives},
                            {"triangles", s.triangles},  {"images", s.images}};
  return {};
}

int inspect_container(const Tool& tool, const std::string& path, const Bytes& bytes,
                      const InspectOptions& options) {
  ContainerListing listing = list_container(bytes.data(), bytes.size());
  nlohmann::json report = {{"schema", kContainerSchema}, {"file", path}};
  report["container"] = listing_json(listing);
  if (!listing.status.is_ok()) {
    report["error"] = listing.status.message();
    if (tool.json()) {
      tool.print_json(report);
    } else {
      print_listing(std::cout, path, listing);
    }
    return tool.fail(path, listing.status);
  }
  // Sections stored compact or with Draco are read as their raw payloads.
  Result<OpenedContainer> opened = open_container(bytes);
  if (!opened.is_ok()) {
    const Status& codecs = opened.status();
    // As for a broken file: the listing, then the error.
    report["error"] = codecs.message();
    if (tool.json()) {
      tool.print_json(report);
    } else {
      print_listing(std::cout, path, listing);
    }
    return tool.fail(path, codecs);
  }
  const OpenedContainer& file = opened.value();
  Status undecodable;
  // Group 0's contents, and with several groups each group's.
  report["contents"] = section_contents(single_group(file.decoded(), 0), &undecodable);
  if (file.group_count() > 1) {
    nlohmann::json groups = nlohmann::json::array();
    groups.push_back(report["contents"]);
    for (uint32_t g = 1; g < file.group_count(); ++g)
      groups.push_back(section_contents(single_group(file.decoded(), g), &undecodable));
    report["groups"] = std::move(groups);
  }
  // Without --validate a section that does not even decode is still an
  // invalid file (LBK-E023, exit 3), not a listing that exits 0.
  const bool validating = options.validate || options.strict;
  if (!undecodable.is_ok() && !validating) report["error"] = undecodable.message();

  std::vector<SectionFinding> findings;
  if (options.validate || options.strict) {
    findings = validate_container(file.decoded());
    nlohmann::json jf = nlohmann::json::array();
    for (const SectionFinding& f : findings)
      jf.push_back({{"section", f.tag}, {"message", f.message}});
    report["validation"] = {{"ok", findings.empty()}, {"findings", jf}};
  }
  std::optional<Scene> asset;
  if (has_scene(file.decoded()) && undecodable.is_ok()) {
    Result<Scene> scene = scene_of_container(file.decoded());
    if (scene.is_ok()) {
      report["scene"] = to_json(summarize_scene(scene.value()));
      asset = std::move(scene).value();
      if (validating) {
        // Every level of an asset's PM extracts with its wedges.
        for (std::string& problem : check_scene_levels(file.decoded(), *asset)) {
          report["validation"]["findings"].push_back({{"section", kWedgTag}, {"message", problem}});
          findings.push_back({kWedgTag, std::move(problem)});
        }
        report["validation"]["ok"] = findings.empty();
      }
    } else {
      undecodable = scene.status();
      if (!validating) report["error"] = undecodable.message();
    }
  }
  FileStatus extracted;
  if (!options.extract.empty() && findings.empty() && undecodable.is_ok()) {
    // The whole asset back, unless a level or a group is asked for.
    if (asset && !options.lod && !options.group && is_scene_output(options.extract)) {
      extracted = extract_asset(tool, *asset, options.extract, &report);
    } else if (asset && options.lod && !options.group && is_scene_output(options.extract)) {
      // Every mesh at the level, with its materials and attributes.
      const LodRequest lod = *options.lod;
      Result<Scene> level = scene_at_level(file.decoded(), *asset, [&](const ProgressiveMesh& pm) {
        return lod_vertex_count(pm, lod);
      });
      extracted = level.is_ok() ? extract_asset(tool, level.value(), options.extract, &report)
                                : FileStatus{path, level.status()};
    } else {
      extracted = extract_base(tool, path, file, options, &report);
    }
    if (!extracted.status.is_ok()) report["error"] = extracted.status.message();
  }

  if (tool.json()) {
    tool.print_json(report);
  } else {
    print_listing(std::cout, path, listing);
    print_contents(std::cout, report["contents"]);
    if (report.contains("groups")) {
      for (size_t g = 1; g < report["groups"].size(); ++g) {
        std::cout << "group " << g << "\n";
        print_contents(std::cout, report["groups"][g]);
      }
    }
    if (asset) print_scene(std::cout, summarize_scene(*asset));
    if (report.contains("validation")) {
      std::cout << "validation    " << (findings.empty() ? "ok" : "FAILED") << "\n";
      for (const SectionFinding& f : findings)
        std::cout << "  - " << f.tag << ": " << f.message << "\n";
    }
    if (report.contains("extracted") && report["extracted"].contains("asset")) {
      std::cout << "extracted     " << options.extract
                << " (the asset: " << report["extracted"]["meshes"].get<uint64_t>() << " meshes, "
                << report["extracted"]["triangles"].get<uint64_t>() << " triangles, "
                << report["extracted"]["images"].get<uint64_t>() << " images)\n";
    } else if (report.contains("extracted")) {
      std::cout << "extracted     " << options.extract << " ("
                << report["extracted"]["triangles"].get<uint64_t>() << " triangles, "
                << report["extracted"]["bytes"].get<uint64_t>() << " bytes)\n";
    }
  }
  if (!findings.empty()) {
    return tool.fail(
        path,
        Status(ErrorKind::kValidation,
               "validation failed: " + findings.front().tag + ": " + findings.front().message +
                   (findings.size() > 1
                        ? " (and " + std::to_string(findings.size() - 1) + " more findings)"
                        : "")));
  }
  if (!undecodable.is_ok()) return tool.fail(path, undecodable);
  if (!extracted.status.is_ok()) return tool.fail(extracted.file, extracted.status);
  return 0;
}

int inspect_mesh(const Tool& tool, const std::string& path, Bytes bytes,
                 const InspectOptions& options) {
  if (!options.extract.empty())
    return tool.usage_error("--extract needs a .lbk container; '" + path + "' is a mesh file");
  // Assets (glTF, GLB, OBJ with its materials) are also reported as scenes.
  std::optional<SceneSummary> scene;
  std::string not_an_asset;  // why an OBJ the mesh check reads is no scene
  ImportReport probe;
  Result<MeshContent> content = prepare_mesh_content(path, bytes, &probe);
  if (content.is_ok() &&
      (content.value().format == MeshFormat::kGltf || content.value().format == MeshFormat::kGlb ||
       content.value().format == MeshFormat::kObj)) {
    ImportReport scene_report;
    Result<Scene> read = read_scene_bytes(path, bytes, SceneResources{}, &scene_report);
    const bool obj = content.value().format == MeshFormat::kObj;
    // An OBJ the mesh check can still read gets its report without a scene.
    if (!read.is_ok() && !obj) return tool.fail(path, read.status());
    if (!read.is_ok()) not_an_asset = read.status().message();
    if (read.is_ok()) {
      // A linter reports what is missing (an image, a material library) as
      // findings on its one note line, not as warnings about its own run.
      std::string findings;
      for (const std::vector<std::string>* lines : {&scene_report.warnings, &scene_report.notes})
        for (const std::string& line : *lines)
          findings += (findings.empty() ? "" : "; ") + line;
      if (!findings.empty()) tool.info(path, findings);
      scene = summarize_scene(read.value());
    }
  }
  LoadOptions load;
  load.policy.reset();  // a linter reports every problem instead of refusing
  LoadedMesh loaded;
  Status status = load_mesh_bytes(path, std::move(bytes), load, &loaded);
  if (!status.is_ok()) return tool.fail(path, status);
  // E.g. a material library outside the folder, which the other tools refuse.
  if (!not_an_asset.empty()) tool.info(path, "not read as an asset: " + not_an_asset);
  // An asset's report says what it holds; the notes of the merged mesh the
  // check runs on ("ignored 4 materials") would only contradict it.
  if (!scene) print_import_notes(tool, path, loaded.import);
  const MeshCheckReport& check = loaded.check;
  if (tool.json()) {
    nlohmann::json report = {{"schema", kMeshSchema},
                             {"file", path},
                             {"bytes", loaded.file_bytes},
                             {"sha256", loaded.sha256},
                             {"import", to_json(loaded.import)},
                             {"check", to_json(check)}};
    if (scene) report["scene"] = to_json(*scene);
    tool.print_json(report);
  } else {
    std::cout << "file          " << path << " (" << loaded.file_bytes << " bytes)\n";
    std::cout << "format        " << loaded.import.format << "\n";
    print_check(std::cout, check);
    if (scene) print_scene(std::cout, *scene);
  }
  if ((options.strict || options.validate) && check.has_problems()) {
    std::vector<std::string> problems = check.problems();
    std::string more = problems.size() == 1 ? std::string()
                                            : " (and " + std::to_string(problems.size() - 1) +
                                                  " more kinds of problems)";
    return tool.fail(path, Status(ErrorKind::kValidation, "--strict: " + problems.front() + more));
  }
  return 0;
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
  Tool tool("lodbake-inspect", "FILE [options]",
            "Looks inside a lodbake container (.lbk): header, sections with their codecs,\n"
            "sizes and checksums, and what each section holds. Given a mesh file (.obj .ply\n"
            ".off .stl .gltf .glb .drc, optionally .gz) instead, prints its mesh check report:\n"
            "counts, bounding box, components, boundary, non-manifold, degenerate, duplicate\n"
            "and unreferenced elements, orientation and non-finite coordinates.");
  InspectOptions options;
  tool.options().add_options()(
      "validate", po::bool_switch(&options.validate),
      "container: decode every section and run its deep checks (exit 7 on findings)")(
      "strict", po::bool_switch(&options.strict),
      "mesh: exit 7 when the check finds any problem (a linter for CI); container: as --validate")(
      "extract", po::value<std::string>(&options.extract)->value_name("OUT"),
      "container: write the base mesh to OUT (.obj .ply .off .glb); with STRP, the strips' "
      "triangles as an indexed mesh over BASE's vertices; a container of an asset (SCNE, "
      "lodbake-pack ASSET.gltf) gives the whole asset back as OUT.glb or OUT.gltf (with its "
      ".bin and images beside it) unless --lod or --group asks for one mesh")(
      "lod", po::value<std::string>()->value_name("N|Nt|R"),
      "with --extract on a progressive mesh: the level to write, as a vertex count (5000), "
      "a triangle count (5000t) or a ratio of the full mesh's triangles (0.25)")(
      "group", po::value<uint32_t>()->value_name("G"),
      "with --extract: the group to extract from (a container merged by lodbake-pack holds a "
      "group per base mesh); default 0, or with --lod the first group with a progressive mesh");
  tool.positional("file", -1);
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  std::string path;
  if (std::optional<int> code = tool.single_positional("file", "FILE", &path)) return *code;
  if (tool.has("extract") && options.extract.empty())
    return tool.usage_error("--extract needs a file name");
  if (tool.has("lod")) {
    if (options.extract.empty()) return tool.usage_error("--lod needs --extract OUT");
    Result<LodRequest> lod = parse_lod_request(tool.get<std::string>("lod"));
    if (!lod.is_ok()) return tool.usage_error(lod.status().message());
    options.lod = lod.value();
  }
  if (tool.has("group")) {
    if (options.extract.empty()) return tool.usage_error("--group needs --extract OUT");
    options.group = tool.get<uint32_t>("group");
  }
  if (!options.extract.empty() && same_file(path, options.extract))
    return tool.usage_error("--extract '" + options.extract + "' would overwrite the container");
  return tool.run([&] {
    Result<Bytes> bytes = read_file(path);
    if (!bytes.is_ok()) return tool.fail(path, bytes.status());
    if (is_container_input(path, &bytes.value())) {
      if (std::optional<int> code = tool.check_outputs({options.extract})) return *code;
      return inspect_container(tool, path, bytes.value(), options);
    }
    return inspect_mesh(tool, path, std::move(bytes).value(), options);
  });
}
