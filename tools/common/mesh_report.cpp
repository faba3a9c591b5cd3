#include "tools/common/mesh_report.h"

#include "formats/container/container_layout.h"
#include "formats/support/quantization.h"
#include "lib/meshio/file_name.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace lodbake::cli {

std::string format_float(float value) {
  char buffer[32];
  auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

nlohmann::json to_json(const Vec3f& v) {
  return nlohmann::json::array({v[0], v[1], v[2]});
}

nlohmann::json to_json(const MeshCheckReport& r) {
  nlohmann::json j;
  j["vertices"] = r.vertices;
  j["triangles"] = r.triangles;
  j["bbox"] = {{"min", to_json(r.bbox_min)}, {"max", to_json(r.bbox_max)}};
  j["components"] = r.components;
  j["edges"] = r.edges;
  j["boundary_edges"] = r.boundary_edges;
  j["boundary_loops"] = r.boundary_loops;
  j["closed"] = r.closed();
  j["manifold"] = r.manifold();
  j["non_manifold_edges"] = r.non_manifold_edges;
  j["non_manifold_vertices"] = r.non_manifold_vertices;
  j["degenerate_triangles"] = r.degenerate_triangles;
  j["repeated_index_triangles"] = r.repeated_index_triangles;
  j["zero_area_triangles"] = r.zero_area_triangles;
  j["duplicate_triangles"] = r.duplicate_triangles;
  j["unreferenced_vertices"] = r.unreferenced_vertices;
  j["inconsistent_orientation_edges"] = r.inconsistent_orientation_edges;
  j["non_finite_coordinates"] = r.non_finite_coordinates;
  j["out_of_range_triangles"] = r.out_of_range_triangles;
  j["genus"] = r.genus >= 0 ? nlohmann::json(r.genus) : nlohmann::json(nullptr);
  j["problems"] = r.problems();
  return j;
}

nlohmann::json to_json(const ImportReport& r) {
  return {{"format", r.format},
          {"file_faces", r.file_faces},
          {"polygons_triangulated", r.polygons_triangulated},
          {"welded_vertices", r.welded_vertices},
          {"notes", r.notes}};
}

nlohmann::json to_json(const RepairReport& r) {
  return {{"removed_non_finite_triangles", r.removed_non_finite_triangles},
          {"removed_degenerate_triangles", r.removed_degenerate_triangles},
          {"removed_duplicate_triangles", r.removed_duplicate_triangles},
          {"removed_unreferenced_vertices", r.removed_unreferenced_vertices},
          {"split_non_manifold_edges", r.split_non_manifold_edges},
          {"split_non_manifold_vertices", r.split_non_manifold_vertices},
          {"added_vertices", r.added_vertices},
          {"flipped_triangles", r.flipped_triangles},
          {"actions", r.actions()}};
}

nlohmann::json repairs_json(const LoadOptions& options, const LoadedMesh& loaded) {
  nlohmann::json j = to_json(loaded.repair ? *loaded.repair : RepairReport());
  j["mode"] = options.repair ? "repair" : options.strict ? "strict" : "default";
  j["changed"] = loaded.repair.has_value() && loaded.repair->changed();
  return j;
}

namespace {

void line(std::ostream& out, const char* label, const std::string& value) {
  out << std::left << std::setw(14) << label << value << "\n";
}

std::string vec(const Vec3f& v) {
  return "(" + format_float(v[0]) + ", " + format_float(v[1]) + ", " + format_float(v[2]) + ")";
}

}  // namespace

void print_check(std::ostream& out, const MeshCheckReport& r) {
  line(out, "vertices", std::to_string(r.vertices));
  line(out, "triangles", std::to_string(r.triangles));
  line(out, "bounding box", vec(r.bbox_min) + " .. " + vec(r.bbox_max));
  line(out, "components", std::to_string(r.components));
  line(out, "edges", std::to_string(r.edges));
  line(out, "boundary",
       r.closed() ? std::string("none (closed)")
                  : std::to_string(r.boundary_edges) + " edges in " +
                        std::to_string(r.boundary_loops) + " loops");
  line(out, "manifold",
       r.manifold() ? std::string("yes")
                    : "no (" + std::to_string(r.non_manifold_edges) + " edges, " +
                          std::to_string(r.non_manifold_vertices) + " vertices)");
  if (r.genus >= 0) line(out, "genus", std::to_string(r.genus));
  std::vector<std::string> problems = r.problems();
  line(out, "problems", problems.empty() ? std::string("none") : std::to_string(problems.size()));
  for (const std::string& p : problems)
    out << "  - " << p << "\n";
}

namespace {

std::string joined(const std::vector<std::string>& items, const char* separator) {
  std::string text;
  for (const std::string& item : items)
    text += (text.empty() ? "" : separator) + item;
  return text;
}

}  // namespace

void print_import_notes(const Tool& tool, const std::string& file, const ImportReport& report) {
  if (!report.notes.empty()) tool.info(file, joined(report.notes, "; "));
}

std::string repair_note(const RepairReport& report, bool by_default) {
  std::vector<std::string> actions = report.actions();
  if (by_default)
    return "repaired (positions unchanged; --strict refuses instead): " + joined(actions, ", ");
  return "repair: " + (actions.empty() ? std::string("nothing to repair") : joined(actions, ", "));
}

int load_input(const Tool& tool, const std::string& path, const LoadOptions& options,
               LoadedMesh* loaded) {
  if (options.repair && options.strict)
    return tool.usage_error("--strict refuses what --repair would fix: give one of them");
  Status status = load_mesh(path, options, loaded);
  // A failure is its one error line; the notes of a run that stops there
  // would only add lines about a mesh nothing is made from.
  if (!status.is_ok()) return tool.fail(path, status);
  // Everything the tool changed or left out on the way in, as one line.
  std::vector<std::string> notes = loaded->import.notes;
  if (loaded->seam_vertices != 0)
    notes.push_back("split vertices on attribute seams, adding " +
                    std::to_string(loaded->seam_vertices) +
                    " (a progressive mesh records per-vertex attributes only)");
  if (loaded->repair) notes.push_back(repair_note(*loaded->repair, loaded->repaired_by_default));
  if (loaded->dropped_unreferenced != 0)
    notes.push_back("dropped " + std::to_string(loaded->dropped_unreferenced) +
                    " unreferenced vertices (no triangle uses them)");
  if (!notes.empty()) tool.info(path, joined(notes, "; "));
  for (const std::string& warning : loaded->import.warnings)
    tool.warn(path, warning);
  const MeshCheckReport& check =
      loaded->check_after_repair ? *loaded->check_after_repair : loaded->check;
  for (MeshProblem problem : kAllMeshProblems) {
    if (problem == MeshProblem::kUnreferencedVertices && options.drop_unreferenced) continue;
    if (check.count(problem) == 0) continue;
    tool.warn(path, "kept as it is: " + check.describe(problem) + " (use --repair to fix)");
  }
  return 0;
}

std::optional<int> check_quantize_bits(const Tool& tool, int bits) {
  if (!tool.has("quantize") || (bits >= kMinQuantizationBits && bits <= kMaxQuantizationBits))
    return std::nullopt;
  return tool.usage_error("--quantize takes " + std::to_string(kMinQuantizationBits) + " to " +
                          std::to_string(kMaxQuantizationBits) + " bits, not " +
                          std::to_string(bits));
}

bool is_container_input(const std::string& path, const Bytes* bytes) {
  if (lower_extension(path) == "lbk") return true;
  if (bytes != nullptr) return starts_with_container_magic(bytes->data(), bytes->size());
  // Only the magic of a regular file is read (opening a FIFO would wait for
  // a writer): anything else, or an unreadable file, is not one, and the
  // mesh path then reports why it cannot be read.
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  std::ifstream in(path, std::ios::binary);
  uint8_t head[sizeof(kContainerMagic)] = {};
  return in.read(reinterpret_cast<char*>(head), sizeof(head)) &&
         starts_with_container_magic(head, sizeof(head));
}

}  // namespace lodbake::cli
