// BASE section codec: an indexed triangle mesh with optionally quantized
// positions and bit-packed indices (DESIGN.md "Container"; byte layout in
// docs/format.md "BASE").
//
// Choices where the brief was open:
// - Quantization (formats/support/quantization.h, shared with VSPL) rounds
//   half away from zero in IEEE double with the operations in the documented
//   order, so any conforming implementation reproduces the integers bit for
//   bit. The box is the positions' bounding box.
// - Canonical form only: index_bits must be exactly bits_for_count(V), the
//   padding bits of every packed stream must be zero and the payload must end
//   exactly after its last field. One mesh therefore has one encoding.
// - A mesh with triangles needs at least 2 vertices: with V <= 1 an index
//   takes 0 bits, so a hostile triangle count would not be bounded by the
//   payload size (and such triangles are single points anyway).
// - Decoding first walks the layout (parse_layout) computing every part's
//   size from the counts and checking it against the bytes that remain; only
//   then are arrays allocated. read_base_summary() is that walk alone.
#include "formats/sections/base.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstring>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"
#include "formats/support/quantization.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

Status bad_base(const std::string& detail) {
  return malformed_section(kBaseTag, detail);
}
Status cannot_encode(const std::string& detail) {
  return invalid_input("cannot encode BASE: " + detail);
}

const char* attribute_name(int which) {
  return which == 0 ? "normals" : "texture coordinates";
}
uint32_t attribute_components(int which) {
  return which == 0 ? 3 : 2;
}

// Where each part of a payload lies; every range was checked against the size.
struct AttributeLayout {
  AttributeBinding binding = AttributeBinding::kNone;
  uint32_t value_count = 0;
  size_t values_offset = 0;
  size_t corners_offset = 0;
  uint64_t corners_bytes = 0;
  int corner_bits = 0;
};

struct BaseLayout {
  BaseSummary summary;
  size_t positions_offset = 0;
  uint64_t positions_bytes = 0;
  size_t indices_offset = 0;
  uint64_t indices_bytes = 0;
  AttributeLayout attributes[2];  // normals, texcoords
};

Status need_bytes(const ByteReader& reader, uint64_t bytes, const std::string& what) {
  if (bytes > reader.remaining()) {
    return bad_base(string_printf("%s need %" PRIu64 " bytes at offset %zu, only %zu remain",
                                  what.c_str(), bytes, reader.position(), reader.remaining()));
  }
  return Status::ok();
}

