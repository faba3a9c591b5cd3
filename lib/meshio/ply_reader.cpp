// PLY reader (ASCII, binary little- and big-endian) after the format
// description of Turk's Stanford ply library: header -> plan (ply_plan.cpp)
// -> one pass over the body with a value source per encoding.
// Choices where the format leaves room:
// - Elements may come in any order; indices are checked against the header's
//   vertex count, so faces can precede vertices. Polygons are triangulated
//   after the whole body is read (ear clipping needs positions) and their
//   triangles are put where the face was, keeping the file's face order.
// - Faces need at least 3 corners and at most kMaxFaceCorners; every index
//   must be in range. Strips (`tristrips`) restart at index -1 and alternate
//   winding (triangle k of a strip is v[k] v[k+1] v[k+2], with the first two
//   swapped when k is odd); the triangles with a repeated index that join
//   strips are dropped and counted in a note.
// - Non-finite coordinates, normals or texture coordinates are refused: the
//   algorithms cannot take them (the OBJ and OFF readers do the same).
// - Bytes after the last element are ignored with a note.
// The dragon (34 MB of ASCII) goes through one tight loop per element over a
// TextScanner with std::from_chars, with every array reserved from header
// counts that plan_ply() bounded by the body size first.
#include <algorithm>
#include <cmath>
#include <new>
#include <string>
#include <vector>

#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/ply_ascii_source.h"
#include "lib/meshio/ply_binary_source.h"
#include "lib/meshio/ply_header.h"
#include "lib/meshio/ply_plan.h"
#include "lib/meshio/polygon_triangulation.h"

namespace lodbake {
namespace {

// Bounds the scratch list of one face; real polygons stay far below it.
constexpr uint64_t kMaxFaceCorners = uint64_t{1} << 20;

std::string item(const PlyElement& element, uint64_t i) {
  return element.name + " " + std::to_string(i + 1) + " of " + std::to_string(element.count);
}

std::string item_property(const PlyElement& element, uint64_t i, const PlyProperty& p) {
  return item(element, i) + ", property " + quote_token(p.name);
}

// Faces with more than 3 corners, triangulated once positions are known.
struct PendingPolygon {
  size_t insert_at;  // triangle count when the face was read
  size_t begin;      // first corner in polygon_corners
  uint32_t count;
};

template <class Source>
class PlyBodyReader {
 public:
  PlyBodyReader(Source* source, const PlyPlan& plan, TriangleMesh* mesh, ImportReport* report,
                VertexColours* colours)
      : src_(*source), plan_(plan), mesh_(*mesh), report_(*report), colours_(colours) {}

  Status read() {
    mesh_.positions.resize(static_cast<size_t>(plan_.vertex_count));
    if (plan_.has_normals) normals_.resize(static_cast<size_t>(plan_.vertex_count) * 3);
    if (plan_.has_texcoords) texcoords_.resize(static_cast<size_t>(plan_.vertex_count) * 2);
    if (plan_.colour_components != 0) {
      colours_->components = plan_.colour_components;
      colours_->max_value = plan_.colour_type == PlyType::kUint8    ? 255
                            : plan_.colour_type == PlyType::kUint16 ? 65535
                                                                    : 1;
      colours_->values.resize(static_cast<size_t>(plan_.vertex_count) * plan_.colour_components);
    }
    mesh_.triangles.reserve(static_cast<size_t>(plan_.face_count));
    for (const PlyElementPlan& e : plan_.elements) {
      switch (e.role) {
        case PlyRole::kVertex:
          LODBAKE_RETURN_IF_ERROR(read_vertices(e));
          break;
        case PlyRole::kFace:
          LODBAKE_RETURN_IF_ERROR(read_faces(e));
          report_.file_faces += e.element->count;
          break;
        case PlyRole::kStrips: {
          // Strips count as the triangles they make, as MANIFEST.md counts them.
          const size_t before = mesh_.triangles.size();
          LODBAKE_RETURN_IF_ERROR(read_strips(e));
          report_.file_faces += mesh_.triangles.size() - before;
          break;
        }
        case PlyRole::kSkip:
          LODBAKE_RETURN_IF_ERROR(skip_element(e));
          break;
      }
    }
    if (uint64_t trailing = src_.trailing_bytes(); trailing != 0) {
      report_.notes.push_back("ignored " + std::to_string(trailing) +
                              " bytes after the last element");
    }
    if (strip_degenerates_ != 0) {
      report_.notes.push_back("dropped " + std::to_string(strip_degenerates_) +
                              " strip triangles with a repeated index (strip joins)");
    }
    LODBAKE_RETURN_IF_ERROR(triangulate_polygons());
    if (plan_.has_normals) {
      mesh_.normals.binding = AttributeBinding::kPerVertex;
      mesh_.normals.components = 3;
      mesh_.normals.values = std::move(normals_);
    }
    if (plan_.has_texcoords) {
      mesh_.texcoords.binding = AttributeBinding::kPerVertex;
      mesh_.texcoords.components = 2;
      mesh_.texcoords.values = std::move(texcoords_);
    }
    return Status::ok();
  }

