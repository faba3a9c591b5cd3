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
// - Text after the last face is ignored with a note.
//
// Binary OFF ("[ST][C][N][4][n]OFF BINARY" alone on the first line, comments
// allowed before it) is read by BinaryOffReader below with the same keyword
// parser, count bounds and polygon triangulation. After the header line come
// 32-bit integers and float32 values: [dimension (nOFF)], vertex, face and
// edge counts, per vertex the coordinates [normal] [4 colour values] [2
// texture coordinates], per face its corner count and indices. Two layouts
// are in use and the file does not say which it is:
// - Geomview's original: big-endian, and every face ends with a colour
//   count (0 to 4) and that many float32 values;
// - pmp-library's writer: the machine's byte order, in
//   practice little-endian, and no colour count after the faces.
// The two differ in both respects, so the file decides: both layouts are
// walked over the whole file without allocating (counts bounded by the bytes
// left, corner counts, indices in range, colour counts 0 to 4). The wrong
// byte order almost always gives counts far beyond the file size (8 vertices
// read the other way round are 134,217,728), and where the counts happen to
// fit both ways the wrong face layout loses step within a face or two. The
// reader takes the layout whose walk ends exactly at the end of the file
// (Geomview's first, should both), else one whose walk succeeds (the bytes
// after the last face are noted), else it reports the error of the walk that
// got furthest (on a tie, the one whose counts ask for fewer bytes). Mixes of
// the two (little-endian with colour counts) are not read.
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
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

// Where the binary part of a binary OFF starts, or nullopt when the file is
// not one (then it is read as text, which reports any header problem).
struct BinaryOffStart {
  OffHeader header;
  std::string keyword;
  size_t body = 0;         // offset of the first binary byte
  bool line_ended = true;  // only blanks follow BINARY on its line
};

std::optional<BinaryOffStart> find_binary_off(const uint8_t* data, size_t size) {
  TextScanner scanner(data, size);
  scanner.skip_whitespace_and_comments('#');
  BinaryOffStart start;
  start.keyword = std::string(scanner.token_until('#'));
  if (!parse_keyword(start.keyword, &start.header)) return std::nullopt;
  if (scanner.token_until('#') != "BINARY") return std::nullopt;
  // The header line ends right after BINARY (blanks allowed) with "\n" or
  // "\r\n"; the next byte is binary, whatever its value.
  scanner.skip_blanks();
  const size_t end = scanner.offset();
  if (end + 1 < size && data[end] == '\r' && data[end + 1] == '\n') {
    start.body = end + 2;
  } else if (end < size && data[end] == '\n') {
    start.body = end + 1;
  } else {
    start.body = end;
    start.line_ended = end == size;
  }
  return start;
}

// One way to read the binary part: byte order and whether faces end with a
// colour count.
struct BinaryOffLayout {
  bool big_endian;
  bool face_colours;
  const char* name;
};

constexpr std::array<BinaryOffLayout, 2> kBinaryOffLayouts = {{
    {true, true, "big-endian, faces with colour counts (Geomview)"},
    {false, false, "little-endian, faces without colour counts (pmp-library)"},
}};

class BinaryOffReader {
 public:
  BinaryOffReader(const uint8_t* data, size_t size, const BinaryOffStart& start,
                  ImportReport* report)
      : data_(data), size_(size), start_(start), report_(report) {}

  Result<TriangleMesh> read();

 private:
  // What walking the file with one layout found.
  struct Walk {
    Status status = Status::ok();
    size_t reached = 0;     // offset of the failure, or of the end of the last face
    uint64_t declared = 0;  // bytes the counts ask for at least (saturating)
    uint64_t vertex_count = 0;
    uint64_t face_count = 0;
    uint64_t coloured_faces = 0;
  };

