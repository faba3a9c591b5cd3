// VSPL section codec: the vertex-split records of a progressive mesh (Hoppe
// 1996, "Progressive meshes"), byte layout in docs/format.md "VSPL".
//
// Choices where the brief was open:
// - Structure of arrays: one bit-packed topology stream (vs, vl, vr of every
//   record), then the positions, the errors, the split vertices' normals and
//   texture coordinates, and the permutation. Every part's size follows from
//   the fixed fields, so the layout walk (and the O(1) summary) checks the
//   whole payload size before anything is allocated, and a later byte-level
//   codec sees like values next to each other.
// - Split i happens on a mesh of n = B + i vertices, so vs takes bits(n)
//   bits and each wing bits(n + 1): the value n (which is the new vertex vt
//   itself, never a valid wing) means "no wing" (a boundary edge has only
//   one; the engine records either side missing). That costs one extra bit
//   per wing only when n is a power of two, where a per-record boundary
//   field would cost bits on every record. Both wings missing is malformed.
// - Attributes: a progressive mesh's normals and texture coordinates are
//   per vertex and never change along the LoDs, so BASE holds the base
//   vertices' values and VSPL appends one value per split (the new vertex
//   vt's), float32 like BASE's attribute blocks. Presence must agree between
//   the two sections; join_progressive_mesh() refuses a mismatch rather than
//   inventing values.
// - The base vertex count is stored redundantly (4 bytes): the summary is then
//   self-contained and the reader cross-checks it against BASE instead of
//   trusting the caller.
// - vs positions are stored only when some split moves vs (optimal
//   placement); otherwise the reader takes vs's position before the split,
//   which is why decoding needs the base positions. Errors are float32, exact
//   (collapse costs are not monotone, so no delta coding is assumed).
// - The header's error range must be the records' own (bitwise the first
//   smallest and first largest), so inspect can show it in O(1) and trust it.
// - Readers accept a stored identity permutation and stored vs positions that
//   equal the implied ones; the reference writer omits both.
#include "formats/sections/vspl.h"

#include <cinttypes>
#include <cmath>
#include <cstring>
#include <new>

#include "formats/container/container_errors.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"
#include "formats/support/string_format.h"

