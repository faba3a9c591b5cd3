#include "formats/support/exp_golomb.h"

namespace lodbake {

int bit_length(uint64_t x) {
  return x == 0 ? 0 : 64 - __builtin_clzll(x);
}

void write_bits64(BitWriter* out, uint64_t value, int width) {
  if (width > 32) {
    out->write(static_cast<uint32_t>(value & 0xFFFFFFFFu), 32);
    out->write(static_cast<uint32_t>(value >> 32), width - 32);
  } else {
    out->write(static_cast<uint32_t>(value), width);
  }
}

bool read_bits64(BitReader* in, int width, uint64_t* value) {
  if (width < 0 || width > 64) return false;
  uint32_t low = 0;
  uint32_t high = 0;
  if (width > 32) {
    if (!in->read(32, &low) || !in->read(width - 32, &high)) return false;
  } else if (!in->read(width, &low)) {
    return false;
  }
  *value = (uint64_t{high} << 32) | low;
  return true;
}

void write_exp_golomb(BitWriter* out, uint64_t x, int k) {
  const uint64_t y = x + (uint64_t{1} << k);
  const int length = bit_length(y);
  for (int i = 0; i < length - k - 1; ++i)
    out->write(0, 1);
  out->write(1, 1);
  write_bits64(out, y & ((uint64_t{1} << (length - 1)) - 1), length - 1);
}

uint64_t exp_golomb_bits(uint64_t x, int k) {
  return static_cast<uint64_t>(2 * bit_length(x + (uint64_t{1} << k)) - k - 1);
}

bool read_exp_golomb(BitReader* in, int k, int max_prefix, uint64_t* x) {
  if (k < 0 || k > 32) return false;
  int zeros = 0;
  for (;;) {
    uint32_t bit = 0;
    if (!in->read(1, &bit)) return false;
    if (bit == 1) break;
    if (++zeros > max_prefix) return false;
  }
  const int low_bits = zeros + k;
  if (low_bits > 62) return false;
  uint64_t low = 0;
  if (!read_bits64(in, low_bits, &low)) return false;
  *x = ((uint64_t{1} << low_bits) | low) - (uint64_t{1} << k);
  return true;
}

}  // namespace lodbake
