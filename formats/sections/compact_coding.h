// The entropy coding shared by the compact codecs of VTRE, SETS, VHIE and
// RFIN (docs/format.md "Codecs"): one LSB-first bit stream (section 11's bit
// packing) of fixed-width fields and Exp-Golomb codes, each code in a
// *context* whose order k the encoder chooses and stores first, one byte
// per context. Writers run their walk once: the writer counts (to choose
// the orders) and keeps the symbols, a byte or three each, then codes them
// (a second walk cost more than the list: replays, fans, searches).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/support/bit_packing.h"
#include "formats/support/exp_golomb.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// The largest Exp-Golomb order a compact stream may name.
inline constexpr int kCompactMaxOrder = 32;
/// The longest zero prefix a reader accepts: values below 2^40 · 2^k.
inline constexpr int kCompactMaxPrefix = 40;

/// The detail of a section error ("LBK-E023: section VHIE: depth 0" gives
/// "depth 0"), for a codec that reports it under its own prefix.
inline std::string section_error_detail(const std::string& message) {
  if (message.compare(0, 5, "LBK-E") != 0) return message;
  const size_t first = message.find(": ");
  const size_t second = first == std::string::npos ? first : message.find(": ", first + 2);
  return second == std::string::npos ? message : message.substr(second + 2);
}

/// Writes one compact stream: construct with the number of contexts, run
/// the walk (golomb() and bits() in stream order), then write_to().
class CompactStreamWriter {
 public:
  /// \pre 1 <= contexts <= kMaxContexts.
  explicit CompactStreamWriter(int contexts);

  static constexpr int kMaxContexts = 64;

  /// Exp-Golomb code of `value` in context `ctx`. \pre value < 2^62.
  void golomb(int ctx, uint64_t value);
  /// `value` in `width` bits (0..64). \pre value < 2^width.
  void bits(uint64_t value, int width);

  /// Chooses each context's order from the values seen, appends the order
  /// bytes to `out`, then the stream of every value so far, padded to a
  /// whole byte. Call once.
  void write_to(Bytes* out);

 private:
  void record(uint8_t tag, uint64_t value);

  std::vector<std::vector<uint64_t>> length_counts_;  // per context: values by bit length
  std::vector<int> orders_;
  // The symbols in stream order: a tag byte (the context of a code, or
  // kMaxContexts + width for a field) and the value in LEB128, in chunks
  // of kChunk bytes that never split a symbol (a growing vector would copy
  // them all at each doubling).
  static constexpr size_t kChunk = size_t{1} << 20;
  std::vector<Bytes> symbols_;
};

/// Reads a compact stream written by CompactStreamWriter. Every read
/// returns false, without reading past the span, on a truncated or
/// malformed code.
class CompactStreamReader {
 public:
  /// Reads the `contexts` order bytes. \return false when they are missing
  /// or an order exceeds kCompactMaxOrder.
  bool start(const uint8_t* data, size_t size, int contexts);

  bool golomb(int ctx, uint64_t* value);
  bool bits(int width, uint64_t* value);

  /// Bits not read yet: a lower bound for counts (each code takes >= 1 bit).
  uint64_t bits_left() const { return total_bits_ - reader_.bits_consumed(); }
  /// True when the rest of the last byte is zero and no byte follows.
  bool at_clean_end() const {
    return reader_.padding_is_zero() && reader_.bytes_consumed() == size_;
  }

 private:
  std::vector<int> orders_;
  BitReader reader_{nullptr, 0};
  size_t size_ = 0;
  uint64_t total_bits_ = 0;
};

/// The checks every compact codec of a kind `tag` shares (errors are that
/// section's LBK-E023 "compact: ..." and, for the writer, kUnsupported).
///
/// The encoder's: the kind's reference writer must give back `raw` byte
/// for byte from the decoded structure (`canonical`), since the decoder
/// rebuilds raw payloads with that writer; `widths` names what the writer
/// chooses ("degree width").
Status require_canonical_layout(const char* tag, const Bytes& canonical, const uint8_t* raw,
                                size_t raw_size, const char* widths);
/// The decoder's first: a version byte equal to `version`, then at least
/// `fixed_bytes` bytes of fixed fields.
Status check_compact_start(const char* tag, const uint8_t* data, size_t size, size_t fixed_bytes,
                           uint8_t version);
/// The decoder's last: the stream ends cleanly, the writer accepts the
/// decoded `structure` (its refusal is a malformed payload) and the raw
/// payload it gives starts with the stored `fixed_bytes` fixed fields.
Result<Bytes> finish_compact_decode(const char* tag, const CompactStreamReader& in,
                                    Result<Bytes> raw, const uint8_t* fixed, size_t fixed_bytes,
                                    const char* structure);

}  // namespace lodbake
