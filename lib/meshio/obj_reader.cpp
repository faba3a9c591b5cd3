// Wavefront OBJ reader (geometry statements of the OBJ spec, Appendix B of
// the Advanced Visualizer manual): v, vt, vn and f, into a TriangleMesh.
//
// Choices where the spec or practice is vague:
// - Face indices must refer to elements defined earlier in the file (as the
//   spec's relative indices assume); 0, indices past the elements read so
//   far and relative indices reaching before the first element are errors
//   naming the line.
// - Faces need at least 3 corners; polygons are split by
//   PolygonTriangulator (fan when convex, ear clipping otherwise).
// - Within one face every corner has the same form (v, v/t, v//n or v/t/n);
//   a face mixing them is an error. Across faces, when some faces have
//   texture coordinates (or normals) and others do not, that attribute is
//   dropped for the whole mesh with a note: inventing values for the faces
//   without them would be silently wrong.
// - Texture coordinates and normals are per-corner attributes; when every
//   corner's attribute index equals its vertex index (and there are as many
//   values as vertices) they become per-vertex attributes instead.
// - "v x y z w" and "v x y z r g b" (vertex colours) are read as x y z and
//   the extra values noted; "vt u" gets v = 0; "vt u v w" drops w with a note.
// - Non-finite numbers (nan, inf) in v, vt, vn are errors: no lodbake
//   algorithm can use them and repair cannot invent coordinates.
// - Asked for material groups (lib/scene), 'mtllib' names its libraries
//   (several, blank-separated) and 'usemtl' the rest of its line; each
//   triangle records the material in use.
// - Every other statement (o, g, s, usemtl, mtllib, l, p, curves, ...) is
//   counted and reported in one note per keyword; lines starting with
//   anything else are counted as unknown. A file without any face is an
//   error, so random bytes or another format never give "empty mesh, OK".
// - A trailing backslash joins a line with the next (spec: line
//   continuation). Input is text: UTF-8 (BOM skipped) or UTF-16 with a BOM
//   (decoded, see prepare_text()); NUL bytes are rejected as binary data.
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/obj_keywords.h"
#include "lib/meshio/polygon_triangulation.h"
#include "lib/meshio/text_mesh_reading.h"
#include "lib/meshio/text_scanner.h"

namespace lodbake {
namespace {

constexpr uint32_t kNoIndex = kObjNoIndex;

const char* describe_keyword(std::string_view k) {
  if (k == "o") return "object names";
  if (k == "g") return "groups";
  if (k == "s") return "smoothing groups";
  if (k == "usemtl" || k == "mtllib" || k == "usemap" || k == "maplib") return "materials";
  if (k == "l") return "line elements";
  if (k == "p") return "point elements";
  return "not used by lodbake";
}

// Per-corner attribute indices collected while reading faces.
struct CornerStream {
  uint64_t faces_with = 0;
  uint64_t faces_without = 0;
  std::vector<Triangle> corners;  // parallel to the triangles once any face has the attribute
};

class ObjReader {
 public:
  ObjReader(const uint8_t* data, size_t size, ImportReport* report,
            ObjMaterialGroups* groups = nullptr)
      : text_(data), size_(size), scanner_(data, size), report_(report), groups_(groups) {
    scanner_.set_line_continuation(true);
  }

  Result<TriangleMesh> read();

 private:
  void reserve_by_precount();
  Status read_vec(float* out, int count, const char* what);
  Status read_vertex();
  Status read_texcoord();
  Status read_normal();
  Status read_face();
  void read_mtllib();
  void read_usemtl();
  // Resolves a 1-based or negative OBJ index against `count` elements so far.
  Status resolve(std::string_view text, uint64_t count, const char* what, uint32_t* out) const;
  // Reads the tokens left on the line (noting how many) and moves past it.
  size_t finish_line();
  Status finish_attribute(CornerStream* stream, std::vector<float>* values, uint32_t components,
                          const char* name, const char* keyword, MeshAttribute* out);
  std::string line_prefix() const { return "line " + std::to_string(scanner_.line()) + ": "; }
  std::string format_hint() const;

