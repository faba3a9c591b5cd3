// STL reader, binary and ASCII, after the 3D Systems "StereoLithography
// Interface Specification" (1989) as commonly written.
// Choices where real files disagree with the specification:
// - Binary vs ASCII: a file whose size is exactly 84 + 50 * (its count field)
//   is binary even when its 80-byte header starts with "solid" (many binary
//   writers put "solid" there). Otherwise it must start with "solid" to be
//   read as ASCII; a file that does neither is refused, never guessed at.
// - ASCII keywords are matched case-insensitively and may be spread over
//   lines in any way; several solids may follow each other; every loop must
//   have exactly 3 vertices; a missing endsolid means a truncated file.
// - Facet normals are ignored with a note: they are per face, often zero or
//   stale, and the winding already gives the orientation. Binary attribute
//   bytes (used by some tools for colour) are ignored with a note when any
//   is non-zero.
// - Corners with exactly equal positions become one vertex (PositionWelder),
//   numbered by first appearance; degenerate triangles are kept for the mesh
//   check to report. Non-finite coordinates are refused.
#include <cmath>
#include <cstring>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "formats/support/byte_reader.h"
#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/position_welder.h"
#include "lib/meshio/text_mesh_reading.h"
#include "lib/meshio/text_scanner.h"

namespace lodbake {
namespace {

constexpr size_t kHeaderBytes = 84;
constexpr size_t kFacetBytes = 50;

bool iequals(std::string_view a, const char* b) {
  size_t n = std::strlen(b);
  if (a.size() != n) return false;
  for (size_t i = 0; i < n; ++i) {
    char c = a[i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != b[i]) return false;
  }
  return true;
}

// True when the first word of the file is "solid" (any case).
bool starts_with_solid(const uint8_t* data, size_t size) {
  TextScanner scanner(data, size);
  scanner.skip_whitespace();
  return iequals(scanner.token(), "solid");
}

bool finite(const Vec3f& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

void note_ignored_normals(ImportReport* report) {
  report->notes.push_back(
      "ignored stl facet normals (per face; the winding gives the orientation)");
}

void finish(PositionWelder* welder, TriangleMesh* mesh, ImportReport* report) {
  report->welded_vertices = welder->welded();
  mesh->positions = welder->take_positions();
}

Result<TriangleMesh> parse_binary(const uint8_t* data, size_t size, uint32_t count,
                                  ImportReport* report) {
  report->format = "stl-binary";
  report->file_faces = count;
  TriangleMesh mesh;
  mesh.triangles.reserve(count);
  PositionWelder welder(size_t{count} * 3);
  ByteReader reader(data, size);
  reader.seek(kHeaderBytes);
  bool normals_seen = false;
  uint64_t attribute_facets = 0;
  for (uint32_t t = 0; t < count; ++t) {
    const size_t at = reader.position();
    float f[12];
    uint16_t attribute = 0;
    for (float& value : f)
      reader.read(&value);  // the size check made every read in bounds
    reader.read(&attribute);
    if (f[0] != 0.0f || f[1] != 0.0f || f[2] != 0.0f) normals_seen = true;
    if (attribute != 0) ++attribute_facets;
    Triangle triangle;
    for (int c = 0; c < 3; ++c) {
      Vec3f p{f[3 + 3 * c], f[4 + 3 * c], f[5 + 3 * c]};
      if (!finite(p)) {
        return invalid_input("byte " + std::to_string(at) + ": facet " + std::to_string(t + 1) +
                             " of " + std::to_string(count) + " has a non-finite coordinate");
      }
      triangle[c] = welder.add(p);
    }
    mesh.triangles.push_back(triangle);
  }
  if (normals_seen) note_ignored_normals(report);
  if (attribute_facets != 0) {
    report->notes.push_back("ignored the non-zero attribute bytes (e.g. colour) of " +
                            std::to_string(attribute_facets) + " stl facets");
  }
  finish(&welder, &mesh, report);
  return mesh;
}

class AsciiStlParser {
 public:
  AsciiStlParser(const uint8_t* data, size_t size) : scanner_(data, size) {}

  Result<TriangleMesh> parse(ImportReport* report) {
    report->format = "stl-ascii";
    TriangleMesh mesh;
    PositionWelder welder;
    bool normals_seen = false;
    uint64_t solids = 0;
    for (;;) {
      scanner_.skip_whitespace();
      if (scanner_.at_end()) break;
      LODBAKE_RETURN_IF_ERROR(expect("solid"));
      scanner_.skip_line();  // the solid's name
      ++solids;
      for (;;) {
        scanner_.skip_whitespace();
        if (scanner_.at_end()) {
          return invalid_input("line " + std::to_string(scanner_.line()) +
                               ": the file ends before 'endsolid' (solid " +
                               std::to_string(solids) + ")");
        }
        std::string_view word = scanner_.token();
        if (iequals(word, "endsolid")) {
          scanner_.skip_line();
          break;
        }
        if (!iequals(word, "facet")) {
          return invalid_input("line " + std::to_string(scanner_.line()) +
                               ": expected 'facet' or 'endsolid', found " + quote_token(word));
        }
        LODBAKE_RETURN_IF_ERROR(expect("normal"));
        Vec3f normal;
        LODBAKE_RETURN_IF_ERROR(read_vec3(&normal, "a facet normal component"));
        if (normal[0] != 0.0f || normal[1] != 0.0f || normal[2] != 0.0f) normals_seen = true;
        LODBAKE_RETURN_IF_ERROR(expect("outer"));
        LODBAKE_RETURN_IF_ERROR(expect("loop"));
        Triangle triangle;
        for (int c = 0; c < 3; ++c) {
          LODBAKE_RETURN_IF_ERROR(expect("vertex"));
          Vec3f p;
          LODBAKE_RETURN_IF_ERROR(read_vec3(&p, "a vertex coordinate"));
          if (!finite(p)) {
            return invalid_input("line " + std::to_string(scanner_.line()) +
                                 ": non-finite vertex coordinate");
          }
          triangle[c] = welder.add(p);
        }
        LODBAKE_RETURN_IF_ERROR(expect("endloop"));
        LODBAKE_RETURN_IF_ERROR(expect("endfacet"));
        mesh.triangles.push_back(triangle);
      }
    }
    if (solids == 0) return invalid_input("no 'solid' in the file");
    report->file_faces = mesh.triangles.size();
    if (normals_seen) note_ignored_normals(report);
    finish(&welder, &mesh, report);
    return mesh;
  }

 private:
  Status expect(const char* keyword) {
    scanner_.skip_whitespace();
    std::string_view word = scanner_.token();
    if (iequals(word, keyword)) return Status::ok();
    return invalid_input("line " + std::to_string(scanner_.line()) + ": expected '" + keyword +
                         "', found " +
                         (word.empty() ? std::string("the end of the file") : quote_token(word)));
  }

  Status read_vec3(Vec3f* out, const char* what) {
    for (float& value : *out) {
      scanner_.skip_whitespace();
      NumberStatus status = scanner_.read_float(&value);
      if (status != NumberStatus::kOk) return invalid_input(scanner_.number_error(status, what));
    }
    return Status::ok();
  }

  TextScanner scanner_;
};

Result<TriangleMesh> parse_ascii(const uint8_t* data, size_t size, ImportReport* report) {
  std::vector<uint8_t> decoded;
  LODBAKE_RETURN_IF_ERROR(prepare_text_into_report(&data, &size, &decoded, report));
  return AsciiStlParser(data, size).parse(report);
}

Result<TriangleMesh> parse_stl_impl(const uint8_t* data, size_t size, ImportReport* report) {
  const bool solid = starts_with_solid(data, size);
  if (size < kHeaderBytes) {
    if (solid) return parse_ascii(data, size, report);
    if (size == 0) return invalid_input("empty file: neither binary nor ascii stl");
    return invalid_input("the file has " + std::to_string(size) +
                         " bytes, fewer than a binary stl header (84), and does not start with "
                         "'solid' as ascii stl does");
  }
  uint32_t count = 0;
  std::memcpy(&count, data + 80, sizeof(count));  // little-endian host (byte_reader.h)
  const uint64_t expected = kHeaderBytes + uint64_t{kFacetBytes} * count;
  const std::string binary_mismatch =
      "binary stl header says " + std::to_string(count) + " triangles (" +
      std::to_string(expected) + " bytes), but the file has " + std::to_string(size) + " bytes";
  if (expected == size) return parse_binary(data, size, count, report);
  if (!solid) return invalid_input(binary_mismatch + " and does not start with 'solid'");
  Result<TriangleMesh> ascii = parse_ascii(data, size, report);
  if (ascii.is_ok()) return ascii;
  return invalid_input("not ascii stl (" + ascii.status().message() + ") and not binary stl (" +
                       binary_mismatch + ")");
}

}  // namespace

Result<TriangleMesh> parse_stl(const uint8_t* data, size_t size, ImportReport* report) {
  ImportReport local;
  ImportReport* out = report != nullptr ? report : &local;
  try {
    return parse_stl_impl(data, size, out);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reading the stl file");
  }
}

}  // namespace lodbake