 private:
  Status read_vertices(const PlyElementPlan& e) {
    const PlyElement& element = *e.element;
    const auto& properties = element.properties;
    for (uint64_t i = 0; i < element.count; ++i) {
      const uint64_t mark = src_.mark();
      float v[kVertexSlots] = {};
      for (size_t k = 0; k < properties.size(); ++k) {
        const PlyProperty& p = properties[k];
        const uint8_t slot = e.slots[k];
        bool ok = slot == kSlotSkip ? skip_property(p) : src_.read_float(p.type, &v[slot]);
        if (!ok) return list_or_read_failure(element, i, p);
      }
      for (size_t k = 0; k < properties.size(); ++k) {
        const uint8_t slot = e.slots[k];
        if (slot < kVertexSlots && !std::isfinite(v[slot])) {
          return invalid_input(src_.where(mark) + ": " + item(element, i) + " has a non-finite " +
                               properties[k].name + " (" + std::to_string(v[slot]) + ")");
        }
      }
      const auto index = static_cast<size_t>(i);
      mesh_.positions[index] = {v[kSlotX], v[kSlotY], v[kSlotZ]};
      if (plan_.has_normals) {
        normals_[3 * index] = v[kSlotNx];
        normals_[3 * index + 1] = v[kSlotNy];
        normals_[3 * index + 2] = v[kSlotNz];
      }
      if (plan_.has_texcoords) {
        texcoords_[2 * index] = v[kSlotU];
        texcoords_[2 * index + 1] = v[kSlotV];
      }
      if (const uint32_t c = plan_.colour_components; c != 0) {
        std::copy(v + kSlotRed, v + kSlotRed + c, colours_->values.begin() + c * index);
      }
    }
    return Status::ok();
  }

  // Calls read_list(i, p, mark, n) for the index list of each item of the
  // element once its length n is read and bounded (mark: where the length
  // stands); every other property is skipped.
  template <class ReadList>
  Status for_each_index_list(const PlyElementPlan& e, ReadList read_list) {
    const PlyElement& element = *e.element;
    const auto& properties = element.properties;
    for (uint64_t i = 0; i < element.count; ++i) {
      for (size_t k = 0; k < properties.size(); ++k) {
        const PlyProperty& p = properties[k];
        if (e.slots[k] != kSlotIndices) {
          if (!skip_property(p)) return list_or_read_failure(element, i, p);
          continue;
        }
        const auto mark = src_.mark();
        uint64_t n = 0;
        LODBAKE_RETURN_IF_ERROR(read_list_length(element, i, p, mark, &n));
        LODBAKE_RETURN_IF_ERROR(read_list(i, p, mark, n));
      }
    }
    return Status::ok();
  }

  Status read_faces(const PlyElementPlan& e) {
    const PlyElement& element = *e.element;
    return for_each_index_list(
        e, [&](uint64_t i, const PlyProperty& p, uint64_t mark, uint64_t n) -> Status {
          if (n < 3) {
            return invalid_input(src_.where(mark) + ": " + item(element, i) + " has " +
                                 std::to_string(n) + " corners; a face needs at least 3");
          }
          if (n > kMaxFaceCorners) {
            return invalid_input(src_.where(mark) + ": " + item(element, i) + " has " +
                                 std::to_string(n) + " corners, more than the " +
                                 std::to_string(kMaxFaceCorners) + " lodbake accepts");
          }
          corners_.resize(static_cast<size_t>(n));
          for (size_t c = 0; c < corners_.size(); ++c) {
            LODBAKE_RETURN_IF_ERROR(read_index(element, i, p, &corners_[c]));
          }
          if (n == 3) {
            mesh_.triangles.push_back({corners_[0], corners_[1], corners_[2]});
          } else {
            polygons_.push_back(
                {mesh_.triangles.size(), polygon_corners_.size(), static_cast<uint32_t>(n)});
            polygon_corners_.insert(polygon_corners_.end(), corners_.begin(), corners_.end());
          }
          return Status::ok();
        });
  }

