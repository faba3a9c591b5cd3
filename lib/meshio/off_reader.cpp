// Object File Format (OFF) reader, after the Geomview OFF specification
// ("[ST][C][N][4][n]OFF", then the counts, the vertices and the faces).
//
// Choices where the spec or practice is vague:
// - Comments ('#' to the end of the line) may appear anywhere, also before
//   the keyword (CGAL writes them there). The counts may follow the keyword
//   on its own line. The edge count is ignored and may be left out when the
//   face count ends its line (as in assimp's test files).
// - Vertex records are read as a stream of numbers (they may wrap or share
//   lines), except with the C prefix: the colour is the rest of the line
//   (3 or 4 numbers, ints or floats; skipped and noted), with ST the last two
//   of them are the texture coordinates. N gives per-vertex normals, ST
//   per-vertex texture coordinates. 4OFF divides by w; nOFF is read only for
//   a space dimension of 3.
// - A face is its corner count and indices (which may wrap lines); the rest
//   of its line is the colour (0 to 4 numbers, skipped and noted). Faces need
//   3 or more corners; polygons are split by PolygonTriangulator.
// - Both counts are checked against the bytes left after the header before
//   anything is allocated (every vertex needs two bytes per number, every
//   face at least eight), so a huge count fails at once with a message.
// - Non-finite numbers (nan, inf) are errors, as in the OBJ reader.
// - A header declaring no faces is an error: lodbake needs a surface.
// - Text after the last face is ignored with a note; binary OFF
//   ("OFF BINARY") is reported as unsupported.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/polygon_triangulation.h"
#include "lib/meshio/text_mesh_reading.h"
#include "lib/meshio/text_scanner.h"

namespace lodbake {
namespace {

struct OffHeader {
  bool texcoords = false;        // ST
  bool colours = false;          // C
  bool normals = false;          // N
  bool homogeneous = false;      // 4
  bool dimension_given = false;  // n
};

// Parses "[ST][C][N][4][n]OFF"; false when `k` is not such a keyword.
bool parse_keyword(std::string_view k, OffHeader* h) {
  auto take = [&k](std::string_view prefix) {
    if (k.substr(0, prefix.size()) != prefix) return false;
    k.remove_prefix(prefix.size());
    return true;
  };
  h->texcoords = take("ST");
  h->colours = take("C");
  h->normals = take("N");
  h->homogeneous = take("4");
  h->dimension_given = take("n");
  return k == "OFF";
}

class OffReader {
 public:
  OffReader(const uint8_t* data, size_t size, ImportReport* report)
      : size_(size), scanner_(data, size), report_(report) {}

  Result<TriangleMesh> read();

 private:
  // The next token, skipping whitespace and comments across lines.
  std::string_view next_token() {
    scanner_.skip_whitespace_and_comments('#');
    return scanner_.token_until('#');
  }
  std::string prefix() const { return "line " + std::to_string(scanner_.line()) + ": "; }
  Status read_count(const char* what, uint64_t* out);
  Status read_header();
  Status read_number(std::string_view t, const char* what, float* out) const;
  Status read_vertex(float* values, size_t count, const char* what);
  Status read_vertices();
  Status read_faces();

