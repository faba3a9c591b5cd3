// The streaming OBJ reader: the file goes through a buffer cut after a line
// end that no backslash continues, where the in-memory reader's scanner is
// always between statements (a token crosses a line end only through a
// continuation, and a statement ends at the first line end after its last
// token), so each buffer is scanned by a TextScanner exactly as that part of
// the whole file would be.
#include "lib/meshio/obj_stream_reader.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>

#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/obj_keywords.h"
#include "lib/meshio/polygon_triangulation.h"
#include "lib/meshio/text_scanner.h"

namespace lodbake {
namespace {

constexpr size_t kChunkBytes = size_t{1} << 20;
// A longer line (a face with millions of corners) is refused rather than
// held: it is the one thing that would make the buffer grow with the file.
constexpr size_t kMaxLineBytes = size_t{64} << 20;

// The end of the last whole line of buf[0, n) after which the text may be
// cut, or 0: a line end not continued by a backslash, and not a '\r' whose
// '\n' may follow.
size_t cut_point(const uint8_t* buf, size_t n) {
  for (size_t i = n; i-- > 0;) {
    const uint8_t c = buf[i];
    if (c != '\n' && c != '\r') continue;
    if (c == '\r' && (i + 1 == n || buf[i + 1] == '\n')) continue;
    const size_t first = (c == '\n' && i > 0 && buf[i - 1] == '\r') ? i - 1 : i;
    if (first > 0 && buf[first - 1] == '\\') continue;
    return i + 1;
  }
  return 0;
}

std::string line_prefix(const TextScanner& s) {
  return "line " + std::to_string(s.line()) + ": ";
}

// Reads the tokens left on the line and moves past it, as the in-memory
// reader's finish_line(); returns how many there were.
size_t finish_line(TextScanner* s) {
  size_t extra = 0;
  while (!s->token_until('#').empty())
    ++extra;
  s->skip_line();
  return extra;
}

Status read_vec(TextScanner* s, float* out, int count, const char* what) {
  for (int i = 0; i < count; ++i) {
    std::string_view t = s->token_until('#');
    NumberStatus status = t.empty() ? NumberStatus::kMissing : parse_float(t, &out[i]);
    if (status != NumberStatus::kOk) return invalid_input(s->number_error(status, what));
    if (!std::isfinite(out[i]))
      return invalid_input(line_prefix(*s) + what + " " + quote_token(t) + " is not finite");
  }
  return Status::ok();
}

// A 1-based or negative OBJ index against `count` elements so far, with the
// in-memory reader's messages.
Status resolve(const TextScanner& s, std::string_view text, uint64_t count, const char* what,
               uint32_t* out) {
  int64_t index = 0;
  if (parse_int64(text, &index) != NumberStatus::kOk)
    return invalid_input(line_prefix(s) + "expected a " + what + " index, found " +
                         quote_token(text));
  if (index == 0)
    return invalid_input(line_prefix(s) + what + " index 0 is invalid (OBJ indices start at 1)");
  if (index > 0) {
    if (static_cast<uint64_t>(index) > count)
      return invalid_input(line_prefix(s) + what + " index " + std::to_string(index) +
                           " out of range (" + std::to_string(count) + " so far)");
    *out = static_cast<uint32_t>(index - 1);
    return Status::ok();
  }
  if (index == std::numeric_limits<int64_t>::min() || static_cast<uint64_t>(-index) > count)
    return invalid_input(line_prefix(s) + "relative " + what + " index " + std::to_string(index) +
                         " reaches before the first one (" + std::to_string(count) + " so far)");
  *out = static_cast<uint32_t>(count - static_cast<uint64_t>(-index));
  return Status::ok();
}

enum class Statement { kVertex, kTexcoord, kNormal, kFace };

// The statements of one pass: `handle` gets the four that matter (the
// scanner after the keyword) and must move past the line; everything else
// is moved past as the in-memory reader does.
template <typename Handle>
Status scan_statements(TextScanner* s, Handle&& handle) {
  for (;;) {
    s->skip_whitespace();
    if (s->at_end()) return Status::ok();
    if (s->peek() == '#') {
      s->skip_line();
      continue;
    }
    std::string_view keyword = s->token_until('#');
    if (keyword == "v") {
      LODBAKE_RETURN_IF_ERROR(handle(Statement::kVertex));
    } else if (keyword == "f" || keyword == "fo") {
      LODBAKE_RETURN_IF_ERROR(handle(Statement::kFace));
    } else if (keyword == "vt") {
      LODBAKE_RETURN_IF_ERROR(handle(Statement::kTexcoord));
    } else if (keyword == "vn") {
      LODBAKE_RETURN_IF_ERROR(handle(Statement::kNormal));
    } else if (is_obj_ignored_keyword(keyword)) {
      finish_line(s);
    } else {
      s->skip_line();
    }
  }
}

}  // namespace

// One pass over the file, buffer by buffer.
class ObjStreamReader::Pass {
 public:
  explicit Pass(std::istream* in) : in_(in) {}