  const uint8_t* text_;
  size_t size_;
  TextScanner scanner_;
  ImportReport* report_;
  ObjMaterialGroups* groups_;  // null: materials are ignored
  int32_t material_ = -1;      // index into groups_->materials of the 'usemtl' in force
  std::map<std::string, int32_t, std::less<>> material_index_;
  TriangleMesh mesh_;
  std::vector<float> texcoord_values_;
  std::vector<float> normal_values_;
  CornerStream texcoord_corners_;
  CornerStream normal_corners_;
  PolygonTriangulator triangulator_;
  std::vector<uint32_t> face_v_, face_t_, face_n_;
  std::vector<Triangle> slots_;
  uint64_t faces_ = 0;
  uint64_t vertex_extra_lines_ = 0;
  uint64_t texcoord_w_lines_ = 0;
  uint64_t unknown_lines_ = 0;
  std::map<std::string, uint64_t, std::less<>> ignored_;
};

void ObjReader::reserve_by_precount() {
  // One cheap pass over line starts. The counts are bounded by the number of
  // lines, hence by the file size, so reserving them is safe.
  uint64_t v = 0, vt = 0, vn = 0, f = 0;
  const uint8_t* p = text_;
  const uint8_t* end = text_ + size_;
  while (p < end) {
    while (p < end && (*p == ' ' || *p == '\t'))
      ++p;
    if (end - p >= 2 && p[0] == 'v') {
      if (p[1] == ' ' || p[1] == '\t') ++v;
      if (p[1] == 't') ++vt;
      if (p[1] == 'n') ++vn;
    } else if (end - p >= 2 && p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
      ++f;
    }
    const void* nl = std::memchr(p, '\n', static_cast<size_t>(end - p));
    if (nl == nullptr) break;
    p = static_cast<const uint8_t*>(nl) + 1;
  }
  mesh_.positions.reserve(v);
  texcoord_values_.reserve(vt * 2);
  normal_values_.reserve(vn * 3);
  mesh_.triangles.reserve(f);
}

size_t ObjReader::finish_line() {
  size_t extra = 0;
  for (;;) {
    std::string_view t = scanner_.token_until('#');
    if (t.empty()) break;
    ++extra;
  }
  scanner_.skip_line();
  return extra;
}

Status ObjReader::read_vec(float* out, int count, const char* what) {
  for (int i = 0; i < count; ++i) {
    std::string_view t = scanner_.token_until('#');
    NumberStatus status = t.empty() ? NumberStatus::kMissing : parse_float(t, &out[i]);
    if (status != NumberStatus::kOk) return invalid_input(scanner_.number_error(status, what));
    if (!std::isfinite(out[i]))
      return invalid_input(line_prefix() + what + " " + quote_token(t) + " is not finite");
  }
  return Status::ok();
}

Status ObjReader::read_vertex() {
  if (mesh_.positions.size() >= kNoIndex)
    return invalid_input(line_prefix() + "more than 4294967294 vertices");
  Vec3f p;
  LODBAKE_RETURN_IF_ERROR(read_vec(p.data(), 3, "a vertex coordinate"));
  mesh_.positions.push_back(p);
  if (finish_line() != 0) ++vertex_extra_lines_;
  return Status::ok();
}

Status ObjReader::read_texcoord() {
  float uv[2] = {0, 0};
  LODBAKE_RETURN_IF_ERROR(read_vec(uv, 1, "a texture coordinate"));
  std::string_view t = scanner_.token_until('#');
  if (!t.empty()) {
    NumberStatus status = parse_float(t, &uv[1]);
    if (status != NumberStatus::kOk)
      return invalid_input(scanner_.number_error(status, "a texture coordinate"));
    if (!std::isfinite(uv[1]))
      return invalid_input(line_prefix() + "texture coordinate " + quote_token(t) +
                           " is not finite");
  }
  texcoord_values_.push_back(uv[0]);
  texcoord_values_.push_back(uv[1]);
  if (finish_line() != 0) ++texcoord_w_lines_;
  return Status::ok();
}

Status ObjReader::read_normal() {
  float n[3];
  LODBAKE_RETURN_IF_ERROR(read_vec(n, 3, "a normal coordinate"));
  normal_values_.insert(normal_values_.end(), n, n + 3);
  const std::string where = line_prefix();
  if (finish_line() != 0) return invalid_input(where + "'vn' takes 3 numbers");
  return Status::ok();
}

Status ObjReader::resolve(std::string_view text, uint64_t count, const char* what,
                          uint32_t* out) const {
  int64_t index = 0;
  NumberStatus status = parse_int64(text, &index);
  if (status != NumberStatus::kOk) {
    return invalid_input(line_prefix() + "expected a " + what + " index, found " +
                         quote_token(text));
  }
  if (index == 0)
    return invalid_input(line_prefix() + what + " index 0 is invalid (OBJ indices start at 1)");
  if (index > 0) {
    if (static_cast<uint64_t>(index) > count) {
      return invalid_input(line_prefix() + what + " index " + std::to_string(index) +
                           " out of range (" + std::to_string(count) + " so far)");
    }
    *out = static_cast<uint32_t>(index - 1);
    return Status::ok();
  }
  // index < 0: -1 is the last element read; int64 min cannot be negated.
  if (index == std::numeric_limits<int64_t>::min() || static_cast<uint64_t>(-index) > count) {
    return invalid_input(line_prefix() + "relative " + what + " index " + std::to_string(index) +
                         " reaches before the first one (" + std::to_string(count) + " so far)");
  }
  *out = static_cast<uint32_t>(count - static_cast<uint64_t>(-index));
  return Status::ok();
}

Status ObjReader::read_face() {
  face_v_.clear();
  face_t_.clear();
  face_n_.clear();
  int form = -1;  // bit 0: texture coordinate, bit 1: normal
  const uint64_t texcoord_count = texcoord_values_.size() / 2;
  const uint64_t normal_count = normal_values_.size() / 3;
  for (;;) {
    std::string_view t = scanner_.token_until('#');
    if (t.empty()) break;
    size_t slash1 = t.find('/');
    std::string_view v_text = t.substr(0, slash1);
    std::string_view t_text;
    std::string_view n_text;
    if (slash1 != std::string_view::npos) {
      std::string_view rest = t.substr(slash1 + 1);
      size_t slash2 = rest.find('/');
      t_text = rest.substr(0, slash2);
      if (slash2 != std::string_view::npos) {
        n_text = rest.substr(slash2 + 1);
        if (n_text.empty() || n_text.find('/') != std::string_view::npos)
          return invalid_input(line_prefix() + "malformed face corner " + quote_token(t));
      } else if (t_text.empty()) {
        return invalid_input(line_prefix() + "malformed face corner " + quote_token(t));
      }
    }
    const int corner_form = (t_text.empty() ? 0 : 1) | (n_text.empty() ? 0 : 2);
    if (form == -1) form = corner_form;
    if (corner_form != form) {
      return invalid_input(line_prefix() +
                           "face mixes corners with and without texture coordinates or normals "
                           "(" +
                           quote_token(t) + ")");
    }
    uint32_t index = 0;
    LODBAKE_RETURN_IF_ERROR(resolve(v_text, mesh_.positions.size(), "vertex", &index));
    face_v_.push_back(index);
    if (!t_text.empty()) {
      LODBAKE_RETURN_IF_ERROR(resolve(t_text, texcoord_count, "texture coordinate", &index));
      face_t_.push_back(index);
    }
    if (!n_text.empty()) {
      LODBAKE_RETURN_IF_ERROR(resolve(n_text, normal_count, "normal", &index));
      face_n_.push_back(index);
    }
  }
  const uint64_t face_line = scanner_.line();
  scanner_.skip_line();
  const size_t n = face_v_.size();
  if (n < 3) {
    return invalid_input("line " + std::to_string(face_line) + ": face has " + std::to_string(n) +
                         (n == 1 ? " corner" : " corners") + ", at least 3 needed");
  }
  ++faces_;
  const size_t first = mesh_.triangles.size();
  if (n == 3) {
    mesh_.triangles.push_back({face_v_[0], face_v_[1], face_v_[2]});
    slots_.assign(1, Triangle{0, 1, 2});
  } else {
    slots_.clear();
    LODBAKE_RETURN_IF_ERROR(
        triangulator_.triangulate(face_v_.data(), n, mesh_.positions, &mesh_.triangles, &slots_));
  }
  const size_t added = mesh_.triangles.size() - first;
  if (groups_ != nullptr) groups_->triangle_material.resize(first + added, material_);
  auto follow = [&](CornerStream* stream, const std::vector<uint32_t>& indices) {
    if (indices.empty()) {
      ++stream->faces_without;
      if (stream->faces_with != 0)
        stream->corners.resize(first + added, {kNoIndex, kNoIndex, kNoIndex});
      return;
    }
    if (stream->faces_with++ == 0) stream->corners.assign(first, {kNoIndex, kNoIndex, kNoIndex});
    for (size_t k = 0; k < added; ++k) {
      const Triangle& s = slots_[k];
      stream->corners.push_back({indices[s[0]], indices[s[1]], indices[s[2]]});
    }
  };
  follow(&texcoord_corners_, face_t_);
  follow(&normal_corners_, face_n_);
  return Status::ok();
}

void ObjReader::read_mtllib() {
  for (;;) {
    std::string_view t = scanner_.token_until('#');
    if (t.empty()) break;
    groups_->libraries.emplace_back(t);
  }
  scanner_.skip_line();
}

void ObjReader::read_usemtl() {
  std::string name;
  for (;;) {
    std::string_view t = scanner_.token_until('#');
    if (t.empty()) break;
    if (!name.empty()) name += ' ';
    name += t;
  }
  scanner_.skip_line();
  auto it = material_index_.find(name);
  if (it == material_index_.end()) {
    it = material_index_.emplace(name, static_cast<int32_t>(groups_->materials.size())).first;
    groups_->materials.push_back(name);
  }
  material_ = it->second;
}

Status ObjReader::finish_attribute(CornerStream* stream, std::vector<float>* values,
                                   uint32_t components, const char* name, const char* keyword,
                                   MeshAttribute* out) {
  const uint64_t value_count = values->size() / components;
  if (stream->faces_with == 0) {
    if (value_count != 0) {
      report_->notes.push_back("ignored " + std::to_string(value_count) + " " + name + " ('" +
                               keyword + "') that no face uses");
    }
    return Status::ok();
  }
  if (stream->faces_without != 0) {
    if (groups_ != nullptr) {
      MeshAttribute* partial =
          components == 2 ? &groups_->partial_texcoords : &groups_->partial_normals;
      partial->binding = AttributeBinding::kPerCorner;
      partial->components = components;
      partial->values = std::move(*values);
      partial->corners = std::move(stream->corners);
      return Status::ok();  // the caller says what it keeps
    }
    report_->notes.push_back("dropped " + std::string(name) + ": " +
                             std::to_string(stream->faces_without) + " of " +
                             std::to_string(faces_) + " faces have none");
    return Status::ok();
  }
  out->components = components;
  bool identity = value_count == mesh_.positions.size();
  for (size_t t = 0; identity && t < mesh_.triangles.size(); ++t)
    identity = stream->corners[t] == mesh_.triangles[t];
  out->values = std::move(*values);
  if (identity) {
    out->binding = AttributeBinding::kPerVertex;
  } else {
    out->binding = AttributeBinding::kPerCorner;
    out->corners = std::move(stream->corners);
  }
  return Status::ok();
}

std::string ObjReader::format_hint() const {
  auto starts_with = [&](const char* prefix) {
    size_t n = std::strlen(prefix);
    return size_ >= n && std::memcmp(text_, prefix, n) == 0;
  };
  if (starts_with("ply")) return " (the text starts with 'ply': a PLY file?)";
  if (starts_with("OFF") || starts_with("COFF") || starts_with("NOFF"))
    return " (the text starts with an OFF keyword: an OFF file?)";
  if (starts_with("solid")) return " (the text starts with 'solid': an STL file?)";
  return "";
}

Result<TriangleMesh> ObjReader::read() {
  report_->format = "obj";
  if (size_ == 0) return invalid_input("empty file");
  reserve_by_precount();
  for (;;) {
    scanner_.skip_whitespace();
    if (scanner_.at_end()) break;
    if (scanner_.peek() == '#') {
      scanner_.skip_line();
      continue;
    }
    std::string_view keyword = scanner_.token_until('#');
    if (keyword == "v") {
      LODBAKE_RETURN_IF_ERROR(read_vertex());
    } else if (keyword == "f" || keyword == "fo") {
      LODBAKE_RETURN_IF_ERROR(read_face());
    } else if (keyword == "vt") {
      LODBAKE_RETURN_IF_ERROR(read_texcoord());
    } else if (keyword == "vn") {
      LODBAKE_RETURN_IF_ERROR(read_normal());
    } else if (groups_ != nullptr && keyword == "mtllib") {
      read_mtllib();
    } else if (groups_ != nullptr && keyword == "usemtl") {
      read_usemtl();
    } else if (is_obj_ignored_keyword(keyword)) {
      auto it = ignored_.find(keyword);
      if (it == ignored_.end()) it = ignored_.emplace(std::string(keyword), 0).first;
      ++it->second;
      finish_line();
    } else {
      ++unknown_lines_;
      scanner_.skip_line();
    }
  }

  if (mesh_.triangles.empty()) {
    if (mesh_.positions.empty()) return invalid_input("no vertices or faces found" + format_hint());
    return invalid_input("no faces found (" + std::to_string(mesh_.positions.size()) +
                         " vertices)" + format_hint());
  }
  LODBAKE_RETURN_IF_ERROR(finish_attribute(&texcoord_corners_, &texcoord_values_, 2,
                                           "texture coordinates", "vt", &mesh_.texcoords));
  LODBAKE_RETURN_IF_ERROR(
      finish_attribute(&normal_corners_, &normal_values_, 3, "normals", "vn", &mesh_.normals));

  report_->file_faces = faces_;
  triangulator_.add_to_report(report_);
  if (vertex_extra_lines_ != 0) {
    report_->notes.push_back("ignored the values after x y z (w or a vertex colour) on " +
                             std::to_string(vertex_extra_lines_) + " 'v' lines");
  }
  if (texcoord_w_lines_ != 0) {
    report_->notes.push_back("ignored the values after u v on " +
                             std::to_string(texcoord_w_lines_) + " 'vt' lines");
  }
  for (const auto& [keyword, count] : ignored_) {
    report_->notes.push_back("ignored " + std::to_string(count) + " '" + keyword + "' statement" +
                             (count == 1 ? "" : "s") + " (" + describe_keyword(keyword) + ")");
  }
  if (unknown_lines_ != 0) {
    report_->notes.push_back("ignored " + std::to_string(unknown_lines_) +
                             " lines with an unknown statement");
  }
  return std::move(mesh_);
}

}  // namespace

Result<TriangleMesh> parse_obj(const uint8_t* data, size_t size, ImportReport* report) {
  return read_text_mesh<ObjReader>(data, size, report, "OBJ");
}

Result<TriangleMesh> parse_obj(const uint8_t* data, size_t size, ImportReport* report,
                               ObjMaterialGroups* groups) {
  *groups = ObjMaterialGroups();
  return read_text_mesh<ObjReader>(data, size, report, "OBJ", groups);
}

}  // namespace lodbake
