// The LZMA range coder (Pavlov, LZMA SDK "LzmaEnc.c" / "LzmaDec.c"): 32-bit
// range, probabilities adapting by 1/32 of the distance to certainty (here
// with 16 bits of precision instead of LZMA's 11),
// carry propagation through a cached byte and a count of pending 0xFF
// bytes. Additions over LZMA: uniform values over any n (the range divided
// by n, in 16-bit pieces so the division loses at most 2^-8 of the range),
// and a cost counter for the encoder.
#include "formats/support/range_coder.h"

#include <array>
#include <cmath>

namespace lodbake {
namespace {

constexpr uint32_t kTop = 1u << 24;
constexpr int kMoveBits = 5;
constexpr uint64_t kUniformPiece = 1u << 16;

constexpr int kCostIndexShift = 4;

// -log2(p / 65536) for the probabilities p in each 1/4096th (at the bin's
// middle): the statistics need no more precision.
float cost_of(uint32_t p) {
  static const std::array<float, 1u << (kBitModelBits - kCostIndexShift)> table = [] {
    std::array<float, 1u << (kBitModelBits - kCostIndexShift)> t{};
    for (size_t i = 0; i < t.size(); ++i)
      t[i] = static_cast<float>(-std::log2((static_cast<double>(i) + 0.5) / t.size()));
    return t;
  }();
  return table[p >> kCostIndexShift];
}

}  // namespace

void RangeEncoder::shift_low() {
  if (static_cast<uint32_t>(low_) < 0xFF000000u || (low_ >> 32) != 0) {
    const uint8_t carry = static_cast<uint8_t>(low_ >> 32);
    uint8_t pending = cache_;
    do {
      out_->push_back(static_cast<uint8_t>(pending + carry));
      pending = 0xFF;
    } while (--cache_size_ != 0);
    cache_ = static_cast<uint8_t>(low_ >> 24);
  }
  ++cache_size_;
  low_ = (low_ & 0x00FFFFFFu) << 8;
}

void RangeEncoder::normalize() {
  while (range_ < kTop) {
    range_ <<= 8;
    shift_low();
  }
}

void RangeEncoder::encode_bit(BitModel* model, int bit) {
  const uint32_t bound = (range_ >> kBitModelBits) * *model;
  if (bit == 0) {
    cost_ += cost_of(*model);
    range_ = bound;
    *model = static_cast<BitModel>(*model + (((1u << kBitModelBits) - *model) >> kMoveBits));
  } else {
    cost_ += cost_of((1u << kBitModelBits) - *model);
    low_ += bound;
    range_ -= bound;
    *model = static_cast<BitModel>(*model - (*model >> kMoveBits));
  }
  normalize();
}

void RangeEncoder::encode_direct(uint32_t value, int bits) {
  for (int i = bits - 1; i >= 0; --i) {
    range_ >>= 1;
    if (((value >> i) & 1) != 0) low_ += range_;
    normalize();
  }
  cost_ += bits;
}

void RangeEncoder::encode_uniform(uint32_t value, uint64_t n) {
  cost_ += std::log2(static_cast<double>(n));
  auto piece = [this](uint32_t v, uint32_t m) {
    if (m <= 1) return;
    range_ /= m;
    low_ += uint64_t{v} * range_;
    normalize();
  };
  if (n <= kUniformPiece) {
    piece(value, static_cast<uint32_t>(n));
    return;
  }
  const uint32_t top = static_cast<uint32_t>((n - 1) >> 16);
  const uint32_t high = value >> 16;
  piece(high, top + 1);
  piece(value & 0xFFFFu,
        high < top ? static_cast<uint32_t>(kUniformPiece) : (((n - 1) & 0xFFFFu) + 1));
}

void RangeEncoder::finish() {
  for (int i = 0; i < 5; ++i)
    shift_low();
}

RangeDecoder::RangeDecoder(const uint8_t* data, size_t size) : data_(data), size_(size) {
  const uint8_t first = next_byte();
  for (int i = 0; i < 4; ++i)
    code_ = (code_ << 8) | next_byte();
  // The encoder's first byte is its empty cache; a code at the full range
  // would break the invariant code < range that keeps every decode in bounds.
  valid_start_ = size >= 5 && first == 0 && code_ != 0xFFFFFFFFu;
}

uint8_t RangeDecoder::next_byte() {
  const uint8_t b = position_ < size_ ? data_[position_] : 0;
  if (position_ <= size_) ++position_;
  return b;
}

void RangeDecoder::normalize() {
  while (range_ < kTop) {
    range_ <<= 8;
    code_ = (code_ << 8) | next_byte();
  }
}

int RangeDecoder::decode_bit(BitModel* model) {
  const uint32_t bound = (range_ >> kBitModelBits) * *model;
  int bit = 0;
  if (code_ < bound) {
    range_ = bound;
    *model = static_cast<BitModel>(*model + (((1u << kBitModelBits) - *model) >> kMoveBits));
  } else {
    code_ -= bound;
    range_ -= bound;
    *model = static_cast<BitModel>(*model - (*model >> kMoveBits));
    bit = 1;
  }
  normalize();
  return bit;
}

uint32_t RangeDecoder::decode_direct(int bits) {
  uint32_t value = 0;
  for (int i = 0; i < bits; ++i) {
    range_ >>= 1;
    uint32_t bit = 0;
    if (code_ >= range_) {
      code_ -= range_;
      bit = 1;
    }
    value = (value << 1) | bit;
    normalize();
  }
  return value;
}

bool RangeDecoder::decode_uniform(uint64_t n, uint32_t* value) {
  auto piece = [this](uint32_t m, uint32_t* v) {
    if (m <= 1) {
      *v = 0;
      return true;
    }
    range_ /= m;
    const uint32_t q = code_ / range_;
    if (q >= m) return false;
    code_ -= q * range_;
    *v = q;
    normalize();
    return true;
  };
  if (n == 0) return false;
  if (n <= kUniformPiece) return piece(static_cast<uint32_t>(n), value);
  const uint32_t top = static_cast<uint32_t>((n - 1) >> 16);
  uint32_t high = 0;
  uint32_t low = 0;
  if (!piece(top + 1, &high)) return false;
  if (!piece(high < top ? static_cast<uint32_t>(kUniformPiece) : (((n - 1) & 0xFFFFu) + 1), &low))
    return false;
  *value = (high << 16) | low;
  return true;
}

void BitTreeModel::encode(RangeEncoder* rc, uint32_t symbol) {
  uint32_t node = 1;
  for (int i = bits_ - 1; i >= 0; --i) {
    const int bit = static_cast<int>((symbol >> i) & 1);
    rc->encode_bit(&models_[node], bit);
    node = (node << 1) | static_cast<uint32_t>(bit);
  }
}

uint32_t BitTreeModel::decode(RangeDecoder* rc) {
  uint32_t node = 1;
  for (int i = 0; i < bits_; ++i)
    node = (node << 1) | static_cast<uint32_t>(rc->decode_bit(&models_[node]));
  return node - (1u << bits_);
}

AdaptiveIntModel::AdaptiveIntModel(size_t contexts)
    : lengths_(contexts, BitTreeModel(6)),
      mantissa_(contexts * (kMaxLength + 1) * (size_t{1} << kAdaptiveBits), kBitModelHalf) {}

void AdaptiveIntModel::encode(RangeEncoder* rc, size_t context, uint64_t value) {
  const int length = length_of(value);
  lengths_[context].encode(rc, static_cast<uint32_t>(length));
  if (length < 2) return;
  BitModel* m =
      &mantissa_[(context * (kMaxLength + 1) + static_cast<size_t>(length)) << kAdaptiveBits];
  int rest = length - 1;
  uint32_t node = 1;
  for (int j = 0; j < kAdaptiveBits && rest > 0; ++j) {
    const int bit = static_cast<int>((value >> (rest - 1)) & 1);
    rc->encode_bit(&m[node], bit);
    node = (node << 1) | static_cast<uint32_t>(bit);
    --rest;
  }
  if (rest > 32) {
    rc->encode_direct(static_cast<uint32_t>(value >> 32) & ((1u << (rest - 32)) - 1), rest - 32);
    rest = 32;
  }
  rc->encode_direct(static_cast<uint32_t>(value & (rest == 32 ? 0xFFFFFFFFu : (1u << rest) - 1)),
                    rest);
}

bool AdaptiveIntModel::decode(RangeDecoder* rc, size_t context, uint64_t* value) {
  const int length = static_cast<int>(lengths_[context].decode(rc));
  if (length > kMaxLength) return false;
  if (length < 2) {
    *value = static_cast<uint64_t>(length);
    return true;
  }
  BitModel* m =
      &mantissa_[(context * (kMaxLength + 1) + static_cast<size_t>(length)) << kAdaptiveBits];
  int rest = length - 1;
  uint64_t v = 1;
  uint32_t node = 1;
  for (int j = 0; j < kAdaptiveBits && rest > 0; ++j) {
    const int bit = rc->decode_bit(&m[node]);
    node = (node << 1) | static_cast<uint32_t>(bit);
    v = (v << 1) | static_cast<uint64_t>(bit);
    --rest;
  }
  if (rest > 32) {
    v = (v << (rest - 32)) | rc->decode_direct(rest - 32);
    rest = 32;
  }
  if (rest > 0) v = (v << rest) | rc->decode_direct(rest);
  *value = v;
  return true;
}

void AdaptiveSignedModel::encode(RangeEncoder* rc, size_t context, int64_t value) {
  const uint64_t magnitude =
      value < 0 ? uint64_t{0} - static_cast<uint64_t>(value) : static_cast<uint64_t>(value);
  magnitude_.encode(rc, context, magnitude);
  if (magnitude != 0) rc->encode_bit(&sign_[context], value < 0 ? 1 : 0);
}

bool AdaptiveSignedModel::decode(RangeDecoder* rc, size_t context, int64_t* value) {
  uint64_t magnitude = 0;
  if (!magnitude_.decode(rc, context, &magnitude)) return false;
  const int negative = magnitude != 0 ? rc->decode_bit(&sign_[context]) : 0;
  *value = negative != 0 ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
  return true;
}

}  // namespace lodbake