namespace lodbake {
namespace {

Status bad_vspl(const std::string& detail) {
  return malformed_section(kVsplTag, detail);
}
Status cannot_encode(const std::string& detail) {
  return invalid_input("cannot encode VSPL: " + detail);
}

// Sum of bits_for_count(n) for n in [lo, hi), one step per run of equal
// widths (at most 34 runs), so sizes are known in O(1).
uint64_t sum_of_widths(uint64_t lo, uint64_t hi) {
  uint64_t total = 0;
  uint64_t n = lo;
  while (n < hi) {
    const int width = bits_for_count(n);
    // bits_for_count is 0 on [0, 2) and w on (2^(w-1), 2^w].
    const uint64_t run_end = width == 0 ? 2 : (uint64_t{1} << width) + 1;
    const uint64_t end = run_end < hi ? run_end : hi;
    total += static_cast<uint64_t>(width) * (end - n);
    n = end;
  }
  return total;
}

// Bits of the topology stream: split i (n = B + i vertices before it) takes
// bits(n) for vs and bits(n + 1) for each of vl and vr.
uint64_t topology_bits(uint64_t base_vertices, uint64_t splits) {
  return sum_of_widths(base_vertices, base_vertices + splits) +
         2 * sum_of_widths(base_vertices + 1, base_vertices + splits + 1);
}

bool stores_vs(const VsplSummary& s) {
  return (s.flags & kVsplStoresVsPositions) != 0;
}
bool stores_permutation(const VsplSummary& s) {
  return (s.flags & kVsplStoresPermutation) != 0;
}
bool stores_normals(const VsplSummary& s) {
  return (s.flags & kVsplStoresNormals) != 0;
}
bool stores_texcoords(const VsplSummary& s) {
  return (s.flags & kVsplStoresTexcoords) != 0;
}

// Where each part of a payload lies; every range was checked against the size.
struct VsplLayout {
  VsplSummary summary;
  size_t topology_offset = 0;
  uint64_t topology_bytes = 0;
  size_t positions_offset = 0;
  uint64_t positions_bytes = 0;
  size_t errors_offset = 0;
  size_t normals_offset = 0;    // when stores_normals()
  size_t texcoords_offset = 0;  // when stores_texcoords()
  size_t permutation_offset = 0;
  uint64_t permutation_bytes = 0;
};

Status need_bytes(ByteReader* reader, uint64_t bytes, const std::string& what, size_t* offset) {
  if (bytes > reader->remaining()) {
    return bad_vspl(string_printf("%s need %" PRIu64 " bytes at offset %zu, only %zu remain",
                                  what.c_str(), bytes, reader->position(), reader->remaining()));
  }
  *offset = reader->position();
  reader->skip(bytes);
  return Status::ok();
}

Status parse_layout(const uint8_t* data, size_t size, VsplLayout* layout) {
  ByteReader reader(data, size);
  VsplSummary& s = layout->summary;
  uint8_t encoding = 0;
  if (!reader.read(&s.split_count) || !reader.read(&s.base_vertex_count) ||
      !reader.read(&encoding) || !reader.read(&s.quantization_bits) || !reader.read(&s.flags) ||
      !reader.read(&s.min_error) || !reader.read(&s.max_error)) {
    return bad_vspl(
        string_printf("payload has %zu bytes, the fixed fields need %zu", size, kVsplFixedBytes));
  }
  if (encoding > 1) {
    return bad_vspl(
        string_printf("position encoding %u is unknown (0 float32, 1 quantized)", encoding));
  }
  s.position_encoding = static_cast<PositionEncoding>(encoding);
  const bool quantized = s.position_encoding == PositionEncoding::kQuantized;
  const uint8_t qbits = s.quantization_bits;
  if (quantized && (qbits < kMinQuantizationBits || qbits > kMaxQuantizationBits)) {
    return bad_vspl(string_printf("quantization bits %u outside 1..30", qbits));
  }
  if (!quantized && qbits != 0) {
    return bad_vspl(string_printf("quantization bits %u with float32 positions, must be 0", qbits));
  }
  if ((s.flags & ~kVsplKnownFlags) != 0) {
    return bad_vspl(string_printf("unknown flag bits 0x%02X", s.flags));
  }
  const uint64_t r = s.split_count;
  const uint64_t b = s.base_vertex_count;
  if (b + r > UINT32_MAX) {
    return bad_vspl(string_printf("%u base vertices and %u splits make %" PRIu64
                                  " vertices, at most 2^32 - 1",
                                  s.base_vertex_count, s.split_count, b + r));
  }
  if (r != 0 && b < 2) {
    return bad_vspl(string_printf("%u splits over a base of %u vertices (a split needs 2)",
                                  s.split_count, s.base_vertex_count));
  }
  if (!std::isfinite(s.min_error) || !std::isfinite(s.max_error) || !(s.min_error <= s.max_error)) {
    return bad_vspl(string_printf("error range [%g, %g] is not finite and ordered",
                                  static_cast<double>(s.min_error),
                                  static_cast<double>(s.max_error)));
  }
  if (quantized) {
    for (float* v : {&s.box_min[0], &s.box_min[1], &s.box_min[2], &s.box_max[0], &s.box_max[1],
                     &s.box_max[2]}) {
      if (!reader.read(v)) return bad_vspl("payload ends inside the quantization box");
    }
    int a = 0;
    if (!is_valid_quantization_box(s.box_min, s.box_max, &a)) {
      return bad_vspl(string_printf("quantization box axis %d [%g, %g] is not finite and ordered",
                                    a, static_cast<double>(s.box_min[a]),
                                    static_cast<double>(s.box_max[a])));
    }
  }

  layout->topology_bytes = (topology_bits(b, r) + 7) / 8;
  LODBAKE_RETURN_IF_ERROR(need_bytes(
      &reader, layout->topology_bytes,
      string_printf("the vertex indices of %u splits", s.split_count), &layout->topology_offset));
  const uint64_t coordinates = 3 * r * (stores_vs(s) ? 2 : 1);
  layout->positions_bytes = quantized ? packed_size_bytes(coordinates, qbits) : 4 * coordinates;
  LODBAKE_RETURN_IF_ERROR(need_bytes(&reader, layout->positions_bytes,
                                     string_printf("the positions of %u splits", s.split_count),
                                     &layout->positions_offset));
  LODBAKE_RETURN_IF_ERROR(need_bytes(&reader, 4 * r,
                                     string_printf("the errors of %u splits", s.split_count),
                                     &layout->errors_offset));
  if (stores_normals(s)) {
    LODBAKE_RETURN_IF_ERROR(need_bytes(&reader, 12 * r,
                                       string_printf("the normals of %u splits", s.split_count),
                                       &layout->normals_offset));
  }
  if (stores_texcoords(s)) {
    LODBAKE_RETURN_IF_ERROR(need_bytes(
        &reader, 8 * r, string_printf("the texture coordinates of %u splits", s.split_count),
        &layout->texcoords_offset));
  }
  if (stores_permutation(s)) {
    const uint64_t full = b + r;
    layout->permutation_bytes = packed_size_bytes(full, bits_for_count(full));
    LODBAKE_RETURN_IF_ERROR(
        need_bytes(&reader, layout->permutation_bytes,
                   string_printf("the permutation entries of %" PRIu64 " vertices", full),
                   &layout->permutation_offset));
  }
  if (!reader.at_end()) {
    return bad_vspl(string_printf("%zu trailing bytes after the last field (offset %zu)",
                                  reader.remaining(), reader.position()));
  }
  return Status::ok();
}

std::string wing_text(uint32_t wing) {
  return wing == kNoVertex ? std::string("none") : std::to_string(wing);
}

Status decode_topology(const uint8_t* data, const VsplLayout& layout,
                       std::vector<VertexSplit>* splits) {
  BitReader in(data + layout.topology_offset, static_cast<size_t>(layout.topology_bytes));
  const uint32_t base = layout.summary.base_vertex_count;
  for (size_t i = 0; i < splits->size(); ++i) {
    const uint32_t n = base + static_cast<uint32_t>(i);
    const int wing_width = bits_for_count(uint64_t{n} + 1);
    VertexSplit& split = (*splits)[i];
    if (!in.read(bits_for_count(n), &split.vs) || !in.read(wing_width, &split.vl) ||
        !in.read(wing_width, &split.vr)) {
      return bad_vspl("vertex index stream too short");
    }
    if (split.vs >= n || split.vl > n || split.vr > n) {
      return bad_vspl(string_printf(
          "split %zu (vs %u, vl %u, vr %u) has an index out of range (%u vertices before it, "
          "a wing of %u means none)",
          i, split.vs, split.vl, split.vr, n, n));
    }
    if (split.vl == n && split.vr == n) {
      return bad_vspl(string_printf(
          "split %zu (vs %u) has neither wing (vl and vr are both %u, none)", i, split.vs, n));
    }
    if (split.vl == n) split.vl = kNoVertex;
    if (split.vr == n) split.vr = kNoVertex;
    if (split.vl == split.vs || split.vr == split.vs || split.vr == split.vl) {
      return bad_vspl(string_printf("split %zu (vs %u, vl %s, vr %s) repeats a vertex", i, split.vs,
                                    wing_text(split.vl).c_str(), wing_text(split.vr).c_str()));
    }
  }
  if (!in.padding_is_zero()) return bad_vspl("nonzero padding bits after the vertex indices");
  return Status::ok();
}

Status decode_positions(const uint8_t* data, const VsplLayout& layout,
                        std::vector<VertexSplit>* splits) {
  const VsplSummary& s = layout.summary;
  const uint8_t* bytes = data + layout.positions_offset;
  BitReader bits_in(bytes, static_cast<size_t>(layout.positions_bytes));
  const uint32_t steps = s.position_encoding == PositionEncoding::kQuantized
                             ? quantization_steps(s.quantization_bits)
                             : 0;
  size_t float_index = 0;
  auto read_position = [&](size_t i, const char* which, Vec3f* p) -> Status {
    for (int a = 0; a < 3; ++a) {
      if (s.position_encoding == PositionEncoding::kFloat32) {
        std::memcpy(&(*p)[a], bytes + 4 * float_index++, 4);
        if (!std::isfinite((*p)[a])) {
          return bad_vspl(
              string_printf("split %zu: %s position coordinate %d is not finite", i, which, a));
        }
      } else {
        uint32_t q = 0;
        if (!bits_in.read(s.quantization_bits, &q)) return bad_vspl("position stream too short");
        (*p)[a] = dequantize_coordinate(q, s.box_min[a], s.box_max[a], steps);
      }
    }
    return Status::ok();
  };
  for (size_t i = 0; i < splits->size(); ++i) {
    VertexSplit& split = (*splits)[i];
    LODBAKE_RETURN_IF_ERROR(read_position(i, "vt", &split.vt_position));
    if (stores_vs(s)) LODBAKE_RETURN_IF_ERROR(read_position(i, "vs", &split.vs_position));
  }
  if (!bits_in.padding_is_zero()) return bad_vspl("nonzero padding bits after the positions");
  return Status::ok();
}

// The first smallest and first largest error, as the header must hold them.
void error_range(const std::vector<VertexSplit>& splits, float* lo, float* hi) {
  *lo = 0;
  *hi = 0;
  if (splits.empty()) return;
  *lo = splits[0].error;
  *hi = splits[0].error;
  for (const VertexSplit& split : splits) {
    if (split.error < *lo) *lo = split.error;
    if (split.error > *hi) *hi = split.error;
  }
}

// Bitwise equality: tells -0 from +0, which == does not.
bool same_bits(float a, float b) {
  uint32_t x = 0;
  uint32_t y = 0;
  std::memcpy(&x, &a, sizeof(float));
  std::memcpy(&y, &b, sizeof(float));
  return x == y;
}

Status decode_errors(const uint8_t* data, const VsplLayout& layout,
                     std::vector<VertexSplit>* splits) {
  const uint8_t* bytes = data + layout.errors_offset;
  for (size_t i = 0; i < splits->size(); ++i) {
    float& error = (*splits)[i].error;
    std::memcpy(&error, bytes + 4 * i, 4);
    if (!std::isfinite(error)) return bad_vspl(string_printf("split %zu: error is not finite", i));
  }
  float lo = 0;
  float hi = 0;
  error_range(*splits, &lo, &hi);
  const VsplSummary& s = layout.summary;
  if (!same_bits(lo, s.min_error) || !same_bits(hi, s.max_error)) {
    return bad_vspl(string_printf("error range [%g, %g] in the header, the splits' is [%g, %g]",
                                  static_cast<double>(s.min_error),
                                  static_cast<double>(s.max_error), static_cast<double>(lo),
                                  static_cast<double>(hi)));
  }
  return Status::ok();
}

// The split vertices' values of one attribute: `components` float32 per
// split, all finite (as in BASE's attribute blocks).
Status decode_split_attribute(const uint8_t* bytes, uint32_t splits, int components,
                              const char* what, std::vector<float>* values) {
  values->resize(size_t{splits} * static_cast<size_t>(components));
  for (size_t k = 0; k < values->size(); ++k) {
    std::memcpy(&(*values)[k], bytes + 4 * k, 4);
    if (!std::isfinite((*values)[k])) {
      return bad_vspl(string_printf("split %zu: %s component %zu is not finite",
                                    k / static_cast<size_t>(components), what,
                                    k % static_cast<size_t>(components)));
    }
  }
  return Status::ok();
}

Status decode_permutation(const uint8_t* data, const VsplLayout& layout,
                          std::vector<uint32_t>* input_vertex) {
  const uint64_t full = layout.summary.full_vertex_count();
  input_vertex->resize(static_cast<size_t>(full));
  if (!stores_permutation(layout.summary)) {
    for (size_t v = 0; v < input_vertex->size(); ++v)
      (*input_vertex)[v] = static_cast<uint32_t>(v);
    return Status::ok();
  }
  BitReader in(data + layout.permutation_offset, static_cast<size_t>(layout.permutation_bytes));
  const int width = bits_for_count(full);
  std::vector<bool> seen(static_cast<size_t>(full), false);
  for (size_t v = 0; v < input_vertex->size(); ++v) {
    uint32_t value = 0;
    if (!in.read(width, &value)) return bad_vspl("input permutation stream too short");
    if (value >= full) {
      return bad_vspl(string_printf(
          "input permutation maps PM vertex %zu to %u, out of range (%" PRIu64 " vertices)", v,
          value, full));
    }
    if (seen[value]) {
      return bad_vspl(string_printf(
          "input permutation maps PM vertex %zu to input vertex %u a second time", v, value));
    }
    seen[value] = true;
    (*input_vertex)[v] = value;
  }
  if (!in.padding_is_zero()) return bad_vspl("nonzero padding bits after the input permutation");
  return Status::ok();
}

// Storability problems of a PM's records; all of them when `all`, else stops
// at the first.
void structural_problems(size_t base_vertices, const std::vector<VertexSplit>& splits,
                         const std::vector<uint32_t>& input_vertex, bool all,
                         std::vector<std::string>* out) {
  const size_t r = splits.size();
  const uint64_t full = uint64_t{base_vertices} + r;
  if (full > UINT32_MAX) {
    out->push_back(string_printf("%" PRIu64 " vertices after all splits, at most 2^32 - 1", full));
    if (!all) return;
  }
  if (r != 0 && base_vertices < 2) {
    out->push_back(string_printf("%zu splits over a base of %zu vertices (a split needs 2)", r,
                                 base_vertices));
    if (!all) return;
  }
  size_t out_of_range = 0, first_out_of_range = 0;
  size_t wingless = 0, first_wingless = 0;
  size_t repeated = 0, first_repeated = 0;
  size_t bad_position = 0, first_bad_position = 0;
  size_t bad_error = 0, first_bad_error = 0;
  auto finite = [](const Vec3f& p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  };
  for (size_t i = 0; i < r; ++i) {
    const VertexSplit& s = splits[i];
    const uint64_t n = uint64_t{base_vertices} + i;
    if (s.vs >= n || (s.vl != kNoVertex && s.vl >= n) || (s.vr != kNoVertex && s.vr >= n)) {
      if (out_of_range++ == 0) first_out_of_range = i;
    } else if (s.vl == kNoVertex && s.vr == kNoVertex) {
      if (wingless++ == 0) first_wingless = i;
    } else if (s.vl == s.vs || s.vr == s.vs || s.vr == s.vl) {
      if (repeated++ == 0) first_repeated = i;
    }
    if (!finite(s.vt_position) || !finite(s.vs_position)) {
      if (bad_position++ == 0) first_bad_position = i;
    }
    if (!std::isfinite(s.error)) {
      if (bad_error++ == 0) first_bad_error = i;
    }
  }
  auto describe = [&](size_t i) {
    const VertexSplit& s = splits[i];
    return string_printf("split %zu (vs %u, vl %s, vr %s)", i, s.vs, wing_text(s.vl).c_str(),
                         wing_text(s.vr).c_str());
  };
  if (out_of_range != 0) {
    out->push_back(
        string_printf("%zu splits have a vertex index out of range, first: %s with %" PRIu64
                      " vertices before it",
                      out_of_range, describe(first_out_of_range).c_str(),
                      uint64_t{base_vertices} + first_out_of_range));
    if (!all) return;
  }
  if (wingless != 0) {
    out->push_back(string_printf("%zu splits have neither wing, first: %s", wingless,
                                 describe(first_wingless).c_str()));
    if (!all) return;
  }
  if (repeated != 0) {
    out->push_back(string_printf("%zu splits repeat a vertex, first: %s", repeated,
                                 describe(first_repeated).c_str()));
    if (!all) return;
  }
  if (bad_position != 0) {
    out->push_back(string_printf("%zu splits have a non-finite position, first: split %zu",
                                 bad_position, first_bad_position));
    if (!all) return;
  }
  if (bad_error != 0) {
    out->push_back(string_printf("%zu splits have a non-finite error, first: split %zu", bad_error,
                                 first_bad_error));
    if (!all) return;
  }
  if (input_vertex.size() != full) {
    out->push_back(string_printf("input_vertex has %zu entries for %" PRIu64 " vertices",
                                 input_vertex.size(), full));
    return;
  }
  // first_owner[x]: the first PM vertex mapped to input vertex x, or kNoVertex.
  std::vector<uint32_t> first_owner(input_vertex.size(), kNoVertex);
  size_t bad_range = 0, first_bad_range = 0;
  size_t twice = 0, first_twice = 0;
  for (size_t v = 0; v < input_vertex.size(); ++v) {
    const uint32_t x = input_vertex[v];
    if (x >= full) {
      if (bad_range++ == 0) first_bad_range = v;
    } else if (first_owner[x] != kNoVertex) {
      if (twice++ == 0) first_twice = v;
    } else {
      first_owner[x] = static_cast<uint32_t>(v);
    }
  }
  if (bad_range != 0) {
    out->push_back(string_printf("%zu input_vertex entries out of range (%" PRIu64
                                 " vertices), first: PM vertex %zu -> %u",
                                 bad_range, full, first_bad_range, input_vertex[first_bad_range]));
    if (!all) return;
  }
  if (twice != 0) {
    const uint32_t x = input_vertex[first_twice];
    out->push_back(string_printf(
        "input_vertex is not a permutation: %zu repeated entries, first: input vertex %u for PM "
        "vertices %u and %zu",
        twice, x, first_owner[x], first_twice));
  }
}

// Storability problems of one of a PM's attributes (`what`: "normals" or
// "texture coordinates", `components` 3 or 2): all of them when `all`.
void attribute_problems(const MeshAttribute& attr, const MeshAttribute& base_attr, const char* what,
                        uint32_t components, size_t base_vertices, size_t full_vertices, bool all,
                        std::vector<std::string>* out) {
  if (!attr.present()) {
    if (base_attr.present()) {
      out->push_back(string_printf(
          "the base mesh has %s but the progressive mesh has none for its %zu vertices", what,
          full_vertices));
    }
    return;
  }
  if (attr.binding != AttributeBinding::kPerVertex || attr.components != components ||
      attr.values.size() != full_vertices * components) {
    out->push_back(string_printf(
        "%s must be per-vertex with %u components for each of the %zu vertices, they are %s "
        "with %u components and %zu floats",
        what, components, full_vertices,
        attr.binding == AttributeBinding::kPerVertex ? "per-vertex" : "per-corner", attr.components,
        attr.values.size()));
    return;
  }
  size_t non_finite = 0, first_non_finite = 0;
  for (size_t k = 0; k < attr.values.size(); ++k) {
    if (!std::isfinite(attr.values[k]) && non_finite++ == 0) first_non_finite = k / components;
  }
  if (non_finite != 0) {
    out->push_back(string_printf("%s: %zu non-finite values, first: vertex %zu", what, non_finite,
                                 first_non_finite));
    if (!all) return;
  }
  // BASE stores the base vertices' values: they must be the PM's first ones,
  // bit for bit, or the decoded PM would differ from this one.
  const size_t base_floats = base_vertices * components;
  if (base_attr.binding != AttributeBinding::kPerVertex || base_attr.components != components ||
      base_attr.values.size() != base_floats) {
    out->push_back(
        string_printf("the progressive mesh has %s but the base mesh does not have "
                      "them per-vertex for its %zu vertices",
                      what, base_vertices));
    return;
  }
  for (size_t k = 0; k < base_floats; ++k) {
    if (!same_bits(base_attr.values[k], attr.values[k])) {
      out->push_back(string_printf(
          "the base mesh's %s differ from the progressive mesh's, first at vertex %zu", what,
          k / components));
      return;
    }
  }
}

void all_attribute_problems(const ProgressiveMesh& pm, bool all, std::vector<std::string>* out) {
  const size_t before = out->size();
  attribute_problems(pm.normals, pm.base.normals, "normals", 3, pm.base.vertex_count(),
                     pm.full_vertex_count(), all, out);
  if (!all && out->size() != before) return;
  attribute_problems(pm.texcoords, pm.base.texcoords, "texture coordinates", 2,
                     pm.base.vertex_count(), pm.full_vertex_count(), all, out);
}

// vs's position before split i when no vertex ever moves.
const Vec3f& initial_position(const std::vector<Vec3f>& base_positions,
                              const std::vector<VertexSplit>& splits, uint32_t v) {
  return v < base_positions.size() ? base_positions[v]
                                   : splits[v - base_positions.size()].vt_position;
}

bool same_position(const Vec3f& a, const Vec3f& b) {
  return same_bits(a[0], b[0]) && same_bits(a[1], b[1]) && same_bits(a[2], b[2]);
}

}  // namespace

Result<Bytes> encode_vspl(const ProgressiveMesh& pm, const VsplEncodeOptions& options) {
  if (options.quantize &&
      (options.bits < kMinQuantizationBits || options.bits > kMaxQuantizationBits)) {
    return cannot_encode(string_printf("quantization bits %d outside 1..30", options.bits));
  }
  try {
    std::vector<std::string> problems;
    structural_problems(pm.base.vertex_count(), pm.splits, pm.input_vertex, false, &problems);
    if (problems.empty()) all_attribute_problems(pm, false, &problems);
    if (!problems.empty()) return cannot_encode(problems.front());

    const uint32_t b = static_cast<uint32_t>(pm.base.vertex_count());
    const uint32_t r = static_cast<uint32_t>(pm.splits.size());
    uint8_t flags = 0;
    for (const VertexSplit& split : pm.splits) {
      if (!same_position(split.vs_position,
                         initial_position(pm.base.positions, pm.splits, split.vs))) {
        flags |= kVsplStoresVsPositions;
        break;
      }
    }
    for (size_t v = 0; v < pm.input_vertex.size(); ++v) {
      if (pm.input_vertex[v] != v) {
        flags |= kVsplStoresPermutation;
        break;
      }
    }
    if (pm.normals.present()) flags |= kVsplStoresNormals;
    if (pm.texcoords.present()) flags |= kVsplStoresTexcoords;
    const bool with_vs = (flags & kVsplStoresVsPositions) != 0;
    std::vector<Vec3f> stored;
    stored.reserve(size_t{r} * (with_vs ? 2 : 1));
    for (const VertexSplit& split : pm.splits) {
      stored.push_back(split.vt_position);
      if (with_vs) stored.push_back(split.vs_position);
    }
    float min_error = 0;
    float max_error = 0;
    error_range(pm.splits, &min_error, &max_error);

    Bytes out;
    ByteWriter writer(&out);
    writer.write(r);
    writer.write(b);
    writer.write(static_cast<uint8_t>(options.quantize ? PositionEncoding::kQuantized
                                                       : PositionEncoding::kFloat32));
    writer.write(static_cast<uint8_t>(options.quantize ? options.bits : 0));
    writer.write(flags);
    writer.write(min_error);
    writer.write(max_error);

    Vec3f lo{};
    Vec3f hi{};
    if (options.quantize) {
      bounding_box(stored, &lo, &hi);
      for (float f : lo)
        writer.write(f);
      for (float f : hi)
        writer.write(f);
    }

    BitWriter topology(&out);
    for (uint32_t i = 0; i < r; ++i) {
      const VertexSplit& split = pm.splits[i];
      const uint32_t n = b + i;
      const int wing_width = bits_for_count(uint64_t{n} + 1);
      topology.write(split.vs, bits_for_count(n));
      topology.write(split.vl == kNoVertex ? n : split.vl, wing_width);
      topology.write(split.vr == kNoVertex ? n : split.vr, wing_width);
    }
    topology.finish();

    if (options.quantize) {
      const uint32_t steps = quantization_steps(options.bits);
      BitWriter positions(&out);
      for (const Vec3f& p : stored) {
        for (int a = 0; a < 3; ++a)
          positions.write(quantize_coordinate(p[a], lo[a], hi[a], steps), options.bits);
      }
      positions.finish();
    } else {
      for (const Vec3f& p : stored) {
        for (float f : p)
          writer.write(f);
      }
    }
    for (const VertexSplit& split : pm.splits)
      writer.write(split.error);
    // The split vertices' values follow the base vertices' (which BASE holds).
    for (const MeshAttribute* attr : {&pm.normals, &pm.texcoords}) {
      if (!attr->present()) continue;
      for (size_t k = size_t{b} * attr->components; k < attr->values.size(); ++k)
        writer.write(attr->values[k]);
    }

    if ((flags & kVsplStoresPermutation) != 0) {
      const int width = bits_for_count(pm.input_vertex.size());
      BitWriter permutation(&out);
      for (uint32_t x : pm.input_vertex)
        permutation.write(x, width);
      permutation.finish();
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while encoding VSPL");
  }
}

Result<VsplSection> decode_vspl(const uint8_t* data, size_t size,
                                const std::vector<Vec3f>& base_positions, VsplSummary* summary) {
  try {
    VsplLayout layout;
    LODBAKE_RETURN_IF_ERROR(parse_layout(data, size, &layout));
    const VsplSummary& s = layout.summary;
    if (s.base_vertex_count != base_positions.size()) {
      return bad_vspl(string_printf("base vertex count %u, but the base mesh has %zu vertices",
                                    s.base_vertex_count, base_positions.size()));
    }
    VsplSection section;
    section.summary = s;
    section.splits.resize(s.split_count);
    LODBAKE_RETURN_IF_ERROR(decode_topology(data, layout, &section.splits));
    LODBAKE_RETURN_IF_ERROR(decode_positions(data, layout, &section.splits));
    LODBAKE_RETURN_IF_ERROR(decode_errors(data, layout, &section.splits));
    if (stores_normals(s)) {
      LODBAKE_RETURN_IF_ERROR(decode_split_attribute(data + layout.normals_offset, s.split_count, 3,
                                                     "normal", &section.split_normals));
    }
    if (stores_texcoords(s)) {
      LODBAKE_RETURN_IF_ERROR(decode_split_attribute(data + layout.texcoords_offset, s.split_count,
                                                     2, "texture coordinate",
                                                     &section.split_texcoords));
    }
    LODBAKE_RETURN_IF_ERROR(decode_permutation(data, layout, &section.input_vertex));
    if (!stores_vs(s)) {
      for (VertexSplit& split : section.splits)
        split.vs_position = initial_position(base_positions, section.splits, split.vs);
    }
    if (summary != nullptr) *summary = s;
    return section;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding VSPL");
  }
}

Result<VsplSummary> read_vspl_summary(const uint8_t* data, size_t size) {
  VsplLayout layout;
  LODBAKE_RETURN_IF_ERROR(parse_layout(data, size, &layout));
  return layout.summary;
}

Result<VsplParts> locate_vspl_parts(const uint8_t* data, size_t size) {
  VsplLayout layout;
  LODBAKE_RETURN_IF_ERROR(parse_layout(data, size, &layout));
  VsplParts parts;
  parts.summary = layout.summary;
  parts.topology_offset = layout.topology_offset;
  parts.topology_bytes = static_cast<size_t>(layout.topology_bytes);
  parts.positions_offset = layout.positions_offset;
  parts.positions_bytes = static_cast<size_t>(layout.positions_bytes);
  parts.errors_offset = layout.errors_offset;
  parts.tail_offset = layout.errors_offset + size_t{4} * layout.summary.split_count;
  return parts;
}

Result<Bytes> round_vspl_errors(const uint8_t* data, size_t size, int significant_bits) {
  if (significant_bits < kMinSignificantBits || significant_bits > kMaxSignificantBits) {
    return invalid_input(string_printf("error bits %d outside %d..%d", significant_bits,
                                       kMinSignificantBits, kMaxSignificantBits));
  }
  LODBAKE_ASSIGN_OR_RETURN(VsplParts parts, locate_vspl_parts(data, size));
  Bytes out(data, data + size);
  auto round_at = [&](size_t offset) {
    float value = 0;
    std::memcpy(&value, out.data() + offset, 4);
    value = round_up_to_significant_bits(value, significant_bits);
    std::memcpy(out.data() + offset, &value, 4);
  };
  // Rounding is monotone, so the rounded range is the rounded records' range.
  round_at(kVsplErrorRangeOffset);
  round_at(kVsplErrorRangeOffset + 4);
  for (uint32_t i = 0; i < parts.summary.split_count; ++i)
    round_at(parts.errors_offset + size_t{4} * i);
  return out;
}

namespace {

// One attribute of the joined PM: BASE's per-vertex values, then the split
// vertices' from VSPL.
Status join_attribute(const MeshAttribute& base_attr, size_t base_vertices, bool stored,
                      const std::vector<float>& split_values, const char* what, uint32_t components,
                      MeshAttribute* out) {
  if (!stored) {
    if (base_attr.present()) {
      return bad_vspl(
          string_printf("BASE has %s but VSPL does not store those of the split vertices", what));
    }
    return Status::ok();
  }
  if (!base_attr.present()) {
    return bad_vspl(string_printf(
        "VSPL stores the split vertices' %s but BASE has none for its vertices", what));
  }
  if (base_attr.binding != AttributeBinding::kPerVertex) {
    return bad_vspl(string_printf(
        "VSPL stores the split vertices' %s but BASE's are per corner, a progressive mesh needs "
        "them per vertex",
        what));
  }
  if (base_attr.components != components || base_attr.values.size() != base_vertices * components) {
    return bad_vspl(string_printf(
        "BASE's %s have %u components and %zu floats, expected %u for each of %zu vertices", what,
        base_attr.components, base_attr.values.size(), components, base_vertices));
  }
  out->binding = AttributeBinding::kPerVertex;
  out->components = components;
  out->values.reserve(base_attr.values.size() + split_values.size());
  out->values.insert(out->values.end(), base_attr.values.begin(), base_attr.values.end());
  out->values.insert(out->values.end(), split_values.begin(), split_values.end());
  return Status::ok();
}

}  // namespace

Result<ProgressiveMesh> join_progressive_mesh(TriangleMesh base, VsplSection section) {
  try {
    const VsplSummary& s = section.summary;
    if (s.base_vertex_count != base.vertex_count()) {
      return bad_vspl(string_printf("base vertex count %u, but the base mesh has %zu vertices",
                                    s.base_vertex_count, base.vertex_count()));
    }
    if (section.splits.size() != s.split_count ||
        section.input_vertex.size() != s.full_vertex_count() ||
        section.split_normals.size() != (stores_normals(s) ? 3 * section.splits.size() : 0) ||
        section.split_texcoords.size() != (stores_texcoords(s) ? 2 * section.splits.size() : 0)) {
      return bad_vspl("the decoded section's arrays disagree with its summary");
    }
    ProgressiveMesh pm;
    const size_t n0 = base.vertex_count();
    LODBAKE_RETURN_IF_ERROR(join_attribute(base.normals, n0, stores_normals(s),
                                           section.split_normals, "normals", 3, &pm.normals));
    LODBAKE_RETURN_IF_ERROR(join_attribute(base.texcoords, n0, stores_texcoords(s),
                                           section.split_texcoords, "texture coordinates", 2,
                                           &pm.texcoords));
    pm.base = std::move(base);
    pm.splits = std::move(section.splits);
    pm.input_vertex = std::move(section.input_vertex);
    return pm;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while joining a progressive mesh");
  }
}

Result<ProgressiveMesh> decode_progressive_mesh(const uint8_t* base_data, size_t base_size,
                                                const uint8_t* vspl_data, size_t vspl_size) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(TriangleMesh base, decode_base(base_data, base_size));
    LODBAKE_ASSIGN_OR_RETURN(VsplSection section,
                             decode_vspl(vspl_data, vspl_size, base.positions));
    return join_progressive_mesh(std::move(base), std::move(section));
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decoding a progressive mesh");
  }
}

