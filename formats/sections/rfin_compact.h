// The compact codec (codec 1) of the RFIN section: a lossless recoding of a
// raw RFIN payload (docs/format.md "Compact RFIN"). Each record's floats as
// differences of their bit patterns from the previous record's, its cone
// as differences of the quantized values. Decoding gives back the raw
// payload byte for byte and needs no other section.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact RFIN payload.
inline constexpr uint8_t kRfinCompactVersion = 1;

/// Recodes a raw RFIN payload. Deterministic.
/// \return the compact bytes; read_rfin_summary()'s error (kInvalidInput)
///         when the payload's size or flags are wrong; kRuntime when memory
///         runs out. Every payload of the right size can be recoded.
Result<Bytes> encode_rfin_compact(const uint8_t* raw, size_t raw_size);

/// The raw RFIN payload that `data` encodes. The record count is bounded by
/// the bits that remain before anything is allocated. The result has
/// RFIN's layout but is not checked against its hierarchy: decode it with
/// decode_rfin() as any raw payload.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section RFIN: compact ..." (kInvalidInput) for an
///         unknown version, nonzero flags, a count the bytes cannot hold, a
///         truncated or out-of-range code, nonzero padding or trailing
///         bytes; kRuntime when memory runs out. Never throws.
Result<Bytes> decode_rfin_compact(const uint8_t* data, size_t size);

}  // namespace lodbake
