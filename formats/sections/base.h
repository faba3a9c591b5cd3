// The BASE section: an indexed triangle mesh (positions as float32 or
// quantized, bit-packed triangle indices, optional normals and texture
// coordinates per vertex or per corner). Byte layout: docs/format.md "BASE".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/quantization.h"
#include "formats/support/status.h"

namespace lodbake {

inline constexpr uint8_t kBaseHasNormals = 0x01;    ///< attribute mask bit 0
inline constexpr uint8_t kBaseHasTexcoords = 0x02;  ///< attribute mask bit 1

struct BaseEncodeOptions {
  bool quantize = false;  ///< false: float32 positions (exact round trip)
  int bits = 16;          ///< bits per coordinate when quantizing, 1..30
};

/// The fixed fields of a BASE payload and its attribute headers: what
/// inspect shows without decoding the mesh.
struct BaseSummary {
  uint32_t vertex_count = 0;
  uint32_t triangle_count = 0;
  PositionEncoding position_encoding = PositionEncoding::kFloat32;
  uint8_t quantization_bits = 0;  ///< 0 for float32
  uint8_t index_bits = 0;         ///< bits_for_count(vertex_count)
  uint8_t attribute_mask = 0;     ///< kBaseHasNormals | kBaseHasTexcoords
  Vec3f box_min{};                ///< dequantization box (quantized only)
  Vec3f box_max{};
  AttributeBinding normals_binding = AttributeBinding::kNone;
  uint32_t normals_count = 0;  ///< normal values stored
  AttributeBinding texcoords_binding = AttributeBinding::kNone;
  uint32_t texcoords_count = 0;  ///< texture coordinate values stored
};

/// Encodes `mesh` as a BASE payload. Deterministic: the bytes depend only on
/// the mesh and the options. With quantize, the box is the positions'
/// bounding box and each coordinate becomes
///   q = floor((p - min) / (max - min) * (2^bits - 1) + 0.5)   (0 when max == min)
/// computed in IEEE double (formats/support/quantization.h).
/// \return kInvalidInput ("cannot encode BASE: ...") when the mesh is not
///         storable: more than 2^32 - 1 vertices or triangles, triangles over
///         fewer than 2 vertices, an index out of range, a non-finite position
///         or attribute value, an attribute whose shape disagrees with its
///         binding (components 3 for normals and 2 for texture coordinates,
///         per-vertex count == vertex count, per-corner one corner triple per
///         triangle with values in range), or bits outside 1..30 when quantizing;
///         kRuntime when memory runs out.
Result<Bytes> encode_base(const TriangleMesh& mesh, const BaseEncodeOptions& options);

/// Decodes a BASE payload. Every count is checked against the bytes that
/// remain before anything is allocated, so memory stays proportional to
/// `size` for any input (one bit-packed bit can become at most 4 bytes of a
/// mesh array, and per-corner attributes reuse the triangles' count).
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return the mesh (float32 positions exact; quantized ones dequantized as
///         docs/format.md specifies), and its fixed fields in `*summary` when
///         `summary` is not null; or LBK-E023 "section BASE: ..." (kInvalidInput)
///         for any deviation from the layout: unknown encoding or attribute bits,
///         bits out of range, index_bits not bits_for_count(vertex_count),
///         triangles with fewer than 2 vertices, a non-finite or inverted box,
///         counts needing more bytes than remain, an index or corner out of
///         range, a non-finite float, nonzero padding bits, trailing bytes.
///         Never throws.
Result<TriangleMesh> decode_base(const uint8_t* data, size_t size, BaseSummary* summary = nullptr);

/// Reads only the fixed fields and attribute headers, skipping the arrays:
/// O(1) time and memory. Checks the same layout constraints as decode_base()
/// except what needs the array contents (index ranges, floats, padding bits).
Result<BaseSummary> read_base_summary(const uint8_t* data, size_t size);

/// Deep check of a mesh as BASE stores it (for `lodbake-inspect --validate`):
/// storability as listed for encode_base(), plus triangles that repeat a
/// vertex index and vertices no triangle uses. Each kind of problem gives
/// one line with its count and first instance; empty when all is well.
std::vector<std::string> validate_base(const TriangleMesh& mesh);

/// decode_base() then validate_base(): a decode error is the single finding.
std::vector<std::string> validate_base_payload(const uint8_t* data, size_t size);

/// What quantizing positions to `bits` bits costs.
struct QuantizationReport {
  Vec3f box_min{};
  Vec3f box_max{};
  double max_error = 0;    ///< largest |decoded - original| over all coordinates
  double error_bound = 0;  ///< quantization_error_bound() for this box and bits
};

/// Quantizes and dequantizes `positions` exactly as encode_base() and
/// decode_base() do and measures the largest coordinate error.
/// \return kInvalidInput when bits is outside 1..30 or a position is not finite.
Result<QuantizationReport> measure_quantization(const std::vector<Vec3f>& positions, int bits);

}  // namespace lodbake