std::vector<std::string> validate_vspl(const ProgressiveMesh& pm) {
  std::vector<std::string> findings;
  try {
    structural_problems(pm.base.vertex_count(), pm.splits, pm.input_vertex, true, &findings);
    all_attribute_problems(pm, true, &findings);
  } catch (const std::bad_alloc&) {
    findings.push_back("out of memory while validating VSPL");
  }
  return findings;
}

std::vector<std::string> validate_vspl_payload(const uint8_t* data, size_t size,
                                               const std::vector<Vec3f>& base_positions) {
  Result<VsplSection> section = decode_vspl(data, size, base_positions);
  if (!section.is_ok()) return {section.status().message()};
  std::vector<std::string> findings;
  try {
    structural_problems(base_positions.size(), section.value().splits, section.value().input_vertex,
                        true, &findings);
  } catch (const std::bad_alloc&) {
    findings.push_back("out of memory while validating VSPL");
  }
  return findings;
}

uint64_t full_triangle_count(uint64_t base_triangles, const std::vector<VertexSplit>& splits) {
  uint64_t total = base_triangles;
  for (const VertexSplit& split : splits)
    total += uint64_t{split.vl != kNoVertex} + uint64_t{split.vr != kNoVertex};
  return total;
}

}  // namespace lodbake
