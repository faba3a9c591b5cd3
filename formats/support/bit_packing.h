// Bit packing of unsigned integers at a fixed width, least significant bit
// first: the indices and quantized positions of the BASE section (and of
// later sections) are stored this way. Layout in docs/format.md, "Bit packing".
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace lodbake {

/// Bits of `v` up to its highest set bit: 0 for 0, else floor(log2(v)) + 1.
inline int bit_width(uint64_t v) {
  int w = 0;
  for (; v != 0; v >>= 1)
    ++w;
  return w;
}

/// Bits needed to store any index in [0, count): 0 for count <= 1, else
/// ceil(log2(count)) = bit width of (count - 1). Results are in [0, 64].
int bits_for_count(uint64_t count);

/// Bytes taken by `values` values of `bits` bits each, padded to a whole byte:
/// ceil(values * bits / 8). Overflow-safe for values < 2^58 and bits <= 32;
/// returns UINT64_MAX when the product would not fit (callers compare it with
/// the bytes that remain, so that value simply fails the check).
uint64_t packed_size_bytes(uint64_t values, int bits);

/// A float's IEEE-754 bit pattern, and back: bit-exact, for codecs that
/// store floats in bit streams.
inline uint32_t float_bits(float f) {
  uint32_t u = 0;
  std::memcpy(&u, &f, 4);
  return u;
}
inline float bits_float(uint32_t u) {
  float f = 0;
  std::memcpy(&f, &u, 4);
  return f;
}

/// Appends values LSB-first to a byte vector: bit 0 of the first value is
/// bit 0 of the first byte; each value's bits follow the previous value's
/// without gaps. finish() pads the last byte with zero bits.
class BitWriter {
 public:
  explicit BitWriter(std::vector<uint8_t>* out) : out_(out) {}

  /// Appends the low `bits` bits of `value`.
  /// \pre 0 <= bits <= 32 and value < 2^bits (higher bits would be lost).
  void write(uint32_t value, int bits);

  /// Flushes a partial last byte (zero padded). Call once after the last
  /// value of a stream; the next write() then starts a new byte.
  void finish();

 private:
  std::vector<uint8_t>* out_;
  uint64_t buffer_ = 0;  // pending bits, bit 0 is the next to go out
  int buffered_ = 0;     // number of pending bits, < 8 between calls
};

/// Reads LSB-first packed values from a bounded span; never reads past it.
class BitReader {
 public:
  BitReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  /// Reads `bits` (0..32) bits into `*out`. Returns false, leaving `*out`
  /// unchanged, when fewer than `bits` bits remain.
  bool read(int bits, uint32_t* out);

  /// Bytes touched so far (a partially read byte counts as whole).
  size_t bytes_consumed() const { return static_cast<size_t>((bit_pos_ + 7) / 8); }

  /// Bits read so far.
  uint64_t bits_consumed() const { return bit_pos_; }

  /// True when the unread bits of the last touched byte are all zero; a
  /// strict decoder requires this so every stream has one canonical form.
  bool padding_is_zero() const;

 private:
  const uint8_t* data_;
  size_t size_;
  uint64_t bit_pos_ = 0;
};

}  // namespace lodbake
