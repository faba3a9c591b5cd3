// Exp-Golomb codes and 64-bit fields on the LSB-first bit streams of
// bit_packing.h, shared by the compact codecs (docs/format.md "Codecs"):
// one definition of the code, and of the bounds a reader enforces on a
// hostile stream.
#pragma once

#include <cstdint>

#include "formats/support/bit_packing.h"

namespace lodbake {

/// Signed to unsigned, small magnitudes first: 0, -1, 1, -2, ... -> 0, 1, 2, 3, ...
inline uint64_t zigzag64(int64_t d) {
  return (static_cast<uint64_t>(d) << 1) ^ static_cast<uint64_t>(d >> 63);
}
inline int64_t unzigzag64(uint64_t z) {
  return static_cast<int64_t>(z >> 1) ^ -static_cast<int64_t>(z & 1);
}

/// Bits of x without leading zeros: 0 for 0, 64 for values >= 2^63.
int bit_length(uint64_t x);

/// `value` in `width` bits (0..64), low 32 bits first. \pre value < 2^width.
void write_bits64(BitWriter* out, uint64_t value, int width);
/// Reads what write_bits64() wrote; false (nothing read past the span) when
/// fewer bits remain or `width` is outside 0..64.
bool read_bits64(BitReader* in, int width, uint64_t* value);

/// Exp-Golomb of order k: with y = x + 2^k of L bits, L - k - 1 zero bits,
/// a one bit, then the low L - 1 bits of y (least significant first).
/// \pre 0 <= k <= 32 and x < 2^62.
void write_exp_golomb(BitWriter* out, uint64_t x, int k);
/// Its length in bits.
uint64_t exp_golomb_bits(uint64_t x, int k);
/// Reads one code of order k (0..32); false on a truncated stream, a zero
/// prefix longer than `max_prefix` bits, or a value of 2^62 or more (no
/// writer produces those: they would overflow the arithmetic).
bool read_exp_golomb(BitReader* in, int k, int max_prefix, uint64_t* x);

}  // namespace lodbake
