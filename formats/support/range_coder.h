// An adaptive binary range coder (the LZMA "rc" coder, Igor Pavlov, after
// Martin 1979 "Range encoding") with the binarisations the compact codecs
// build on: adaptive bit trees, uniform values over any range, and signed
// or unsigned integers as an adaptive bit-length class plus mantissa bits.
// Layout and rules in docs/format.md "Range coder".
//
// Why not Draco's entropy coders: Draco is optional (`make test-nodraco`),
// the compact codecs must work without it, and Draco's rANS coders take
// whole symbol tables per stream, which small sections would pay for;
// an adaptive binary coder needs no tables and learns the statistics of
// each context as it goes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lodbake {

/// The probability that a bit is 0, in 1/65536ths; starts at 1/2. LZMA
/// uses 1/2048ths, which caps a probability at 1 - 31/2048 and so charges
/// 0.02 bit for every near-certain decision (the top bits of a length that
/// never gets long): 16 bits of precision gave 0.3 bit per split less on
/// the bunny's progressive mesh, and also beat mixing a fast and a slow
/// estimate.
using BitModel = uint16_t;
inline constexpr int kBitModelBits = 16;
inline constexpr BitModel kBitModelHalf = 1u << (kBitModelBits - 1);

/// Appends a range-coded stream to a byte vector. Deterministic: the same
/// calls give the same bytes.
class RangeEncoder {
 public:
  explicit RangeEncoder(std::vector<uint8_t>* out) : out_(out) {}

  /// Codes `bit` (0 or 1) with `*model`, then adapts the model.
  void encode_bit(BitModel* model, int bit);
  /// Codes the low `bits` (0..32) bits of `value` at probability 1/2 each,
  /// most significant first.
  void encode_direct(uint32_t value, int bits);
  /// Codes `value` uniformly in [0, n): log2(n) bits.
  /// \pre 1 <= n and value < n.
  void encode_uniform(uint32_t value, uint64_t n);
  /// Writes the last bytes. Call once; nothing may be coded afterwards.
  void finish();

  /// The information coded so far, in bits (-log2 of each coded event's
  /// probability): what the stream costs, before the 5 framing bytes.
  double cost_bits() const { return cost_; }

 private:
  void shift_low();
  void normalize();
  std::vector<uint8_t>* out_;
  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;
  uint64_t cache_size_ = 1;
  double cost_ = 0;
};

/// Decodes a stream written by RangeEncoder from a bounded span. Reading
/// past the span yields zero bytes and sets overrun(); a corrupt stream
/// decodes to arbitrary values but never reads out of bounds.
class RangeDecoder {
 public:
  /// \pre `data` points to `size` readable bytes (may be null when size == 0).
  RangeDecoder(const uint8_t* data, size_t size);

  /// False when the stream cannot be a RangeEncoder stream: shorter than 5
  /// bytes, a first byte other than 0, or a first code at the full range.
  bool valid_start() const { return valid_start_; }
  int decode_bit(BitModel* model);
  uint32_t decode_direct(int bits);
  /// The value coded by encode_uniform(value, n); false when the stream
  /// holds none below n (a corrupt stream).
  bool decode_uniform(uint64_t n, uint32_t* value);

  /// True once the decoder needed a byte past the span.
  bool overrun() const { return position_ > size_; }
  /// True when the decoder read exactly the encoder's bytes and nothing is
  /// left of the code: the encoder's last bytes are its low end, so a
  /// well-formed stream ends where the span ends with a zero code, and no
  /// other bytes decode to the same events (one canonical stream per
  /// sequence of events).
  bool at_end() const { return position_ == size_ && code_ == 0; }

 private:
  uint8_t next_byte();
  void normalize();
  const uint8_t* data_;
  size_t size_;
  size_t position_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint32_t code_ = 0;
  bool valid_start_ = false;
};

/// An adaptive bit tree over `bits` bits (1..8): one model per tree node,
/// symbols coded most significant bit first.
class BitTreeModel {
 public:
  explicit BitTreeModel(int bits) : bits_(bits), models_(size_t{1} << bits, kBitModelHalf) {}
  void encode(RangeEncoder* rc, uint32_t symbol);
  uint32_t decode(RangeDecoder* rc);
  int bits() const { return bits_; }

 private:
  int bits_;
  std::vector<BitModel> models_;
};

/// Unsigned integers below 2^40 in `contexts` contexts: the bit length c of
/// the value (0..40) by an adaptive bit tree of the context, then the c - 1
/// bits under the leading one, the first two of them adaptive (per context
/// and length), the rest at probability 1/2.
class AdaptiveIntModel {
 public:
  static constexpr int kMaxLength = 40;
  /// The mantissa bits under the leading one that are coded adaptively.
  static constexpr int kAdaptiveBits = 2;
  explicit AdaptiveIntModel(size_t contexts);
  void encode(RangeEncoder* rc, size_t context, uint64_t value);
  /// false when the decoded length is above kMaxLength (a corrupt stream).
  bool decode(RangeDecoder* rc, size_t context, uint64_t* value);
  /// The bit length of the last value coded in `context`'s slot: callers
  /// use it to pick the next context.
  static int length_of(uint64_t value) { return value == 0 ? 0 : 64 - __builtin_clzll(value); }

 private:
  std::vector<BitTreeModel> lengths_;
  std::vector<BitModel> mantissa_;  // contexts x (kMaxLength + 1) x 2^kAdaptiveBits
};

/// Signed integers with |value| < 2^40: the magnitude by an
/// AdaptiveIntModel, then (when nonzero) the sign by an adaptive bit of the
/// context.
class AdaptiveSignedModel {
 public:
  explicit AdaptiveSignedModel(size_t contexts)
      : magnitude_(contexts), sign_(contexts, kBitModelHalf) {}
  void encode(RangeEncoder* rc, size_t context, int64_t value);
  bool decode(RangeDecoder* rc, size_t context, int64_t* value);

 private:
  AdaptiveIntModel magnitude_;
  std::vector<BitModel> sign_;
};

}  // namespace lodbake
