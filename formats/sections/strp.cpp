// STRP section codec: triangle strips alone (no multiresolution), byte
// layout in docs/format.md "STRP".
//
// Choices where the brief was open:
// - Strips are separate sequences (lengths stored), not one sequence joined
//   by degenerate triangles or restart indices: the SETS graph keeps one
//   graph per strip, and a renderer can join them either way.
// - Lengths are stored minus 3 (a strip has at least one window) at the
//   width of the longest; indices at bits_for_count(vertex count). Both in
//   one LSB-first bit stream, zero padded to a byte.
// - Strips over fewer than 3 vertices are refused and a payload without
//   strips has no indices, so every index costs at least 2 bits and the
//   index count is bounded by the payload size before anything is allocated.
#include "formats/sections/strp.h"

#include <algorithm>
#include <cinttypes>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/mesh/canonical_triangles.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

Status bad_strp(const std::string& detail) {
  return malformed_section(kStrpTag, detail);
}

// Total bits of the stream after the fixed fields.
uint64_t stream_bits(const StrpSummary& s) {
  return uint64_t{s.strip_count} * s.length_bits +
         uint64_t{s.index_count} * static_cast<uint64_t>(bits_for_count(s.vertex_count));
}

Status check_fixed(const StrpSummary& s, size_t size) {
  if (s.strip_count > 0 && s.vertex_count < 3)
    return bad_strp(string_printf("%u strips over %u vertices, a strip needs at least 3",
                                  s.strip_count, s.vertex_count));
  if (uint64_t{s.strip_count} * 3 > s.index_count)
    return bad_strp(string_printf("%u strips need at least %" PRIu64 " indices, the header has %u",
                                  s.strip_count, uint64_t{s.strip_count} * 3, s.index_count));
  // Without strips the index width can be 0 bits (fewer than 3 vertices),
  // so the size check below would not bound the index count: a 13-byte
  // payload could make the decoder reserve 2^32 indices (fuzz_strp_section).
  if (s.strip_count == 0 && s.index_count != 0)
    return bad_strp(string_printf("no strips, the header has %u indices", s.index_count));
  if (s.length_bits > 32) return bad_strp(string_printf("length width %u above 32", s.length_bits));
  const uint64_t bytes = (stream_bits(s) + 7) / 8;
  if (bytes != size - kStrpFixedBytes)
    return bad_strp(string_printf("the counts need %" PRIu64
                                  " bytes after the fixed fields, the payload has %zu",
                                  bytes, size - kStrpFixedBytes));
  return Status::ok();
}

Result<StrpSummary> parse_fixed(const uint8_t* data, size_t size) {
  ByteReader reader(data, size);
  StrpSummary s;
  if (!reader.read(&s.vertex_count) || !reader.read(&s.strip_count) ||
      !reader.read(&s.index_count) || !reader.read(&s.length_bits)) {
    return bad_strp(
        string_printf("payload has %zu bytes, the fixed fields need %zu", size, kStrpFixedBytes));
  }
  LODBAKE_RETURN_IF_ERROR(check_fixed(s, size));
  return s;
}

}  // namespace

void append_strip_triangles(const uint32_t* v, size_t n, std::vector<Triangle>* out) {
  for (size_t i = 0; i + 2 < n; ++i) {
    if (!is_real_triangle(v[i], v[i + 1], v[i + 2])) continue;
    if (i % 2 == 0) {
      out->push_back({v[i], v[i + 1], v[i + 2]});
    } else {
      out->push_back({v[i + 1], v[i], v[i + 2]});
    }
  }
}

std::vector<Triangle> strip_triangles(const TriangleStrips& strips) {
  std::vector<Triangle> triangles;
  for (size_t s = 0; s < strips.strip_count(); ++s)
    append_strip_triangles(strips.indices.data() + strips.first[s], strips.length(s), &triangles);
  return triangles;
}

Result<Bytes> encode_strp(const TriangleStrips& strips) {
  auto cannot = [](const std::string& detail) {
    return invalid_input("cannot encode STRP: " + detail);
  };
  if (strips.first.empty() || strips.first.front() != 0 ||
      strips.first.back() != strips.indices.size())
    return cannot("strip offsets do not cover the indices");
  if (strips.indices.size() > UINT32_MAX || strips.strip_count() > UINT32_MAX)
    return cannot("more than 2^32 - 1 indices");
  if (strips.strip_count() > 0 && strips.vertex_count < 3)
    return cannot("strips over fewer than 3 vertices");
  uint32_t longest = 0;
  for (size_t s = 0; s < strips.strip_count(); ++s) {
    if (strips.first[s + 1] < strips.first[s] + 3)
      return cannot(string_printf("strip %zu has fewer than 3 indices", s));
    longest = std::max<uint32_t>(longest, static_cast<uint32_t>(strips.length(s)));
  }
  for (size_t i = 0; i < strips.indices.size(); ++i) {
    if (strips.indices[i] >= strips.vertex_count)
      return cannot(string_printf("index %zu is %u, the mesh has %u vertices", i, strips.indices[i],
                                  strips.vertex_count));
  }
  try {
    Bytes out;
    ByteWriter writer(&out);
    const uint8_t length_bits =
        static_cast<uint8_t>(strips.strip_count() == 0 ? 0 : bits_for_count(longest - 3 + 1));
    writer.write(strips.vertex_count);
    writer.write(static_cast<uint32_t>(strips.strip_count()));
    writer.write(static_cast<uint32_t>(strips.indices.size()));
    writer.write(length_bits);
    BitWriter bits(&out);
    for (size_t s = 0; s < strips.strip_count(); ++s)
      bits.write(static_cast<uint32_t>(strips.length(s) - 3), length_bits);
    const int index_bits = bits_for_count(strips.vertex_count);
    for (uint32_t index : strips.indices)
      bits.write(index, index_bits);
    bits.finish();
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding STRP");
  }
}

