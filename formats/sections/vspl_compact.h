// The compact codec (codec 1) of the VSPL section: a lossless recoding of a
// raw VSPL payload (docs/format.md "Compact VSPL"). Vertex-split topology
// with wings predicted from a per-vertex list of known neighbours,
// quantized positions predicted from vs's position before the split and
// Exp-Golomb coded, errors as Exp-Golomb coded differences of their bits.
// Decoding gives back the raw payload byte for byte.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact VSPL payload.
inline constexpr uint8_t kVsplCompactVersion = 1;

/// Recodes a raw VSPL payload. `base` is the decoded BASE mesh the payload
/// belongs to (its positions predict the first splits, its triangles seed
/// the neighbour lists). Deterministic.
/// \return the compact bytes; decode_vspl()'s error when the raw payload is
///         malformed; kRuntime when memory runs out.
Result<Bytes> encode_vspl_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base);

/// The raw VSPL payload that `data` encodes, against the same `base`.
/// Every count is bounded by the bytes that remain before anything is
/// allocated. The result is not validated as a VSPL payload: decode it with
/// decode_vspl() as any raw payload.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section VSPL: compact ..." (kInvalidInput) for an
///         unknown version, a base vertex count other than base's, a count
///         needing more bits than remain, an index, residual or code out of
///         range, nonzero padding bits or trailing bytes. Never throws.
Result<Bytes> decode_vspl_compact(const uint8_t* data, size_t size, const TriangleMesh& base);

}  // namespace lodbake
