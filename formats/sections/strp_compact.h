// The compact codec (codec 1) of the STRP section: a lossless recoding of a
// raw STRP payload against its BASE (docs/format.md "Compact STRP"). Each
// index after a strip's first two is coded among the third vertices of
// BASE's triangles on the edge of the two before it. Decoding gives back
// the raw payload byte for byte.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact STRP payload.
inline constexpr uint8_t kStrpCompactVersion = 1;

/// Recodes a raw STRP payload. `base` is the decoded BASE mesh of the
/// section's container (only its triangles and vertex count are used).
/// Deterministic.
/// \return the compact bytes; decode_strp()'s error when the raw payload is
///         malformed, kInvalidInput when its vertex count is not base's;
///         kUnsupported when it is valid but not as the reference writer
///         lays it out (another length width); kRuntime when memory runs
///         out.
Result<Bytes> encode_strp_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base);

/// The raw STRP payload that `data` encodes, against the same `base`. The
/// index count is bounded by the bits that remain before anything is
/// allocated, and the result is a valid STRP payload (decode_strp()
/// accepts it; validate_strp() checks it against BASE).
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section STRP: compact ..." (kInvalidInput) for an
///         unknown version, a vertex count other than base's, counts the
///         bytes cannot hold, a truncated or out-of-range code, nonzero
///         padding or trailing bytes; kRuntime when memory runs out. Never
///         throws.
Result<Bytes> decode_strp_compact(const uint8_t* data, size_t size, const TriangleMesh& base);

}  // namespace lodbake
