// The compact codec (codec 1) of the SETS section: a lossless recoding of a
// raw SETS payload (docs/format.md "Compact SETS"). Arc labels predicted
// from the LoD at which a successor's vertex is removed, successors as
// steps from the next node or repeats of the previous arc's. Decoding gives
// back the raw payload byte for byte and needs no other section.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact SETS payload.
inline constexpr uint8_t kSetsCompactVersion = 1;

/// Recodes a raw SETS payload. Deterministic.
/// \return the compact bytes; decode_sets()'s error when the raw payload is
///         malformed; kUnsupported when it is valid but not as the reference
///         writer lays it out (other bit widths), which this codec cannot
///         reproduce; kRuntime when memory runs out.
Result<Bytes> encode_sets_compact(const uint8_t* raw, size_t raw_size);

/// The raw SETS payload that `data` encodes. Every count is bounded by the
/// bits that remain before anything is allocated, and the result is a
/// valid SETS payload (decode_sets() accepts it).
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section SETS: compact ..." (kInvalidInput) for an
///         unknown version, counts the bytes cannot hold, a truncated or
///         out-of-range code, a graph that breaks a SETS rule, nonzero padding
///         or trailing bytes; kRuntime when memory runs out. Never throws.
Result<Bytes> decode_sets_compact(const uint8_t* data, size_t size);

}  // namespace lodbake