  size_t size_;
  TextScanner scanner_;
  ImportReport* report_;
  OffHeader header_;
  uint32_t dimension_ = 3;
  uint64_t vertex_count_ = 0;
  uint64_t face_count_ = 0;
  TriangleMesh mesh_;
  PolygonTriangulator triangulator_;
  std::vector<uint32_t> face_;
  uint64_t coloured_vertices_ = 0;
  uint64_t coloured_faces_ = 0;
};

Status OffReader::read_count(const char* what, uint64_t* out) {
  std::string_view t = next_token();
  if (t.empty())
    return invalid_input(prefix() + "expected the " + what + " count, found the end of the file");
  int64_t value = 0;
  NumberStatus status = parse_int64(t, &value);
  if (status == NumberStatus::kOk && value < 0)
    return invalid_input(prefix() + "negative " + what + " count " + std::to_string(value));
  if (status == NumberStatus::kOutOfRange)
    return invalid_input(prefix() + what + " count " + quote_token(t) + " is out of range");
  if (status != NumberStatus::kOk)
    return invalid_input(prefix() + "expected the " + what + " count, found " + quote_token(t));
  *out = static_cast<uint64_t>(value);
  return Status::ok();
}

Status OffReader::read_header() {
  std::string_view keyword = next_token();
  if (keyword.empty()) return invalid_input("no OFF keyword: the file holds only comments");
  if (!parse_keyword(keyword, &header_)) {
    return invalid_input(prefix() +
                         "expected an OFF keyword (OFF, COFF, NOFF, STOFF, ...), found " +
                         quote_token(keyword));
  }
  {
    // "OFF BINARY" must be on the keyword's line; anything else there is the
    // first count, so look ahead on a copy of the scanner.
    TextScanner ahead = scanner_;
    if (ahead.token_until('#') == "BINARY")
      return unsupported("binary OFF ('" + std::string(keyword) + " BINARY') is not supported");
  }
  if (header_.dimension_given) {
    uint64_t dimension = 0;
    LODBAKE_RETURN_IF_ERROR(read_count("dimension", &dimension));
    if (dimension != 3) {
      return unsupported(prefix() + "vertices of dimension " + std::to_string(dimension) +
                         " are not supported (only 3)");
    }
  }
  dimension_ = header_.homogeneous ? 4 : 3;
  LODBAKE_RETURN_IF_ERROR(read_count("vertex", &vertex_count_));
  LODBAKE_RETURN_IF_ERROR(read_count("face", &face_count_));
  // The edge count is optional: absent when the face count ends its line.
  scanner_.skip_blanks();
  if (!scanner_.at_line_end() && scanner_.peek() != '#') {
    uint64_t edges = 0;
    LODBAKE_RETURN_IF_ERROR(read_count("edge", &edges));
  }

  // Bound both counts by the bytes left before allocating anything.
  const uint64_t numbers_per_vertex = dimension_ + (header_.normals ? 3 : 0) +
                                      (header_.texcoords ? 2 : 0) + (header_.colours ? 3 : 0);
  const uint64_t room = static_cast<uint64_t>(scanner_.remaining()) + 1;
  const uint64_t vertex_room = room / (2 * numbers_per_vertex);
  if (vertex_count_ > vertex_room) {
    return invalid_input("header declares " + std::to_string(vertex_count_) +
                         " vertices but the file has room for at most " +
                         std::to_string(vertex_room));
  }
  const uint64_t face_room = (room - vertex_count_ * 2 * numbers_per_vertex) / 8;
  if (face_count_ > face_room) {
    return invalid_input("header declares " + std::to_string(face_count_) +
                         " faces but the file has room for at most " + std::to_string(face_room) +
                         " after the vertices");
  }
  if (vertex_count_ >= std::numeric_limits<uint32_t>::max())
    return invalid_input("header declares more than 4294967294 vertices");
  if (face_count_ == 0) return invalid_input("header declares no faces");
  return Status::ok();
}

Status OffReader::read_number(std::string_view t, const char* what, float* out) const {
  NumberStatus status = t.empty() ? NumberStatus::kMissing : parse_float(t, out);
  if (status != NumberStatus::kOk) return invalid_input(scanner_.number_error(status, what));
  if (!std::isfinite(*out))
    return invalid_input(prefix() + what + " " + quote_token(t) + " is not finite");
  return Status::ok();
}

Status OffReader::read_vertex(float* values, size_t count, const char* what) {
  for (size_t i = 0; i < count; ++i) {
    std::string_view t = next_token();
    if (t.empty()) {
      return invalid_input(prefix() + "expected " + what + ", found the end of the file (" +
                           std::to_string(mesh_.positions.size()) + " of " +
                           std::to_string(vertex_count_) + " vertices read)");
    }
    LODBAKE_RETURN_IF_ERROR(read_number(t, what, &values[i]));
  }
  return Status::ok();
}

Status OffReader::read_vertices() {
  mesh_.positions.reserve(vertex_count_);
  if (header_.normals) {
    mesh_.normals.binding = AttributeBinding::kPerVertex;
    mesh_.normals.components = 3;
    mesh_.normals.values.reserve(vertex_count_ * 3);
  }
  if (header_.texcoords) {
    mesh_.texcoords.binding = AttributeBinding::kPerVertex;
    mesh_.texcoords.components = 2;
    mesh_.texcoords.values.reserve(vertex_count_ * 2);
  }
  for (uint64_t i = 0; i < vertex_count_; ++i) {
    float p[4];
    LODBAKE_RETURN_IF_ERROR(read_vertex(p, dimension_, "a vertex coordinate"));
    if (header_.homogeneous) {
      if (p[3] == 0) return invalid_input(prefix() + "homogeneous vertex with w = 0");
      for (int k = 0; k < 3; ++k) {
        p[k] /= p[3];
        if (!std::isfinite(p[k]))
          return invalid_input(prefix() + "vertex coordinate overflows when divided by w");
      }
    }
    mesh_.positions.push_back({p[0], p[1], p[2]});
    if (header_.normals) {
      float n[3];
      LODBAKE_RETURN_IF_ERROR(read_vertex(n, 3, "a normal coordinate"));
      mesh_.normals.values.insert(mesh_.normals.values.end(), n, n + 3);
    }
    if (header_.colours) {
      // The colour (and then the texture coordinates) fill the rest of the line.
      std::string_view rest[7];
      size_t count = 0;
      for (std::string_view t = scanner_.token_until('#'); !t.empty();
           t = scanner_.token_until('#')) {
        if (count == 7) return invalid_input(prefix() + "too many values on a vertex line");
        rest[count++] = t;
      }
      const size_t st = header_.texcoords ? 2 : 0;
      if (count < st + 3 || count > st + 4) {
        return invalid_input(prefix() + "expected 3 or 4 colour values" +
                             (st != 0 ? " and 2 texture coordinates" : "") +
                             " after the vertex, found " + std::to_string(count) + " values");
      }
      for (size_t k = 0; k < count - st; ++k) {
        float c = 0;
        LODBAKE_RETURN_IF_ERROR(read_number(rest[k], "a colour value", &c));
      }
      ++coloured_vertices_;
      for (size_t k = count - st; k < count; ++k) {
        float t = 0;
        LODBAKE_RETURN_IF_ERROR(read_number(rest[k], "a texture coordinate", &t));
        mesh_.texcoords.values.push_back(t);
      }
    } else if (header_.texcoords) {
      float t[2];
      LODBAKE_RETURN_IF_ERROR(read_vertex(t, 2, "a texture coordinate"));
      mesh_.texcoords.values.insert(mesh_.texcoords.values.end(), t, t + 2);
    }
  }
  return Status::ok();
}

Status OffReader::read_faces() {
  mesh_.triangles.reserve(face_count_);
  for (uint64_t f = 0; f < face_count_; ++f) {
    std::string_view t = next_token();
    if (t.empty()) {
      return invalid_input(prefix() + "expected a face, found the end of the file (" +
                           std::to_string(f) + " of " + std::to_string(face_count_) +
                           " faces read)");
    }
    int64_t corners = 0;
    NumberStatus status = parse_int64(t, &corners);
    if (status != NumberStatus::kOk)
      return invalid_input(prefix() + "expected a face's corner count, found " + quote_token(t));
    if (corners < 3) {
      return invalid_input(prefix() + "face has " + std::to_string(corners) +
                           (corners == 1 ? " corner" : " corners") + ", at least 3 needed");
    }
    // Each corner needs at least two bytes ("0 "); bounds the scratch below.
    if (static_cast<uint64_t>(corners) > scanner_.remaining() / 2 + 1) {
      return invalid_input(prefix() + "face declares " + std::to_string(corners) +
                           " corners but only " + std::to_string(scanner_.remaining()) +
                           " bytes remain");
    }
    face_.clear();
    for (int64_t c = 0; c < corners; ++c) {
      std::string_view it = next_token();
      int64_t index = 0;
      status = it.empty() ? NumberStatus::kMissing : parse_int64(it, &index);
      if (status == NumberStatus::kMissing) {
        return invalid_input(prefix() + "face ends after " + std::to_string(c) + " of its " +
                             std::to_string(corners) + " corners");
      }
      if (status != NumberStatus::kOk)
        return invalid_input(prefix() + "expected a face index, found " + quote_token(it));
      if (index < 0 || static_cast<uint64_t>(index) >= vertex_count_) {
        return invalid_input(prefix() + "face index " + std::to_string(index) + " out of range (" +
                             std::to_string(vertex_count_) + " vertices)");
      }
      face_.push_back(static_cast<uint32_t>(index));
    }
    // The face's colour: the rest of its line.
    size_t colour_values = 0;
    for (std::string_view c = scanner_.token_until('#'); !c.empty();
         c = scanner_.token_until('#')) {
      float value = 0;
      if (++colour_values > 4) {
        return invalid_input(prefix() + "more than 4 colour values after the face's " +
                             std::to_string(corners) + " indices");
      }
      LODBAKE_RETURN_IF_ERROR(read_number(c, "a face colour value", &value));
    }
    if (colour_values != 0) ++coloured_faces_;
    if (face_.size() == 3) {
      mesh_.triangles.push_back({face_[0], face_[1], face_[2]});
    } else {
      LODBAKE_RETURN_IF_ERROR(triangulator_.triangulate(face_.data(), face_.size(), mesh_.positions,
                                                        &mesh_.triangles, nullptr));
    }
  }
  return Status::ok();
}

Result<TriangleMesh> OffReader::read() {
  report_->format = "off";
  if (size_ == 0) return invalid_input("empty file");
  LODBAKE_RETURN_IF_ERROR(read_header());
  LODBAKE_RETURN_IF_ERROR(read_vertices());
  LODBAKE_RETURN_IF_ERROR(read_faces());
  scanner_.skip_whitespace_and_comments('#');
  if (!scanner_.at_end()) {
    report_->notes.push_back("ignored " + std::to_string(scanner_.remaining()) +
                             " bytes after the last face (from line " +
                             std::to_string(scanner_.line()) + ")");
  }
  report_->file_faces = face_count_;
  triangulator_.add_to_report(report_);
  if (coloured_vertices_ != 0) {
    report_->notes.push_back("ignored the colours of " + std::to_string(coloured_vertices_) +
                             " vertices");
  }
  if (coloured_faces_ != 0) {
    report_->notes.push_back("ignored the colours of " + std::to_string(coloured_faces_) +
                             " faces");
  }
  return std::move(mesh_);
}

}  // namespace

Result<TriangleMesh> parse_off(const uint8_t* data, size_t size, ImportReport* report) {
  return read_text_mesh<OffReader>(data, size, report, "OFF");
}

}  // namespace lodbake