Status parse_layout(const uint8_t* data, size_t size, BaseLayout* layout) {
  ByteReader reader(data, size);
  BaseSummary& s = layout->summary;
  uint8_t encoding = 0;
  uint8_t qbits = 0;
  if (!reader.read(&s.vertex_count) || !reader.read(&s.triangle_count) || !reader.read(&encoding) ||
      !reader.read(&qbits) || !reader.read(&s.index_bits) || !reader.read(&s.attribute_mask)) {
    return bad_base(string_printf("payload has %zu bytes, the fixed fields need 12", size));
  }
  if (encoding > 1) {
    return bad_base(
        string_printf("position encoding %u is unknown (0 float32, 1 quantized)", encoding));
  }
  s.position_encoding = static_cast<PositionEncoding>(encoding);
  s.quantization_bits = qbits;
  const bool quantized = s.position_encoding == PositionEncoding::kQuantized;
  if (quantized && (qbits < kMinQuantizationBits || qbits > kMaxQuantizationBits)) {
    return bad_base(string_printf("quantization bits %u outside 1..30", qbits));
  }
  if (!quantized && qbits != 0) {
    return bad_base(string_printf("quantization bits %u with float32 positions, must be 0", qbits));
  }
  const int expected_index_bits = bits_for_count(s.vertex_count);
  if (s.index_bits != expected_index_bits) {
    return bad_base(string_printf("index bits %u, %u vertices need exactly %d", s.index_bits,
                                  s.vertex_count, expected_index_bits));
  }
  if ((s.attribute_mask & ~(kBaseHasNormals | kBaseHasTexcoords)) != 0) {
    return bad_base(string_printf("unknown attribute mask bits 0x%02X", s.attribute_mask));
  }
  if (s.vertex_count <= 1 && s.triangle_count != 0) {
    return bad_base(string_printf("%u triangles over %u vertices (triangles need at least 2)",
                                  s.triangle_count, s.vertex_count));
  }
  if (quantized) {
    for (float* v : {&s.box_min[0], &s.box_min[1], &s.box_min[2], &s.box_max[0], &s.box_max[1],
                     &s.box_max[2]}) {
      if (!reader.read(v)) return bad_base("payload ends inside the quantization box");
    }
    int a = 0;
    if (!is_valid_quantization_box(s.box_min, s.box_max, &a)) {
      return bad_base(string_printf("quantization box axis %d [%g, %g] is not finite and ordered",
                                    a, s.box_min[a], s.box_max[a]));
    }
  }

  const uint64_t v = s.vertex_count;
  const uint64_t t = s.triangle_count;
  layout->positions_bytes = quantized ? packed_size_bytes(3 * v, qbits) : 12 * v;
  LODBAKE_RETURN_IF_ERROR(
      need_bytes(reader, layout->positions_bytes, string_printf("%u vertices", s.vertex_count)));
  layout->positions_offset = reader.position();
  reader.skip(layout->positions_bytes);

  layout->indices_bytes = packed_size_bytes(3 * t, s.index_bits);
  LODBAKE_RETURN_IF_ERROR(
      need_bytes(reader, layout->indices_bytes, string_printf("%u triangles", s.triangle_count)));
  layout->indices_offset = reader.position();
  reader.skip(layout->indices_bytes);

  for (int which = 0; which < 2; ++which) {
    const uint8_t bit = which == 0 ? kBaseHasNormals : kBaseHasTexcoords;
    if ((s.attribute_mask & bit) == 0) continue;
    AttributeLayout& attr = layout->attributes[which];
    const char* name = attribute_name(which);
    uint8_t binding = 0;
    if (!reader.read(&binding) || !reader.read(&attr.value_count)) {
      return bad_base(string_printf("payload ends inside the %s header", name));
    }
    if (binding != static_cast<uint8_t>(AttributeBinding::kPerVertex) &&
        binding != static_cast<uint8_t>(AttributeBinding::kPerCorner)) {
      return bad_base(
          string_printf("%s binding %u is unknown (1 per vertex, 2 per corner)", name, binding));
    }
    attr.binding = static_cast<AttributeBinding>(binding);
    if (attr.binding == AttributeBinding::kPerVertex && attr.value_count != s.vertex_count) {
      return bad_base(string_printf("%u per-vertex %s for %u vertices", attr.value_count, name,
                                    s.vertex_count));
    }
    if (attr.binding == AttributeBinding::kPerCorner && attr.value_count == 0 && t != 0) {
      return bad_base(
          string_printf("no %s values for the corners of %u triangles", name, s.triangle_count));
    }
    const uint64_t values_bytes = uint64_t{attr.value_count} * attribute_components(which) * 4;
    LODBAKE_RETURN_IF_ERROR(
        need_bytes(reader, values_bytes, string_printf("%u %s", attr.value_count, name)));
    attr.values_offset = reader.position();
    reader.skip(values_bytes);
    if (attr.binding == AttributeBinding::kPerCorner) {
      attr.corner_bits = bits_for_count(attr.value_count);
      attr.corners_bytes = packed_size_bytes(3 * t, attr.corner_bits);
      LODBAKE_RETURN_IF_ERROR(
          need_bytes(reader, attr.corners_bytes, string_printf("the %s corner indices", name)));
      attr.corners_offset = reader.position();
      reader.skip(attr.corners_bytes);
    }
    if (which == 0) {
      s.normals_binding = attr.binding;
      s.normals_count = attr.value_count;
    } else {
      s.texcoords_binding = attr.binding;
      s.texcoords_count = attr.value_count;
    }
  }
  if (!reader.at_end()) {
    return bad_base(string_printf("%zu trailing bytes after the last field (offset %zu)",
                                  reader.remaining(), reader.position()));
  }
  return Status::ok();
}

// Reads `count` packed values below `limit` into `out` (already sized).
Status read_packed(const uint8_t* data, uint64_t bytes, int bits, uint32_t limit, uint32_t* out,
                   size_t count, const char* what) {
  BitReader bits_in(data, static_cast<size_t>(bytes));
  for (size_t i = 0; i < count; ++i) {
    uint32_t value = 0;
    if (!bits_in.read(bits, &value)) return bad_base(string_printf("%s stream too short", what));
    if (value >= limit) {
      return bad_base(string_printf("%s %zu of triangle %zu is %u, out of range (%u values)", what,
                                    i % 3, i / 3, value, limit));
    }
    out[i] = value;
  }
  if (!bits_in.padding_is_zero())
    return bad_base(string_printf("nonzero padding bits after %s", what));
  return Status::ok();
}