  // Calls scan(scanner) on each buffer of whole statements.
  template <typename Scan>
  Status run(Scan&& scan) {
    in_->clear();
    in_->seekg(0);
    if (!*in_) return io_error("cannot seek to the start");
    std::vector<uint8_t> buffer(kChunkBytes);
    size_t have = 0;
    uint64_t file_offset = 0;  // of buffer[0]
    uint64_t line = 1;
    size_t checked = 0;  // bytes of the buffer checked for NUL
    bool first = true, eof = false;
    size_t bom = 0;  // bytes of a UTF-8 BOM not yet skipped
    while (!eof || have != 0) {
      if (!eof) {
        if (have == buffer.size()) {
          if (buffer.size() >= kMaxLineBytes)
            return invalid_input("line " + std::to_string(line) + ": a statement longer than " +
                                 std::to_string(kMaxLineBytes >> 20) +
                                 " MiB, more than --memory-limit reads");
          buffer.resize(buffer.size() * 2);
        }
        in_->read(reinterpret_cast<char*>(buffer.data() + have),
                  static_cast<std::streamsize>(buffer.size() - have));
        const auto got = static_cast<size_t>(in_->gcount());
        if (in_->bad()) return io_error("cannot read");
        eof = in_->eof();
        have += got;
      }
      if (first) {
        if (!eof && have < 3) continue;
        if (have >= 2 &&
            ((buffer[0] == 0xfe && buffer[1] == 0xff) || (buffer[0] == 0xff && buffer[1] == 0xfe)))
          return unsupported("UTF-16 text: --memory-limit reads OBJ files in UTF-8 or ASCII");
        if (have >= 3 && buffer[0] == 0xef && buffer[1] == 0xbb && buffer[2] == 0xbf) bom = 3;
        first = false;
      }
      if (checked < have) {
        if (const void* nul = std::memchr(buffer.data() + checked, 0, have - checked))
          return invalid_input(
              "binary data where text was expected: NUL byte at byte " +
              std::to_string(file_offset + static_cast<size_t>(static_cast<const uint8_t*>(nul) -
                                                               buffer.data())));
        checked = have;
      }
      const size_t cut = eof ? have : cut_point(buffer.data(), have);
      if (cut == 0) continue;  // no whole statement yet: read more
      // The BOM is skipped by the first scan, which may come several reads
      // after the first one when the first statement is long.
      const size_t skip = bom;
      bom = 0;
      TextScanner scanner(buffer.data() + skip, cut - skip);
      scanner.set_line_continuation(true);
      scanner.set_line(line);
      LODBAKE_RETURN_IF_ERROR(scan(&scanner));
      line = scanner.line();
      std::memmove(buffer.data(), buffer.data() + cut, have - cut);
      have -= cut;
      checked -= cut;
      file_offset += cut;
    }
    return Status::ok();
  }

