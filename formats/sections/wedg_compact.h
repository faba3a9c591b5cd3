// The compact codec (codec 1) of the WEDG section: a lossless recoding of a
// raw WEDG payload against its BASE (docs/format.md "Compact WEDG"). A
// corner's wedge is named by its rank among the wedges of the corner's
// vertex (BASE's corners, every split's vt), which is nearly always free;
// the wedge table's homes by the removed vertices not used yet. Decoding
// gives back the raw payload byte for byte.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact WEDG payload.
inline constexpr uint8_t kWedgCompactVersion = 1;

/// Recodes a raw WEDG payload. `base` is the decoded BASE mesh of the
/// section's group (its vertex count and triangles are used). Deterministic.
/// \return the compact bytes; decode_wedg()'s error when the raw payload is
///         malformed; kUnsupported when it is valid but does not follow
///         base (another base triangle count, a wedge's home at or above
///         base's vertices plus the splits) or moves more corners than 8
///         per bit of the coded stream, which the codec cannot store;
///         kRuntime when memory runs out.
Result<Bytes> encode_wedg_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base);

/// The raw WEDG payload that `data` encodes, against the same `base`.
/// Every count is bounded by the bits that remain before anything is
/// allocated, and the result is a valid WEDG payload (decode_wedg()
/// accepts it).
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section WEDG: compact ..." (kInvalidInput) for an
///         unknown version or mode, a base triangle count other than
///         base's, counts the bits cannot hold, a truncated or out-of-range
///         code, lists that break a WEDG rule, nonzero padding or trailing
///         bytes; kRuntime when memory runs out. Never throws.
Result<Bytes> decode_wedg_compact(const uint8_t* data, size_t size, const TriangleMesh& base);

}  // namespace lodbake