Status read_floats(const uint8_t* data, size_t count, float* out, const char* what) {
  if (count != 0) std::memcpy(out, data, count * sizeof(float));
  for (size_t i = 0; i < count; ++i) {
    if (!std::isfinite(out[i])) {
      return bad_base(string_printf("%s float %zu is not finite", what, i));
    }
  }
  return Status::ok();
}

Status decode_with_layout(const uint8_t* data, const BaseLayout& layout, TriangleMesh* mesh) {
  const BaseSummary& s = layout.summary;
  mesh->positions.resize(s.vertex_count);
  if (s.position_encoding == PositionEncoding::kFloat32) {
    LODBAKE_RETURN_IF_ERROR(
        read_floats(data + layout.positions_offset, 3 * size_t{s.vertex_count},
                    mesh->positions.empty() ? nullptr : mesh->positions[0].data(), "position"));
  } else {
    BitReader bits_in(data + layout.positions_offset, static_cast<size_t>(layout.positions_bytes));
    const uint32_t steps = quantization_steps(s.quantization_bits);
    for (Vec3f& p : mesh->positions) {
      for (int a = 0; a < 3; ++a) {
        uint32_t q = 0;
        if (!bits_in.read(s.quantization_bits, &q)) return bad_base("position stream too short");
        p[a] = dequantize_coordinate(q, s.box_min[a], s.box_max[a], steps);
      }
    }
    if (!bits_in.padding_is_zero()) return bad_base("nonzero padding bits after the positions");
  }

  mesh->triangles.resize(s.triangle_count);
  LODBAKE_RETURN_IF_ERROR(read_packed(data + layout.indices_offset, layout.indices_bytes,
                                      s.index_bits, s.vertex_count,
                                      mesh->triangles.empty() ? nullptr : mesh->triangles[0].data(),
                                      3 * size_t{s.triangle_count}, "vertex index"));

  for (int which = 0; which < 2; ++which) {
    const AttributeLayout& attr = layout.attributes[which];
    MeshAttribute& out = which == 0 ? mesh->normals : mesh->texcoords;
    out = MeshAttribute();
    if (attr.binding == AttributeBinding::kNone) continue;
    out.binding = attr.binding;
    out.components = attribute_components(which);
    out.values.resize(size_t{attr.value_count} * out.components);
    LODBAKE_RETURN_IF_ERROR(read_floats(data + attr.values_offset, out.values.size(),
                                        out.values.data(), attribute_name(which)));
    if (attr.binding == AttributeBinding::kPerCorner) {
      out.corners.resize(s.triangle_count);
      LODBAKE_RETURN_IF_ERROR(read_packed(
          data + attr.corners_offset, attr.corners_bytes, attr.corner_bits, attr.value_count,
          out.corners.empty() ? nullptr : out.corners[0].data(), 3 * size_t{s.triangle_count},
          which == 0 ? "normal corner index" : "texture coordinate corner index"));
    }
  }
  return Status::ok();
}

