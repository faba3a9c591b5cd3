// Exp-Golomb streams of the compact section codecs (see the header). The
// writer keeps, per context, how many values have each bit length;
// the cost of order k is estimated from that histogram (a value of bit
// length L costs 2·L' - k - 1 bits, L' the bit length of x + 2^k: k + 1
// for L <= k, L + 1 for L = k + 1, L or L + 1 above), taking the low bits
// as uniform. It is only used to choose k (the stream records the chosen
// order, so a reader never repeats the estimate).
#include "formats/sections/compact_coding.h"

#include <cstring>

#include "formats/container/container_errors.h"
#include "formats/support/string_format.h"

namespace lodbake {

CompactStreamWriter::CompactStreamWriter(int contexts)
    : length_counts_(static_cast<size_t>(contexts), std::vector<uint64_t>(65, 0)),
      orders_(static_cast<size_t>(contexts), 0) {}

void CompactStreamWriter::record(uint8_t tag, uint64_t value) {
  constexpr size_t kLongest = 11;  // the tag and ten LEB128 bytes
  if (symbols_.empty() || symbols_.back().size() > kChunk - kLongest) {
    symbols_.emplace_back();
    symbols_.back().reserve(kChunk);
  }
  Bytes& chunk = symbols_.back();
  chunk.push_back(tag);
  while (value >= 0x80) {
    chunk.push_back(static_cast<uint8_t>(value | 0x80));
    value >>= 7;
  }
  chunk.push_back(static_cast<uint8_t>(value));
}

void CompactStreamWriter::golomb(int ctx, uint64_t value) {
  ++length_counts_[static_cast<size_t>(ctx)][static_cast<size_t>(bit_length(value))];
  record(static_cast<uint8_t>(ctx), value);
}

void CompactStreamWriter::bits(uint64_t value, int width) {
  if (width != 0) record(static_cast<uint8_t>(kMaxContexts + width), value);
}

namespace {

// The LSB-first bit stream of bit_packing.h's BitWriter, for one whole
// stream: whole 32-bit words go out at once.
class StreamBits {
 public:
  explicit StreamBits(Bytes* out) : out_(out) {}
  // \pre width <= 32, value < 2^width.
  void put(uint64_t value, int width) {
    buffer_ |= value << buffered_;
    buffered_ += width;
    if (buffered_ >= 32) {
      const uint8_t word[4] = {static_cast<uint8_t>(buffer_), static_cast<uint8_t>(buffer_ >> 8),
                               static_cast<uint8_t>(buffer_ >> 16),
                               static_cast<uint8_t>(buffer_ >> 24)};
      out_->insert(out_->end(), word, word + 4);
      buffer_ >>= 32;
      buffered_ -= 32;
    }
  }
  // \pre width <= 64, value < 2^width.
  void put64(uint64_t value, int width) {
    if (width > 32) {
      put(value & 0xFFFFFFFFu, 32);
      put(value >> 32, width - 32);
    } else {
      put(value, width);
    }
  }
  // write_exp_golomb()'s code.
  void exp_golomb(uint64_t x, int k) {
    const uint64_t y = x + (uint64_t{1} << k);
    const int length = bit_length(y);
    int zeros = length - k - 1;
    for (; zeros > 31; zeros -= 32)
      put(0, 32);
    put(uint64_t{1} << zeros, zeros + 1);
    put64(y & ((uint64_t{1} << (length - 1)) - 1), length - 1);
  }
  // Pads the last byte with zero bits.
  void finish() {
    for (; buffered_ > 0; buffered_ -= 8) {
      out_->push_back(static_cast<uint8_t>(buffer_));
      buffer_ >>= 8;
    }
  }

 private:
  Bytes* out_;
  uint64_t buffer_ = 0;
  int buffered_ = 0;  // < 32 between calls
};

}  // namespace

void CompactStreamWriter::write_to(Bytes* out) {
  constexpr uint64_t kOne = uint64_t{1} << 16;  // costs in 1/65536 bits: integers, so
                                                // the choice is the same on every platform
  uint64_t estimate = 0;
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
    estimate += best_cost / kOne / 8;
    out->push_back(static_cast<uint8_t>(orders_[c]));
  }
  out->reserve(out->size() + estimate + 16);
  StreamBits stream(out);
  for (const Bytes& chunk : symbols_) {
    const uint8_t* p = chunk.data();
    const uint8_t* end = p + chunk.size();
    while (p != end) {
      const uint8_t tag = *p++;
      uint64_t value = 0;
      for (int shift = 0;; shift += 7) {
        const uint8_t byte = *p++;
        value |= uint64_t{byte & 0x7Fu} << shift;
        if (byte < 0x80) break;
      }
      if (tag < kMaxContexts) {
        stream.exp_golomb(value, orders_[tag]);
      } else {
        stream.put64(value, tag - kMaxContexts);
      }
    }
  }
  stream.finish();
  symbols_.clear();
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
  return read_exp_golomb(&reader_, orders_[static_cast<size_t>(ctx)], kCompactMaxPrefix, value);
}

bool CompactStreamReader::bits(int width, uint64_t* value) {
  return read_bits64(&reader_, width, value);
}

namespace {

Status bad_compact(const char* tag, const std::string& detail) {
  return malformed_section(tag, "compact: " + detail);
}

}  // namespace

Status require_canonical_layout(const char* tag, const Bytes& canonical, const uint8_t* raw,
                                size_t raw_size, const char* widths) {
  if (canonical.size() == raw_size && std::memcmp(canonical.data(), raw, raw_size) == 0)
    return Status::ok();
  return unsupported(std::string(tag) + " payload is not laid out as the reference writer does (" +
                     widths + "), which the compact codec cannot reproduce");
}

Status check_compact_start(const char* tag, const uint8_t* data, size_t size, size_t fixed_bytes,
                           uint8_t version) {
  if (size < 1 + fixed_bytes) {
    return bad_compact(tag, string_printf("%zu bytes, the version and fixed fields need %zu", size,
                                          1 + fixed_bytes));
  }
  if (data[0] != version)
    return bad_compact(tag, string_printf("unknown layout version %u", data[0]));
  return Status::ok();
}

Result<Bytes> finish_compact_decode(const char* tag, const CompactStreamReader& in,
                                    Result<Bytes> raw, const uint8_t* fixed, size_t fixed_bytes,
                                    const char* structure) {
  if (!in.at_clean_end())
    return bad_compact(tag, "nonzero padding or trailing bytes after the stream");
  if (!raw.is_ok()) {
    if (raw.status().kind() == ErrorKind::kInvalidInput)
      return bad_compact(tag, raw.status().message());
    return raw.status();
  }
  if (raw.value().size() < fixed_bytes || std::memcmp(raw.value().data(), fixed, fixed_bytes) != 0)
    return bad_compact(tag, std::string("the fixed fields disagree with the decoded ") + structure);
  return raw;
}

}  // namespace lodbake
