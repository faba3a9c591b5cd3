// The draco codec (codec 2) of the BASE section: the base mesh as a Draco
// bitstream, layout in docs/format.md "Draco BASE". Sequential connectivity
// keeps every vertex id and the triangle order; positions are quantized by
// Draco (qp bits), normals and texture coordinates are stored unquantized.
// Built only with LODBAKE_DRACO_CODEC (formats/container/section_codecs.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every Draco BASE payload.
inline constexpr uint8_t kDracoBaseVersion = 1;

/// The quantization bits (qp) encode_base_draco() takes. BASE positions
/// are float32, whose 24 significant bits a finer grid over the extent
/// cannot add to, and Draco 1.5.5's encoder sizes a histogram by the
/// largest quantized residual: past about 22 bits its memory doubles with
/// each bit (the bunny's BASE: 75 MB at 24 bits, 272 MB at 26, 4.2 GB and
/// 7 s at 30).
inline constexpr int kMinDracoQuantizationBits = 1;
inline constexpr int kMaxDracoQuantizationBits = 24;
inline bool is_valid_draco_quantization_bits(int bits) {
  return bits >= kMinDracoQuantizationBits && bits <= kMaxDracoQuantizationBits;
}
/// The largest qp a stored payload may name: what Draco itself accepts and
/// earlier versions of lodbake-pack wrote; decoding is bounded by the
/// payload's size at any of them.
inline constexpr int kMaxStoredDracoQuantizationBits = 30;

struct DracoOptions {
  int quantization_bits = 14;  ///< Draco's qp for positions, 1..24 to encode
  int compression_level = 7;   ///< Draco's cl, 0..10 (speed = 10 - cl)

  bool operator==(const DracoOptions& o) const {
    return quantization_bits == o.quantization_bits && compression_level == o.compression_level;
  }
};

/// Encodes `mesh` (a BASE mesh) with Draco. Deterministic.
/// \return kUnsupported when the mesh has per-corner normals or texture
///         coordinates, no triangles, or positions Draco cannot quantize
///         (non-finite ones, an axis whose float extent overflows): keep such
///         a BASE raw; kInvalidInput for options out of range
///         (quantization_bits outside kMinDracoQuantizationBits..
///         kMaxDracoQuantizationBits); kRuntime when Draco fails.
Result<Bytes> encode_base_draco(const TriangleMesh& mesh, const DracoOptions& options);

/// The options a Draco BASE payload was written with (its first bytes).
Result<DracoOptions> read_draco_base_options(const uint8_t* data, size_t size);

/// Decodes a Draco BASE payload: vertex v and triangle t are those encoded.
/// Only the bitstream version this build writes (2.2, triangular mesh,
/// sequential connectivity) is accepted.
/// \return LBK-E023 "section BASE: draco ..." (kInvalidInput) for an unknown
///         layout version, a bitstream of another version or method, a
///         bitstream Draco refuses, or a mesh whose attributes do not map
///         every point. Never throws.
Result<TriangleMesh> decode_base_draco(const uint8_t* data, size_t size);

}  // namespace lodbake
