// The compact codec (codec 1) of the VTRE section: a lossless recoding of a
// raw VTRE payload (docs/format.md "Compact VTRE"). Fan entries as moves
// through the fan of the split vertex before the split, coordinates as
// differences of their bit patterns from the parent's. Decoding gives back
// the raw payload byte for byte and needs no other section.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact VTRE payload.
inline constexpr uint8_t kVtreCompactVersion = 1;

/// Recodes a raw VTRE payload. Deterministic.
/// \return the compact bytes; decode_vtre()'s error when the raw payload is
///         malformed; kUnsupported when it is valid but not as the reference
///         writer lays it out (other bit widths), which this codec cannot
///         reproduce; kRuntime when memory runs out.
Result<Bytes> encode_vtre_compact(const uint8_t* raw, size_t raw_size);

/// The raw VTRE payload that `data` encodes. Every count is bounded by the
/// bits that remain before anything is allocated, and the result is a
/// valid VTRE payload (decode_vtre() accepts it).
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section VTRE: compact ..." (kInvalidInput) for an
///         unknown version, counts the bytes cannot hold, a truncated or
///         out-of-range code, trees that break a VTRE rule, nonzero padding
///         or trailing bytes; kRuntime when memory runs out. Never throws.
Result<Bytes> decode_vtre_compact(const uint8_t* data, size_t size);

}  // namespace lodbake
