// The compact codec (codec 1) of the DAGE section: a lossless recoding of a
// raw DAGE payload (docs/format.md "Compact DAGE"). Each node's parents as
// gaps, from the node down. Decoding gives back the raw payload byte for
// byte and needs no other section.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact DAGE payload.
inline constexpr uint8_t kDageCompactVersion = 1;

/// Recodes a raw DAGE payload. Deterministic.
/// \return the compact bytes; decode_dage()'s error when the raw payload is
///         malformed; kUnsupported when it is valid but not as the reference
///         writer lays it out (another degree width), which this codec cannot
///         reproduce; kRuntime when memory runs out.
Result<Bytes> encode_dage_compact(const uint8_t* raw, size_t raw_size);

/// The raw DAGE payload that `data` encodes. Every count is bounded by the
/// bits that remain before anything is allocated, and the result is a
/// valid DAGE payload (decode_dage() accepts it).
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section DAGE: compact ..." (kInvalidInput) for an
///         unknown version, counts the bytes cannot hold, a truncated or
///         out-of-range code, a DAG that breaks a DAGE rule, nonzero padding
///         or trailing bytes; kRuntime when memory runs out. Never throws.
Result<Bytes> decode_dage_compact(const uint8_t* data, size_t size);

}  // namespace lodbake
