// Exp-Golomb streams of the compact section codecs (see the header). The
// counting pass keeps, per context, how many values have each bit length;
// the cost of order k is estimated from that histogram (a value of bit
// length L costs 2·L' - k - 1 bits, L' the bit length of x + 2^k: k + 1
// for L <= k, L + 1 for L = k + 1, L or L + 1 above), taking the low bits
// as uniform. It is only used to choose k (the stream records the chosen
// order, so a reader never repeats the estimate).
#include "formats/sections/compact_coding.h"

namespace lodbake {
namespace {

int bit_length(uint64_t x) {
  int n = 0;
  while (x != 0) {
    ++n;
    x >>= 1;
  }
  return n;
}

void write_wide(BitWriter* out, uint64_t value, int width) {
  if (width > 32) {
    out->write(static_cast<uint32_t>(value & 0xFFFFFFFFu), 32);
    out->write(static_cast<uint32_t>(value >> 32), width - 32);
  } else {
    out->write(static_cast<uint32_t>(value), width);
  }
}

bool read_wide(BitReader* in, int width, uint64_t* value) {
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

}  // namespace

CompactStreamWriter::CompactStreamWriter(int contexts)
    : length_counts_(static_cast<size_t>(contexts), std::vector<uint64_t>(65, 0)),
      orders_(static_cast<size_t>(contexts), 0) {}

void CompactStreamWriter::golomb(int ctx, uint64_t value) {
  if (out_ == nullptr) {
    ++length_counts_[static_cast<size_t>(ctx)][static_cast<size_t>(bit_length(value))];
    return;
  }
  const int k = orders_[static_cast<size_t>(ctx)];
  const uint64_t y = value + (uint64_t{1} << k);
  const int length = bit_length(y);
  for (int i = 0; i < length - k - 1; ++i)
    writer_.write(0, 1);
  writer_.write(1, 1);
  write_wide(&writer_, y & ((uint64_t{1} << (length - 1)) - 1), length - 1);
}

void CompactStreamWriter::bits(uint64_t value, int width) {
  if (out_ != nullptr) write_wide(&writer_, value, width);
}

void CompactStreamWriter::start_writing(Bytes* out) {
  constexpr uint64_t kOne = uint64_t{1} << 16;  // costs in 1/65536 bits: integers, so
                                                // the choice is the same on every platform
  for (size_t c = 0; c < orders_.size(); ++c) {
    uint64_t best_cost = UINT64_MAX;
    for (int k = 0; k <= kCompactMaxOrder; ++k) {
      uint64_t cost = 0;
      for (int length = 0; length <= 64; ++length) {
        const uint64_t count = length_counts_[c][static_cast<size_t>(length)];
        if (count == 0) continue;
        // Bits of x + 2^k: k + 1 below 2^k; one more than x's own just
        // above (always a carry); above that x's own, plus one for the
        // carry of x's bits k..L-1 all ones, which a uniform x has with
        // probability 2^(k - L + 1).
        uint64_t bits = 0;
        if (length <= k) {
          bits = static_cast<uint64_t>(k + 1) * kOne;
        } else if (length == k + 1) {
          bits = static_cast<uint64_t>(2 * (length + 1) - k - 1) * kOne;
        } else {
          const int shift = length - k - 1;
          bits = static_cast<uint64_t>(2 * length - k - 1) * kOne +
                 (shift < 18 ? (2 * kOne) >> shift : 0);
        }
        cost += count * bits;
      }
      if (cost < best_cost) {
        best_cost = cost;
        orders_[c] = k;
      }
    }
    out->push_back(static_cast<uint8_t>(orders_[c]));
  }
  out_ = out;
  writer_ = BitWriter(out);
}

void CompactStreamWriter::finish() {
  writer_.finish();
}

bool CompactStreamReader::start(const uint8_t* data, size_t size, int contexts) {
  if (size < static_cast<size_t>(contexts)) return false;
  orders_.assign(data, data + contexts);
  for (int k : orders_) {
    if (k > kCompactMaxOrder) return false;
  }
  reader_ = BitReader(data + contexts, size - static_cast<size_t>(contexts));
  size_ = size - static_cast<size_t>(contexts);
  total_bits_ = uint64_t{size_} * 8;
  return true;
}

bool CompactStreamReader::golomb(int ctx, uint64_t* value) {
  int zeros = 0;
  for (;;) {
    uint32_t bit = 0;
    if (!reader_.read(1, &bit)) return false;
    if (bit == 1) break;
    if (++zeros > kCompactMaxPrefix) return false;
  }
  const int low_bits = zeros + orders_[static_cast<size_t>(ctx)];
  if (low_bits > 62) return false;
  uint64_t low = 0;
  if (!read_wide(&reader_, low_bits, &low)) return false;
  *value = ((uint64_t{1} << low_bits) | low) - (uint64_t{1} << orders_[static_cast<size_t>(ctx)]);
  return true;
}

bool CompactStreamReader::bits(int width, uint64_t* value) {
  return read_wide(&reader_, width, value);
}

}  // namespace lodbake
