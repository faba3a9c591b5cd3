// Fixed-width LSB-first bit packing (the order of DEFLATE's bit stream):
// simple to specify for an independent reader and free of byte-order
// questions. Values are at most 32 bits wide, so a 64-bit accumulator never
// overflows while a value is merged in.
#include "formats/support/bit_packing.h"

#include <cassert>

namespace lodbake {

int bits_for_count(uint64_t count) {
  return count <= 1 ? 0 : bit_width(count - 1);
}

uint64_t packed_size_bytes(uint64_t values, int bits) {
  if (bits <= 0 || values == 0) return 0;
  const uint64_t width = static_cast<uint64_t>(bits);
  if (values > (UINT64_MAX - 7) / width) return UINT64_MAX;
  return (values * width + 7) / 8;
}

void BitWriter::write(uint32_t value, int bits) {
  assert(bits >= 0 && bits <= 32);
  if (bits == 0) return;
  assert(bits == 32 || value < (uint64_t{1} << bits));
  buffer_ |= static_cast<uint64_t>(value) << buffered_;
  buffered_ += bits;
  while (buffered_ >= 8) {
    out_->push_back(static_cast<uint8_t>(buffer_ & 0xFFu));
    buffer_ >>= 8;
    buffered_ -= 8;
  }
}

void BitWriter::finish() {
  if (buffered_ > 0) out_->push_back(static_cast<uint8_t>(buffer_ & 0xFFu));
  buffer_ = 0;
  buffered_ = 0;
}

bool BitReader::read(int bits, uint32_t* out) {
  if (bits < 0 || bits > 32) return false;
  const uint64_t total_bits = static_cast<uint64_t>(size_) * 8;
  if (static_cast<uint64_t>(bits) > total_bits - bit_pos_) return false;
  if (bits == 0) {
    *out = 0;
    return true;
  }
  // The value's bits span at most 5 bytes (7 + 32 bits); the check above
  // keeps them inside the span, the word may end past the value but not
  // past the span.
  const size_t byte_index = static_cast<size_t>(bit_pos_ >> 3);
  const int shift = static_cast<int>(bit_pos_ & 7u);
  uint64_t word = 0;
  if (size_ - byte_index >= 8) {
    std::memcpy(&word, data_ + byte_index, 8);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    word = __builtin_bswap64(word);
#endif
  } else {
    for (size_t i = 0; i < size_ - byte_index; ++i)
      word |= static_cast<uint64_t>(data_[byte_index + i]) << (8 * i);
  }
  *out = static_cast<uint32_t>((word >> shift) & ((uint64_t{1} << bits) - 1));
  bit_pos_ += static_cast<uint64_t>(bits);
  return true;
}

bool BitReader::padding_is_zero() const {
  const int bit_in_byte = static_cast<int>(bit_pos_ & 7u);
  if (bit_in_byte == 0) return true;
  const uint8_t last = data_[bit_pos_ >> 3];
  return (last >> bit_in_byte) == 0;
}

}  // namespace lodbake