  std::string at(size_t offset) const { return "byte " + std::to_string(offset) + ": "; }
  uint32_t floats_per_vertex() const {
    const OffHeader& h = start_.header;
    return (h.homogeneous ? 4 : 3) + (h.normals ? 3 : 0) + (h.colours ? 4 : 0) +
           (h.texcoords ? 2 : 0);
  }
  // The 32-bit word at `offset` in `layout`'s byte order. \pre offset + 4 <= size_.
  uint32_t word(const BinaryOffLayout& layout, size_t offset) const {
    const uint8_t* p = data_ + offset;
    return layout.big_endian
               ? uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | uint32_t{p[3]}
               : uint32_t{p[3]} << 24 | uint32_t{p[2]} << 16 | uint32_t{p[1]} << 8 | uint32_t{p[0]};
  }
  float real(const BinaryOffLayout& layout, size_t offset) const {
    const uint32_t bits = word(layout, offset);
    float value = 0;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  // Reads a non-negative int32 at *offset into *out and moves past it.
  Status read_count(const BinaryOffLayout& layout, const char* what, size_t* offset,
                    uint64_t* out) const;
  // Checks the whole file in `layout` without allocating.
  Walk walk(const BinaryOffLayout& layout) const;
  // Reads the mesh in `layout`, whose walk succeeded.
  Result<TriangleMesh> read_mesh(const BinaryOffLayout& layout, const Walk& walked);

  const uint8_t* data_;
  size_t size_;
  BinaryOffStart start_;
  ImportReport* report_;
  PolygonTriangulator triangulator_;
};

Status BinaryOffReader::read_count(const BinaryOffLayout& layout, const char* what, size_t* offset,
                                   uint64_t* out) const {
  if (size_ - *offset < 4) {
    return invalid_input(at(*offset) + "expected the " + what +
                         " count, found the end of the file");
  }
  const int32_t value = static_cast<int32_t>(word(layout, *offset));
  if (value < 0) {
    return invalid_input(at(*offset) + "negative " + what + " count " + std::to_string(value));
  }
  *out = static_cast<uint64_t>(value);
  *offset += 4;
  return Status::ok();
}

BinaryOffReader::Walk BinaryOffReader::walk(const BinaryOffLayout& layout) const {
  Walk w;
  size_t pos = start_.body;
  auto fail = [&w, &pos](Status status) {
    w.status = std::move(status);
    w.reached = pos;
    return w;
  };
  if (start_.header.dimension_given) {
    uint64_t dimension = 0;
    Status read = read_count(layout, "dimension", &pos, &dimension);
    if (!read.is_ok()) return fail(read);
    if (dimension != 3) {
      return fail(unsupported(at(pos - 4) + "vertices of dimension " + std::to_string(dimension) +
                              " are not supported (only 3)"));
    }
  }
  uint64_t edges = 0;  // read and ignored, as in the text form
  const std::pair<const char*, uint64_t*> counts[] = {
      {"vertex", &w.vertex_count}, {"face", &w.face_count}, {"edge", &edges}};
  for (const auto& [what, out] : counts) {
    Status read = read_count(layout, what, &pos, out);
    if (!read.is_ok()) return fail(read);
  }
  // Counts are below 2^31, so these products cannot overflow.
  const uint64_t vertex_bytes = w.vertex_count * floats_per_vertex() * 4;
  const uint64_t min_face_bytes = 4 * (1 + 3 + (layout.face_colours ? 1 : 0));
  w.declared = vertex_bytes + w.face_count * min_face_bytes;
  const uint64_t left = size_ - pos;
  if (w.declared > left) {
    return fail(invalid_input("header declares " + std::to_string(w.vertex_count) +
                              " vertices and " + std::to_string(w.face_count) +
                              " faces, which need at least " + std::to_string(w.declared) +
                              " bytes, but " + std::to_string(left) +
                              " bytes follow the counts (read " + layout.name + ")"));
  }
  if (w.face_count == 0) return fail(invalid_input("header declares no faces"));
  pos += vertex_bytes;
  for (uint64_t f = 0; f < w.face_count; ++f) {
    const size_t face_start = pos;
    uint64_t corners = 0;
    Status read = read_count(layout, "corner", &pos, &corners);
    if (!read.is_ok()) return fail(read);
    if (corners < 3) {
      pos = face_start;
      return fail(invalid_input(at(pos) + "face " + std::to_string(f) + " has " +
                                std::to_string(corners) + (corners == 1 ? " corner" : " corners") +
                                ", at least 3 needed"));
    }
    if (corners > (size_ - pos) / 4) {
      pos = face_start;
      return fail(invalid_input(at(pos) + "face " + std::to_string(f) + " declares " +
                                std::to_string(corners) + " corners but only " +
                                std::to_string(size_ - face_start - 4) + " bytes remain"));
    }
    for (uint64_t c = 0; c < corners; ++c, pos += 4) {
      const int32_t index = static_cast<int32_t>(word(layout, pos));
      if (index < 0 || static_cast<uint64_t>(index) >= w.vertex_count) {
        return fail(invalid_input(at(pos) + "face " + std::to_string(f) + ": index " +
                                  std::to_string(index) + " out of range (" +
                                  std::to_string(w.vertex_count) + " vertices)"));
      }
    }
    if (layout.face_colours) {
      uint64_t colours = 0;
      read = read_count(layout, "colour", &pos, &colours);
      if (!read.is_ok()) return fail(read);
      if (colours > 4 || colours > (size_ - pos) / 4) {
        pos -= 4;
        return fail(invalid_input(at(pos) + "face " + std::to_string(f) + ": colour count " +
                                  std::to_string(colours) +
                                  (colours > 4 ? " (at most 4)" : " overruns the file")));
      }
      pos += colours * 4;
      if (colours != 0) ++w.coloured_faces;
    }
  }
  w.reached = pos;
  return w;
}

Result<TriangleMesh> BinaryOffReader::read_mesh(const BinaryOffLayout& layout, const Walk& walked) {
  const OffHeader& h = start_.header;
  TriangleMesh mesh;
  size_t pos = start_.body + (h.dimension_given ? 16 : 12);
  mesh.positions.reserve(walked.vertex_count);
  if (h.normals) {
    mesh.normals.binding = AttributeBinding::kPerVertex;
    mesh.normals.components = 3;
    mesh.normals.values.reserve(walked.vertex_count * 3);
  }
  if (h.texcoords) {
    mesh.texcoords.binding = AttributeBinding::kPerVertex;
    mesh.texcoords.components = 2;
    mesh.texcoords.values.reserve(walked.vertex_count * 2);
  }
  const uint32_t per_vertex = floats_per_vertex();
  float v[16];
  for (uint64_t i = 0; i < walked.vertex_count; ++i) {
    const size_t vertex_start = pos;
    for (uint32_t k = 0; k < per_vertex; ++k, pos += 4) {
      v[k] = real(layout, pos);
      if (!std::isfinite(v[k])) {
        return invalid_input(at(pos) + "vertex " + std::to_string(i) + ": a value is not finite");
      }
    }
    float* p = v;
    if (h.homogeneous) {
      if (p[3] == 0) return invalid_input(at(vertex_start) + "homogeneous vertex with w = 0");
      for (int k = 0; k < 3; ++k) {
        p[k] /= p[3];
        if (!std::isfinite(p[k])) {
          return invalid_input(at(vertex_start) + "vertex coordinate overflows when divided by w");
        }
      }
    }
    mesh.positions.push_back({p[0], p[1], p[2]});
    float* rest = v + (h.homogeneous ? 4 : 3);
    if (h.normals) {
      mesh.normals.values.insert(mesh.normals.values.end(), rest, rest + 3);
      rest += 3;
    }
    if (h.colours) rest += 4;
    if (h.texcoords) mesh.texcoords.values.insert(mesh.texcoords.values.end(), rest, rest + 2);
  }
  mesh.triangles.reserve(walked.face_count);
  std::vector<uint32_t> face;
  for (uint64_t f = 0; f < walked.face_count; ++f) {
    const uint32_t corners = word(layout, pos);
    pos += 4;
    face.resize(corners);  // bounded by the walk: corners * 4 bytes follow
    for (uint32_t c = 0; c < corners; ++c, pos += 4)
      face[c] = word(layout, pos);
    if (layout.face_colours) pos += 4 + size_t{word(layout, pos)} * 4;
    if (corners == 3) {
      mesh.triangles.push_back({face[0], face[1], face[2]});
    } else {
      LODBAKE_RETURN_IF_ERROR(triangulator_.triangulate(face.data(), face.size(), mesh.positions,
                                                        &mesh.triangles, nullptr));
    }
  }
  report_->file_faces = walked.face_count;
  triangulator_.add_to_report(report_);
  report_->notes.push_back("binary OFF read " + std::string(layout.name));
  if (h.colours) {
    report_->notes.push_back("ignored the colours of " + std::to_string(walked.vertex_count) +
                             " vertices");
  }
  if (walked.coloured_faces != 0) {
    report_->notes.push_back("ignored the colours of " + std::to_string(walked.coloured_faces) +
                             " faces");
  }
  if (walked.reached != size_) {
    report_->notes.push_back("ignored " + std::to_string(size_ - walked.reached) +
                             " bytes after the last face (from byte " +
                             std::to_string(walked.reached) + ")");
  }
  return mesh;
}

Result<TriangleMesh> BinaryOffReader::read() {
  report_->format = "off-binary";
  if (!start_.line_ended) {
    return invalid_input(at(start_.body) + "expected the end of the line after '" + start_.keyword +
                         " BINARY'");
  }
  std::array<Walk, kBinaryOffLayouts.size()> walks;
  for (size_t i = 0; i < walks.size(); ++i)
    walks[i] = walk(kBinaryOffLayouts[i]);
  std::optional<size_t> chosen;
  for (size_t i = 0; i < walks.size() && !chosen; ++i) {
    if (walks[i].status.is_ok() && walks[i].reached == size_) chosen = i;
  }
  for (size_t i = 0; i < walks.size() && !chosen; ++i) {
    if (walks[i].status.is_ok()) chosen = i;
  }
  if (chosen) return read_mesh(kBinaryOffLayouts[*chosen], walks[*chosen]);
  size_t best = 0;
  for (size_t i = 1; i < walks.size(); ++i) {
    if (walks[i].reached > walks[best].reached ||
        (walks[i].reached == walks[best].reached && walks[i].declared < walks[best].declared))
      best = i;
  }
  return walks[best].status;
}

}  // namespace

Result<TriangleMesh> parse_off(const uint8_t* data, size_t size, ImportReport* report) {
  // Binary OFF is recognised before the text path, which refuses NUL bytes.
  if (std::optional<BinaryOffStart> start = find_binary_off(data, size)) {
    ImportReport local;
    if (report == nullptr) report = &local;
    try {
      return BinaryOffReader(data, size, *start, report).read();
    } catch (const std::bad_alloc&) {
      return runtime_error("out of memory while reading the OFF file");
    } catch (const std::length_error&) {
      return runtime_error("out of memory while reading the OFF file");
    }
  }
  return read_text_mesh<OffReader>(data, size, report, "OFF");
}

}  // namespace lodbake