// Structural problems that make a mesh unstorable; all of them when `all`,
// else stops at the first.
void structural_problems(const TriangleMesh& mesh, bool all, std::vector<std::string>* out) {
  const size_t v = mesh.positions.size();
  const size_t t = mesh.triangles.size();
  if (v > UINT32_MAX) out->push_back(string_printf("%zu vertices, at most 2^32 - 1", v));
  if (t > UINT32_MAX) out->push_back(string_printf("%zu triangles, at most 2^32 - 1", t));
  if (v <= 1 && t != 0) {
    out->push_back(
        string_printf("%zu triangles over %zu vertices (triangles need at least 2)", t, v));
  }
  if (!all && !out->empty()) return;
  size_t bad_positions = 0;
  size_t first_bad_position = 0;
  for (size_t i = 0; i < v; ++i) {
    const Vec3f& p = mesh.positions[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      if (bad_positions++ == 0) first_bad_position = i;
    }
  }
  if (bad_positions != 0) {
    out->push_back(string_printf("%zu vertices have a non-finite coordinate, first: vertex %zu",
                                 bad_positions, first_bad_position));
    if (!all) return;
  }
  size_t bad_indices = 0;
  size_t first_bad_triangle = 0;
  for (size_t i = 0; i < t; ++i) {
    for (uint32_t index : mesh.triangles[i]) {
      if (index >= v) {
        if (bad_indices++ == 0) first_bad_triangle = i;
      }
    }
  }
  if (bad_indices != 0) {
    const Triangle& tri = mesh.triangles[first_bad_triangle];
    out->push_back(string_printf(
        "%zu vertex indices out of range (%zu vertices), first: triangle %zu (%u, %u, %u)",
        bad_indices, v, first_bad_triangle, tri[0], tri[1], tri[2]));
    if (!all) return;
  }
  for (int which = 0; which < 2; ++which) {
    const MeshAttribute& attr = which == 0 ? mesh.normals : mesh.texcoords;
    const char* name = attribute_name(which);
    const uint32_t components = attribute_components(which);
    const size_t problems_before = out->size();
    if (attr.binding == AttributeBinding::kNone) {
      if (!attr.values.empty() || !attr.corners.empty()) {
        out->push_back(string_printf("%s have values but no binding", name));
      }
    } else if (attr.binding != AttributeBinding::kPerVertex &&
               attr.binding != AttributeBinding::kPerCorner) {
      out->push_back(
          string_printf("%s have unknown binding %u", name, static_cast<unsigned>(attr.binding)));
    } else if (attr.components != components) {
      out->push_back(
          string_printf("%s have %u components, expected %u", name, attr.components, components));
    } else if (attr.values.size() % components != 0) {
      out->push_back(string_printf("%s hold %zu floats, not a multiple of %u", name,
                                   attr.values.size(), components));
    } else {
      const size_t count = attr.values.size() / components;
      size_t bad_values = 0;
      for (float f : attr.values)
        bad_values += std::isfinite(f) ? 0 : 1;
      if (bad_values != 0) {
        out->push_back(string_printf("%s hold %zu non-finite floats", name, bad_values));
      }
      if (count > UINT32_MAX)
        out->push_back(string_printf("%zu %s, at most 2^32 - 1", count, name));
      if (attr.binding == AttributeBinding::kPerVertex) {
        if (count != v) {
          out->push_back(string_printf("%zu per-vertex %s for %zu vertices", count, name, v));
        }
        if (!attr.corners.empty()) {
          out->push_back(string_printf("per-vertex %s carry corner indices", name));
        }
      } else if (attr.corners.size() != t) {
        out->push_back(string_printf("%zu corner triples of %s for %zu triangles",
                                     attr.corners.size(), name, t));
      } else {
        size_t bad_corners = 0;
        size_t first = 0;
        for (size_t i = 0; i < t; ++i) {
          for (uint32_t index : attr.corners[i]) {
            if (index >= count && bad_corners++ == 0) first = i;
          }
        }
        if (bad_corners != 0) {
          out->push_back(
              string_printf("%zu %s corner indices out of range (%zu values), first: triangle %zu",
                            bad_corners, name, count, first));
        }
      }
    }
    if (!all && out->size() != problems_before) return;
  }
}

}  // namespace