 private:
  std::istream* in_;
};

Result<std::unique_ptr<ObjStreamReader>> ObjStreamReader::open(std::istream* in, uint64_t size) {
  if (size == 0) return invalid_input("empty file");
  return std::unique_ptr<ObjStreamReader>(new ObjStreamReader(in, size));
}

Status ObjStreamReader::for_each_vertex(
    const std::function<Status(uint64_t, const float*)>& vertex) {
  vertices_ = 0;
  faces_ = 0;
  Pass pass(in_);
  Status done = pass.run([&](TextScanner* s) {
    return scan_statements(s, [&](Statement statement) -> Status {
      switch (statement) {
        case Statement::kVertex: {
          if (vertices_ >= kObjNoIndex)
            return invalid_input(line_prefix(*s) + "more than 4294967294 vertices");
          float p[3];
          LODBAKE_RETURN_IF_ERROR(read_vec(s, p, 3, "a vertex coordinate"));
          LODBAKE_RETURN_IF_ERROR(vertex(vertices_++, p));
          finish_line(s);
          return Status::ok();
        }
        case Statement::kTexcoord: {
          float uv[2];
          LODBAKE_RETURN_IF_ERROR(read_vec(s, uv, 1, "a texture coordinate"));
          std::string_view t = s->token_until('#');
          if (!t.empty()) {
            NumberStatus status = parse_float(t, &uv[1]);
            if (status != NumberStatus::kOk)
              return invalid_input(s->number_error(status, "a texture coordinate"));
            if (!std::isfinite(uv[1]))
              return invalid_input(line_prefix(*s) + "texture coordinate " + quote_token(t) +
                                   " is not finite");
          }
          finish_line(s);
          return Status::ok();
        }
        case Statement::kNormal: {
          float n[3];
          LODBAKE_RETURN_IF_ERROR(read_vec(s, n, 3, "a normal coordinate"));
          const std::string where = line_prefix(*s);
          if (finish_line(s) != 0) return invalid_input(where + "'vn' takes 3 numbers");
          return Status::ok();
        }
        case Statement::kFace:
          ++faces_;
          finish_line(s);
          return Status::ok();
      }
      return Status::ok();
    });
  });
  if (!done.is_ok()) return done;
  if (faces_ == 0) {
    if (vertices_ == 0) return invalid_input("no vertices or faces found");
    return invalid_input("no faces found (" + std::to_string(vertices_) + " vertices)");
  }
  return Status::ok();
}

Status ObjStreamReader::for_each_triangle(
    const std::vector<Vec3f>& positions,
    const std::function<Status(uint64_t, const uint32_t*)>& triangle) {
  uint64_t vertices = 0, texcoords = 0, normals = 0, face = 0, triangles = 0;
  // A new one per pass: its work budget is spent across the file, and both
  // passes must split every polygon the same way.
  PolygonTriangulator triangulator;
  std::vector<uint32_t> corners;
  std::vector<Triangle> split;
  Pass pass(in_);
  Status done = pass.run([&](TextScanner* s) {
    return scan_statements(s, [&](Statement statement) -> Status {
      if (statement != Statement::kFace) {
        // Checked by for_each_vertex(); only counted here.
        uint64_t* count = statement == Statement::kVertex     ? &vertices
                          : statement == Statement::kTexcoord ? &texcoords
                                                              : &normals;
        ++*count;
        finish_line(s);
        return Status::ok();
      }
      if (vertices > positions.size())
        return invalid_input(line_prefix(*s) + "the file changed between passes");
      corners.clear();
      int form = -1;  // bit 0: texture coordinate, bit 1: normal
      for (;;) {
        std::string_view t = s->token_until('#');
        if (t.empty()) break;
        const size_t slash1 = t.find('/');
        std::string_view v_text = t.substr(0, slash1);
        std::string_view t_text, n_text;
        if (slash1 != std::string_view::npos) {
          std::string_view rest = t.substr(slash1 + 1);
          const size_t slash2 = rest.find('/');
          t_text = rest.substr(0, slash2);
          if (slash2 != std::string_view::npos) {
            n_text = rest.substr(slash2 + 1);
            if (n_text.empty() || n_text.find('/') != std::string_view::npos)
              return invalid_input(line_prefix(*s) + "malformed face corner " + quote_token(t));
          } else if (t_text.empty()) {
            return invalid_input(line_prefix(*s) + "malformed face corner " + quote_token(t));
          }
        }
        const int corner_form = (t_text.empty() ? 0 : 1) | (n_text.empty() ? 0 : 2);
        if (form == -1) form = corner_form;
        if (corner_form != form)
          return invalid_input(
              line_prefix(*s) +
              "face mixes corners with and without texture coordinates or normals (" +
              quote_token(t) + ")");
        uint32_t index = 0;
        LODBAKE_RETURN_IF_ERROR(resolve(*s, v_text, vertices, "vertex", &index));
        corners.push_back(index);
        if (!t_text.empty())
          LODBAKE_RETURN_IF_ERROR(resolve(*s, t_text, texcoords, "texture coordinate", &index));
        if (!n_text.empty())
          LODBAKE_RETURN_IF_ERROR(resolve(*s, n_text, normals, "normal", &index));
      }
      const uint64_t face_line = s->line();
      s->skip_line();
      const size_t n = corners.size();
      if (n < 3)
        return invalid_input("line " + std::to_string(face_line) + ": face has " +
                             std::to_string(n) + (n == 1 ? " corner" : " corners") +
                             ", at least 3 needed");
      split.clear();
      if (n == 3) {
        split.push_back({corners[0], corners[1], corners[2]});
      } else {
        LODBAKE_RETURN_IF_ERROR(
            triangulator.triangulate(corners.data(), n, positions, &split, nullptr));
      }
      for (const Triangle& t : split)
        LODBAKE_RETURN_IF_ERROR(triangle(face, t.data()));
      triangles += split.size();
      ++face;
      return Status::ok();
    });
  });
  if (!done.is_ok()) return done;
  if (triangles == 0)
    return invalid_input("no faces found (" + std::to_string(vertices) + " vertices)");
  return Status::ok();
}

}  // namespace lodbake