Result<StrpSummary> read_strp_summary(const uint8_t* data, size_t size) {
  return parse_fixed(data, size);
}

Result<TriangleStrips> decode_strp(const uint8_t* data, size_t size, StrpSummary* summary) {
  LODBAKE_ASSIGN_OR_RETURN(StrpSummary s, parse_fixed(data, size));
  if (summary != nullptr) *summary = s;
  try {
    TriangleStrips strips;
    strips.vertex_count = s.vertex_count;
    strips.first.reserve(uint64_t{s.strip_count} + 1);
    strips.indices.reserve(s.index_count);
    BitReader bits(data + kStrpFixedBytes, size - kStrpFixedBytes);
    uint64_t total = 0;
    for (uint32_t i = 0; i < s.strip_count; ++i) {
      uint32_t length = 0;
      bits.read(s.length_bits, &length);  // the size check above guarantees the bits
      total += uint64_t{length} + 3;
      if (total > s.index_count)
        return bad_strp(string_printf("strip %u ends at index %" PRIu64 ", past the %u indices", i,
                                      total, s.index_count));
      strips.first.push_back(static_cast<uint32_t>(total));
    }
    if (total != s.index_count)
      return bad_strp(string_printf(
          "strip lengths add up to %" PRIu64 ", the header has %u indices", total, s.index_count));
    const int index_bits = bits_for_count(s.vertex_count);
    for (uint32_t i = 0; i < s.index_count; ++i) {
      uint32_t index = 0;
      bits.read(index_bits, &index);
      if (index >= s.vertex_count)
        return bad_strp(
            string_printf("index %u is %u, out of range (%u vertices)", i, index, s.vertex_count));
      strips.indices.push_back(index);
    }
    if (!bits.padding_is_zero()) return bad_strp("nonzero padding bits after the indices");
    return strips;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding STRP");
  }
}

std::vector<std::string> compare_strip_triangles(const TriangleStrips& strips,
                                                 const std::vector<Triangle>& triangles,
                                                 const char* what) {
  std::vector<std::string> findings;
  std::vector<Triangle> from_strips = strip_triangles(strips);
  std::vector<Triangle> from_mesh;
  from_mesh.reserve(triangles.size());
  for (const Triangle& t : triangles)
    if (is_real_triangle(t[0], t[1], t[2])) from_mesh.push_back(t);
  sort_canonical_triangles(&from_strips);
  sort_canonical_triangles(&from_mesh);
  std::vector<Triangle> extra, missing;
  std::set_difference(from_strips.begin(), from_strips.end(), from_mesh.begin(), from_mesh.end(),
                      std::back_inserter(extra));
  std::set_difference(from_mesh.begin(), from_mesh.end(), from_strips.begin(), from_strips.end(),
                      std::back_inserter(missing));
  if (!extra.empty())
    findings.push_back(string_printf(
        "%zu strip triangles are not %s triangles (or repeat one), first (%u, %u, %u)",
        extra.size(), what, extra[0][0], extra[0][1], extra[0][2]));
  if (!missing.empty())
    findings.push_back(
        string_printf("%zu %s triangles are missing from the strips, first (%u, %u, %u)",
                      missing.size(), what, missing[0][0], missing[0][1], missing[0][2]));
  return findings;
}

std::vector<std::string> validate_strp(const TriangleStrips& strips, const TriangleMesh& mesh) {
  if (strips.vertex_count != mesh.vertex_count()) {
    return {string_printf("strips index %u vertices, BASE has %zu", strips.vertex_count,
                          mesh.vertex_count())};
  }
  return compare_strip_triangles(strips, mesh.triangles, "BASE");
}

std::vector<std::string> validate_strp_payload(const uint8_t* data, size_t size, bool has_base,
                                               const TriangleMesh* base_mesh) {
  Result<TriangleStrips> strips = decode_strp(data, size);
  if (!strips.is_ok()) return {strips.status().message()};
  if (!has_base) return {"no BASE section holds the vertices the strips index"};
  if (base_mesh == nullptr) return {};
  return validate_strp(strips.value(), *base_mesh);
}

Result<TriangleMesh> mesh_from_strips(const TriangleStrips& strips, const TriangleMesh& mesh) {
  if (strips.vertex_count != mesh.vertex_count())
    return invalid_input(string_printf("the strips index %u vertices, the mesh has %zu",
                                       strips.vertex_count, mesh.vertex_count()));
  TriangleMesh out;
  out.positions = mesh.positions;
  if (mesh.normals.binding == AttributeBinding::kPerVertex) out.normals = mesh.normals;
  if (mesh.texcoords.binding == AttributeBinding::kPerVertex) out.texcoords = mesh.texcoords;
  out.triangles = strip_triangles(strips);
  return out;
}

}  // namespace lodbake
