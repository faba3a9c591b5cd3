// The STRP section: triangle strips over a mesh's vertices (the strips of
// lib/strips/stripify.h), stored on their own by `lodbake-strips
// --strips-only` next to the BASE mesh whose vertices they index. Byte
// layout: docs/format.md "STRP".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// Triangle strips in the usual sequential form: in strip s, every window of
/// three consecutive indices (i, i+1, i+2) is a triangle, counter-clockwise
/// as (v[i], v[i+1], v[i+2]) when i is even and as (v[i+1], v[i], v[i+2])
/// when i is odd; a window repeating a vertex is degenerate (a swap or a
/// leftover of simplification) and describes nothing.
struct TriangleStrips {
  uint32_t vertex_count = 0;       ///< indices are < vertex_count
  std::vector<uint32_t> indices;   ///< every strip's indices, one after the other
  std::vector<uint32_t> first{0};  ///< strip s is indices[first[s], first[s+1])

  size_t strip_count() const { return first.empty() ? 0 : first.size() - 1; }
  size_t length(size_t s) const { return first[s + 1] - first[s]; }
  bool operator==(const TriangleStrips& o) const {
    return vertex_count == o.vertex_count && indices == o.indices && first == o.first;
  }
};

/// True when (a, b, c) are three different vertices.
inline bool is_real_triangle(uint32_t a, uint32_t b, uint32_t c) {
  return a != b && b != c && a != c;
}

/// Appends the non-degenerate triangles of the sequence `v[0..n)`, each in
/// its counter-clockwise order (the window parity rule above).
void append_strip_triangles(const uint32_t* v, size_t n, std::vector<Triangle>* out);

/// Every strip's non-degenerate triangles, strip by strip.
std::vector<Triangle> strip_triangles(const TriangleStrips& strips);

/// The fixed fields of a STRP payload.
struct StrpSummary {
  uint32_t vertex_count = 0;
  uint32_t strip_count = 0;
  uint32_t index_count = 0;
  uint8_t length_bits = 0;  ///< width of each stored strip length minus 3
};

/// The bytes before the bit-packed lengths and indices.
inline constexpr size_t kStrpFixedBytes = 13;

/// Encodes `strips`. Deterministic.
/// \return kInvalidInput ("cannot encode STRP: ...") when a strip is shorter
///         than 3 indices, an index is out of range, offsets are not
///         increasing, or there are strips over fewer than 3 vertices.
Result<Bytes> encode_strp(const TriangleStrips& strips);

/// Decodes a STRP payload. Counts are checked against the bytes that remain
/// before anything is allocated.
/// \return the strips, or LBK-E023 "section STRP: ..." (kInvalidInput) for
///         any deviation from the layout: counts that do not fit the payload,
///         strips over fewer than 3 vertices, a strip shorter than 3, lengths
///         that do not add up to the index count, an index out of range,
///         nonzero padding bits, trailing bytes. Never throws.
Result<TriangleStrips> decode_strp(const uint8_t* data, size_t size,
                                   StrpSummary* summary = nullptr);

/// The fixed fields, with the payload size they imply checked: O(1).
Result<StrpSummary> read_strp_summary(const uint8_t* data, size_t size);

/// The strips' non-degenerate triangles against the non-degenerate ones of
/// `triangles`, each with its orientation (a triangle may start at any
/// corner), as multisets: what validate_strp() checks against BASE and
/// lib/strips checks a recovered LoD with against its progressive mesh.
/// `what` names the triangles' source in the findings ("BASE", "PM").
/// \return one line per kind of difference (strip triangles that are not
///         in `triangles` or repeat one; triangles missing from the strips),
///         each with its count and first instance; empty when they agree.
std::vector<std::string> compare_strip_triangles(const TriangleStrips& strips,
                                                 const std::vector<Triangle>& triangles,
                                                 const char* what);

/// Deep check (for `lodbake-inspect --validate`) of decoded strips against
/// the mesh they index: the vertex counts agree, and each non-degenerate
/// triangle of the strips is a triangle of `mesh` with its orientation, each
/// of the mesh's non-degenerate triangles described exactly once
/// (compare_strip_triangles()). One line per kind of problem; empty when all
/// is well.
std::vector<std::string> validate_strp(const TriangleStrips& strips, const TriangleMesh& mesh);

/// decode_strp() then validate_strp() against BASE's mesh: a decode error
/// is the single finding; without a BASE section, that is the finding;
/// with an undecodable BASE (`base_mesh` null) only the decode is checked.
std::vector<std::string> validate_strp_payload(const uint8_t* data, size_t size, bool has_base,
                                               const TriangleMesh* base_mesh);

/// `mesh` with its triangles replaced by the strips' non-degenerate ones
/// (positions and per-vertex attributes kept; per-corner attributes, which
/// belong to the old triangles, dropped): what `lodbake-inspect --extract`
/// writes for a container with STRP.
/// \return kInvalidInput when the strips' vertex count is not the mesh's.
Result<TriangleMesh> mesh_from_strips(const TriangleStrips& strips, const TriangleMesh& mesh);

}  // namespace lodbake