  Status read_strips(const PlyElementPlan& e) {
    const PlyElement& element = *e.element;
    return for_each_index_list(
        e, [&](uint64_t i, const PlyProperty& p, uint64_t /*mark*/, uint64_t n) -> Status {
          uint32_t window[2] = {0, 0};
          int have = 0;
          bool odd = false;
          for (uint64_t j = 0; j < n; ++j) {
            const uint64_t at = src_.mark();
            int64_t raw = 0;
            if (!src_.read_int(p.type, &raw))
              return src_.read_failure(item_property(element, i, p));
            if (raw == -1) {
              have = 0;
              odd = false;
              continue;
            }
            LODBAKE_RETURN_IF_ERROR(check_index(element, i, at, raw));
            const auto index = static_cast<uint32_t>(raw);
            if (have < 2) {
              window[have++] = index;
              continue;
            }
            Triangle t =
                odd ? Triangle{window[1], window[0], index} : Triangle{window[0], window[1], index};
            if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) {
              mesh_.triangles.push_back(t);
            } else {
              ++strip_degenerates_;
            }
            window[0] = window[1];
            window[1] = index;
            odd = !odd;
          }
          return Status::ok();
        });
  }

  Status skip_element(const PlyElementPlan& e) {
    const PlyElement& element = *e.element;
    const auto& properties = element.properties;
    if (properties.empty()) return Status::ok();
    for (uint64_t i = 0; i < element.count; ++i) {
      for (const PlyProperty& p : properties) {
        if (!skip_property(p)) return list_or_read_failure(element, i, p);
      }
    }
    return Status::ok();
  }

  // Skips a scalar or a whole list. A false return with bad_length_ set
  // means the list's length was impossible rather than a value unreadable.
  bool skip_property(const PlyProperty& p) {
    bad_length_ = false;
    if (!p.is_list) return src_.skip(p.type);
    const uint64_t mark = src_.mark();
    int64_t n = 0;
    if (!src_.read_int(p.count_type, &n)) return false;
    if (n < 0 || static_cast<uint64_t>(n) > src_.max_values(p.type)) {
      bad_length_ = true;
      bad_length_mark_ = mark;
      bad_length_value_ = n;
      return false;
    }
    return src_.skip_values(p.type, static_cast<uint64_t>(n));
  }

  Status list_or_read_failure(const PlyElement& element, uint64_t i, const PlyProperty& p) {
    if (bad_length_) return list_length_error(element, i, p, bad_length_mark_, bad_length_value_);
    return src_.read_failure(item_property(element, i, p));
  }

  Status list_length_error(const PlyElement& element, uint64_t i, const PlyProperty& p,
                           uint64_t mark, int64_t n) const {
    std::string message = src_.where(mark) + ": " + item_property(element, i, p) + ": ";
    if (n < 0) return invalid_input(message + "negative list length " + std::to_string(n));
    return invalid_input(message + "list length " + std::to_string(n) + " overruns the file (" +
                         std::to_string(src_.remaining()) + " bytes left for " +
                         ply_type_name(p.type) + " entries)");
  }

  Status read_list_length(const PlyElement& element, uint64_t i, const PlyProperty& p,
                          uint64_t mark, uint64_t* n) {
    int64_t raw = 0;
    if (!src_.read_int(p.count_type, &raw)) return src_.read_failure(item_property(element, i, p));
    if (raw < 0 || static_cast<uint64_t>(raw) > src_.max_values(p.type)) {
      return list_length_error(element, i, p, mark, raw);
    }
    *n = static_cast<uint64_t>(raw);
    return Status::ok();
  }

