// The compact codec (codec 1) of the VHIE section: a lossless recoding of a
// raw VHIE payload (docs/format.md "Compact VHIE"). Cut vertices and input
// vertices as differences from a nearby leaf's, positions and errors as
// differences of their float bit patterns from a neighbour's. Decoding
// gives back the raw payload byte for byte and needs no other section
// (not even BASE: the root positions are not part of the payload).
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The layout version written first in every compact VHIE payload.
inline constexpr uint8_t kVhieCompactVersion = 1;

/// Recodes a raw VHIE payload. Deterministic.
/// \return the compact bytes; kInvalidInput when the payload's layout is
///         broken (read_vhie_summary()'s checks, a structure stream that
///         does not describe full binary trees in breadth-first order, a
///         cut or input vertex out of range); kUnsupported when it has
///         nonzero padding bits, which the codec cannot reproduce; kRuntime
///         when memory runs out.
Result<Bytes> encode_vhie_compact(const uint8_t* raw, size_t raw_size);

/// The raw VHIE payload that `data` encodes. Every count is bounded by the
/// bits that remain before anything is allocated. The result has VHIE's
/// layout but is not validated as a hierarchy: decode it with decode_vhie()
/// as any raw payload.
/// \pre `data` points to `size` readable bytes (may be null when size == 0).
/// \return LBK-E023 "section VHIE: compact ..." (kInvalidInput) for an
///         unknown version, counts the bytes cannot hold, a structure that
///         is not full binary trees in breadth-first order, a truncated or
///         out-of-range code, nonzero padding or trailing bytes; kRuntime
///         when memory runs out. Never throws.
Result<Bytes> decode_vhie_compact(const uint8_t* data, size_t size);

}  // namespace lodbake
