// The compact codec (codec 1) of the FANH section: a lossless recoding of a
// raw FANH payload against its BASE (docs/format.md "Compact FANH"). The
// merges are replayed over BASE's triangles, which predicts each child's
// removed and modified triangles; children are coded as neighbours of the
// centre. Decoding gives back the raw payload byte for byte.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact FANH payload.
inline constexpr uint8_t kFanhCompactVersion = 1;

/// Recodes a raw FANH payload. `base` is the decoded BASE mesh of the
/// section's container (only its triangles and vertex count are used).
/// Deterministic.
/// \return the compact bytes; decode_fanh()'s error when the raw payload is
///         malformed, kInvalidInput when its counts are not base's;
///         kUnsupported when it is valid but not as the reference writer
///         lays it out, or a child is not the topmost node of its vertex
///         (the codec names children by vertex); kRuntime when memory runs
///         out.
Result<Bytes> encode_fanh_compact(const uint8_t* raw, size_t raw_size, const TriangleMesh& base);

/// The raw FANH payload that `data` encodes, against the same `base`.
/// Every count is bounded by the bits that remain before anything is
/// allocated, and the result is a structurally valid FANH payload
/// (decode_fanh() accepts it; validate_fanh() replays it over BASE).
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section FANH: compact ..." (kInvalidInput) for an
///         unknown version, counts other than base's or more than the bytes
///         can hold, a truncated or out-of-range code, a hierarchy that
///         breaks a FANH rule, nonzero padding or trailing bytes; kRuntime
///         when memory runs out. Never throws.
Result<Bytes> decode_fanh_compact(const uint8_t* data, size_t size, const TriangleMesh& base);

}  // namespace lodbake