  Status read_index(const PlyElement& element, uint64_t i, const PlyProperty& p, uint32_t* out) {
    const uint64_t mark = src_.mark();
    int64_t raw = 0;
    if (!src_.read_int(p.type, &raw)) return src_.read_failure(item_property(element, i, p));
    LODBAKE_RETURN_IF_ERROR(check_index(element, i, mark, raw));
    *out = static_cast<uint32_t>(raw);
    return Status::ok();
  }

  Status check_index(const PlyElement& element, uint64_t i, uint64_t mark, int64_t raw) const {
    if (raw < 0 || static_cast<uint64_t>(raw) >= plan_.vertex_count) {
      return invalid_input(src_.where(mark) + ": " + item(element, i) + ": vertex index " +
                           std::to_string(raw) + " out of range (" +
                           std::to_string(plan_.vertex_count) + " vertices)");
    }
    return Status::ok();
  }

  Status triangulate_polygons() {
    if (polygons_.empty()) return Status::ok();
    std::vector<Triangle> merged;
    merged.reserve(mesh_.triangles.size() + polygon_corners_.size() - 2 * polygons_.size());
    PolygonTriangulator triangulator;
    size_t next = 0;
    for (const PendingPolygon& polygon : polygons_) {
      merged.insert(merged.end(), mesh_.triangles.begin() + static_cast<ptrdiff_t>(next),
                    mesh_.triangles.begin() + static_cast<ptrdiff_t>(polygon.insert_at));
      next = polygon.insert_at;
      LODBAKE_RETURN_IF_ERROR(triangulator.triangulate(
          &polygon_corners_[polygon.begin], polygon.count, mesh_.positions, &merged, nullptr));
    }
    merged.insert(merged.end(), mesh_.triangles.begin() + static_cast<ptrdiff_t>(next),
                  mesh_.triangles.end());
    mesh_.triangles = std::move(merged);
    triangulator.add_to_report(&report_);
    return Status::ok();
  }

  Source& src_;
  const PlyPlan& plan_;
  TriangleMesh& mesh_;
  ImportReport& report_;
  VertexColours* colours_;  // null unless the plan has colours
  std::vector<float> normals_;
  std::vector<float> texcoords_;
  std::vector<uint32_t> corners_;
  std::vector<uint32_t> polygon_corners_;
  std::vector<PendingPolygon> polygons_;
  uint64_t strip_degenerates_ = 0;
  bool bad_length_ = false;
  uint64_t bad_length_mark_ = 0;
  int64_t bad_length_value_ = 0;
};

Result<TriangleMesh> parse_ply_impl(const uint8_t* data, size_t size, ImportReport* report,
                                    VertexColours* colours) {
  LODBAKE_ASSIGN_OR_RETURN(PlyHeader header, parse_ply_header(data, size));
  LODBAKE_ASSIGN_OR_RETURN(PlyPlan plan,
                           plan_ply(header, size - header.body_offset, report, colours != nullptr));
  TriangleMesh mesh;
  switch (header.format) {
    case PlyFormat::kAscii: {
      report->format = "ply-ascii";
      PlyAsciiSource source(data, size, header.body_offset, header.body_first_line);
      LODBAKE_RETURN_IF_ERROR(
          PlyBodyReader<PlyAsciiSource>(&source, plan, &mesh, report, colours).read());
      break;
    }
    case PlyFormat::kBinaryLittleEndian:
    case PlyFormat::kBinaryBigEndian: {
      const bool little = header.format == PlyFormat::kBinaryLittleEndian;
      report->format = little ? "ply-binary-le" : "ply-binary-be";
      PlyBinarySource source(data, size, header.body_offset,
                             little ? Endian::kLittle : Endian::kBig);
      LODBAKE_RETURN_IF_ERROR(
          PlyBodyReader<PlyBinarySource>(&source, plan, &mesh, report, colours).read());
      break;
    }
  }
  return mesh;
}

}  // namespace

Result<TriangleMesh> parse_ply(const uint8_t* data, size_t size, ImportReport* report,
                               VertexColours* colours) {
  ImportReport local;
  ImportReport* out = report != nullptr ? report : &local;
  if (colours != nullptr) *colours = VertexColours();
  try {
    return parse_ply_impl(data, size, out, colours);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reading the ply file");
  }
}

Result<TriangleMesh> parse_ply(const uint8_t* data, size_t size, ImportReport* report) {
  return parse_ply(data, size, report, nullptr);
}

}  // namespace lodbake