Result<Bytes> encode_base(const TriangleMesh& mesh, const BaseEncodeOptions& options) {
  if (options.quantize &&
      (options.bits < kMinQuantizationBits || options.bits > kMaxQuantizationBits)) {
    return cannot_encode(string_printf("quantization bits %d outside 1..30", options.bits));
  }
  std::vector<std::string> problems;
  structural_problems(mesh, false, &problems);
  if (!problems.empty()) return cannot_encode(problems.front());
  try {
    const uint32_t v = static_cast<uint32_t>(mesh.positions.size());
    const uint32_t t = static_cast<uint32_t>(mesh.triangles.size());
    const int index_bits = bits_for_count(v);
    Bytes out;
    out.reserve(64 + size_t{v} * 12 + packed_size_bytes(3 * uint64_t{t}, index_bits));
    ByteWriter writer(&out);
    writer.write(v);
    writer.write(t);
    writer.write(static_cast<uint8_t>(options.quantize ? PositionEncoding::kQuantized
                                                       : PositionEncoding::kFloat32));
    writer.write(static_cast<uint8_t>(options.quantize ? options.bits : 0));
    writer.write(static_cast<uint8_t>(index_bits));
    writer.write(static_cast<uint8_t>((mesh.normals.present() ? kBaseHasNormals : 0) |
                                      (mesh.texcoords.present() ? kBaseHasTexcoords : 0)));
    if (options.quantize) {
      Vec3f lo;
      Vec3f hi;
      bounding_box(mesh.positions, &lo, &hi);
      for (float f : lo)
        writer.write(f);
      for (float f : hi)
        writer.write(f);
      const uint32_t steps = quantization_steps(options.bits);
      BitWriter bits_out(&out);
      for (const Vec3f& p : mesh.positions) {
        for (int a = 0; a < 3; ++a)
          bits_out.write(quantize_coordinate(p[a], lo[a], hi[a], steps), options.bits);
      }
      bits_out.finish();
    } else {
      for (const Vec3f& p : mesh.positions) {
        for (float f : p)
          writer.write(f);
      }
    }
    BitWriter bits_out(&out);
    for (const Triangle& tri : mesh.triangles) {
      for (uint32_t index : tri)
        bits_out.write(index, index_bits);
    }
    bits_out.finish();
    for (int which = 0; which < 2; ++which) {
      const MeshAttribute& attr = which == 0 ? mesh.normals : mesh.texcoords;
      if (!attr.present()) continue;
      const uint32_t count = static_cast<uint32_t>(attr.value_count());
      writer.write(static_cast<uint8_t>(attr.binding));
      writer.write(count);
      for (float f : attr.values)
        writer.write(f);
      if (attr.binding == AttributeBinding::kPerCorner) {
        const int corner_bits = bits_for_count(count);
        BitWriter corners_out(&out);
        for (const Triangle& tri : attr.corners) {
          for (uint32_t index : tri)
            corners_out.write(index, corner_bits);
        }
        corners_out.finish();
      }
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding BASE");
  }
}

Result<TriangleMesh> decode_base(const uint8_t* data, size_t size, BaseSummary* summary) {
  try {
    BaseLayout layout;
    LODBAKE_RETURN_IF_ERROR(parse_layout(data, size, &layout));
    TriangleMesh mesh;
    LODBAKE_RETURN_IF_ERROR(decode_with_layout(data, layout, &mesh));
    if (summary != nullptr) *summary = layout.summary;
    return mesh;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding BASE");
  }
}

Result<BaseSummary> read_base_summary(const uint8_t* data, size_t size) {
  BaseLayout layout;
  LODBAKE_RETURN_IF_ERROR(parse_layout(data, size, &layout));
  return layout.summary;
}

std::vector<std::string> validate_base(const TriangleMesh& mesh) {
  std::vector<std::string> findings;
  try {
    structural_problems(mesh, true, &findings);
    const size_t v = mesh.positions.size();
    size_t degenerate = 0;
    size_t first_degenerate = 0;
    std::vector<bool> used(v, false);
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      const Triangle& tri = mesh.triangles[i];
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
        if (degenerate++ == 0) first_degenerate = i;
      }
      for (uint32_t index : tri) {
        if (index < v) used[index] = true;
      }
    }
    if (degenerate != 0) {
      const Triangle& tri = mesh.triangles[first_degenerate];
      findings.push_back(
          string_printf("%zu triangles repeat a vertex index, first: triangle %zu (%u, %u, %u)",
                        degenerate, first_degenerate, tri[0], tri[1], tri[2]));
    }
    if (!mesh.triangles.empty()) {
      const size_t unused = static_cast<size_t>(std::count(used.begin(), used.end(), false));
      if (unused != 0) {
        const size_t first =
            static_cast<size_t>(std::find(used.begin(), used.end(), false) - used.begin());
        findings.push_back(string_printf("%zu vertices are used by no triangle, first: vertex %zu",
                                         unused, first));
      }
    }
  } catch (const std::bad_alloc&) {
    findings.push_back("out of memory while validating BASE");
  }
  return findings;
}

std::vector<std::string> validate_base_payload(const uint8_t* data, size_t size) {
  Result<TriangleMesh> mesh = decode_base(data, size);
  if (!mesh.is_ok()) return {mesh.status().message()};
  return validate_base(mesh.value());
}

Result<QuantizationReport> measure_quantization(const std::vector<Vec3f>& positions, int bits) {
  if (bits < kMinQuantizationBits || bits > kMaxQuantizationBits) {
    return invalid_input(string_printf("quantization bits %d outside 1..30", bits));
  }
  for (size_t i = 0; i < positions.size(); ++i) {
    const Vec3f& p = positions[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return invalid_input(string_printf("vertex %zu has a non-finite coordinate", i));
    }
  }
  QuantizationReport report;
  bounding_box(positions, &report.box_min, &report.box_max);
  const uint32_t steps = quantization_steps(bits);
  for (const Vec3f& p : positions) {
    for (int a = 0; a < 3; ++a) {
      const uint32_t q = quantize_coordinate(p[a], report.box_min[a], report.box_max[a], steps);
      const float back = dequantize_coordinate(q, report.box_min[a], report.box_max[a], steps);
      report.max_error = std::max(report.max_error, std::fabs(static_cast<double>(back) - p[a]));
    }
  }
  report.error_bound = quantization_error_bound(report.box_min, report.box_max, bits);
  return report;
}

}  // namespace lodbake
