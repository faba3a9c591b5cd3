// TextScanner and the number parsers shared by the text mesh readers; the
// choices (line ends, '+' signs, nan/inf spellings, underflow) are listed in
// text_scanner.h.
#include "lib/meshio/text_scanner.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <system_error>

namespace lodbake {
namespace {

// std::from_chars rejects a leading '+'; text formats allow it. A '+' must be
// followed by the number itself (not by another sign).
bool strip_plus(std::string_view* text) {
  if (text->empty() || (*text)[0] != '+') return true;
  text->remove_prefix(1);
  return !text->empty() && (*text)[0] != '+' && (*text)[0] != '-';
}

// True when the decimal exponent of an out-of-range token is negative, i.e.
// the value underflowed rather than overflowed.
bool has_negative_exponent(std::string_view text) {
  size_t e = text.find_first_of("eE");
  return e != std::string_view::npos && e + 1 < text.size() && text[e + 1] == '-';
}

template <typename T>
NumberStatus parse_integer(std::string_view text, T* out) {
  if (!strip_plus(&text) || text.empty()) return NumberStatus::kMalformed;
  T value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) {
    // from_chars stops at the end of the digits even when they overflow;
    // anything after them still makes the token malformed.
    return ptr == text.data() + text.size() ? NumberStatus::kOutOfRange : NumberStatus::kMalformed;
  }
  if (ec != std::errc() || ptr != text.data() + text.size()) return NumberStatus::kMalformed;
  *out = value;
  return NumberStatus::kOk;
}

}  // namespace

// Blanks, line ends and the backslash that may start a continuation.
const TextScanner::ByteTable TextScanner::kEndsToken = [] {
  ByteTable table{};
  for (uint8_t c : {' ', '\t', '\v', '\f', '\n', '\r', '\\'})
    table[c] = true;
  return table;
}();

NumberStatus parse_double(std::string_view text, double* out) {
  if (!strip_plus(&text) || text.empty()) return NumberStatus::kMalformed;
  double value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ptr != text.data() + text.size() ||
      (ec != std::errc() && ec != std::errc::result_out_of_range))
    return NumberStatus::kMalformed;
  if (ec == std::errc::result_out_of_range) {
    if (!has_negative_exponent(text)) return NumberStatus::kOutOfRange;
    value = text[0] == '-' ? -0.0 : 0.0;
  }
  *out = value;
  return NumberStatus::kOk;
}

NumberStatus parse_float(std::string_view text, float* out) {
  std::string_view digits = text;
  if (!strip_plus(&digits) || digits.empty()) return NumberStatus::kMalformed;
  float value = 0;
  auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ptr != digits.data() + digits.size() ||
      (ec != std::errc() && ec != std::errc::result_out_of_range))
    return NumberStatus::kMalformed;
  if (ec == std::errc::result_out_of_range) {
    // Decide between underflow (a value that rounds to zero) and overflow
    // through the double parse, which has the range to tell them apart.
    double wide = 0;
    NumberStatus status = parse_double(digits, &wide);
    if (status != NumberStatus::kOk) return status;
    if (std::fabs(wide) > static_cast<double>(std::numeric_limits<float>::max()))
      return NumberStatus::kOutOfRange;
    value = static_cast<float>(wide);
  }
  *out = value;
  return NumberStatus::kOk;
}

NumberStatus parse_int64(std::string_view text, int64_t* out) {
  return parse_integer(text, out);
}

NumberStatus parse_uint64(std::string_view text, uint64_t* out) {
  // from_chars for unsigned types rejects '-' already; "-0" is malformed too.
  return parse_integer(text, out);
}

std::string quote_token(std::string_view text) {
  constexpr size_t kMaxShown = 32;
  std::string out = "'";
  size_t shown = 0;
  for (char ch : text) {
    if (shown == kMaxShown) {
      out += "...";
      break;
    }
    auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f) {
      out += ch;
    } else {
      static const char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
    ++shown;
  }
  out += "'";
  return out;
}

TextScanner::TextScanner(const uint8_t* data, size_t size)
    : begin_(data), cur_(data), end_(data + size) {}

bool TextScanner::at_continuation() const {
  if (!line_continuation_ || cur_ == end_ || *cur_ != '\\') return false;
  return cur_ + 1 != end_ && (cur_[1] == '\n' || cur_[1] == '\r');
}

void TextScanner::advance() {
  if (cur_ == end_) return;
  uint8_t c = *cur_++;
  if (c == '\n') {
    ++line_;
  } else if (c == '\r') {
    if (cur_ != end_ && *cur_ == '\n') ++cur_;
    ++line_;
  }
}

void TextScanner::skip_blanks() {
  for (;;) {
    while (cur_ != end_ && is_blank(*cur_))
      ++cur_;
    if (!at_continuation()) return;
    ++cur_;     // the backslash
    advance();  // the line end
  }
}

void TextScanner::skip_whitespace() {
  for (;;) {
    skip_blanks();
    if (cur_ == end_ || (*cur_ != '\n' && *cur_ != '\r')) return;
    advance();
  }
}

void TextScanner::skip_line() {
  while (cur_ != end_ && *cur_ != '\n' && *cur_ != '\r')
    ++cur_;
  advance();
}

void TextScanner::skip_whitespace_and_comments(char comment) {
  for (;;) {
    skip_whitespace();
    if (cur_ == end_ || *cur_ != static_cast<uint8_t>(comment)) return;
    skip_line();
  }
}

// Scans a token's bytes: stops at a blank, a line end, `stop` or a line
// continuation. Bytes of a number stop nothing, so one table lookup per byte
// decides, and only a backslash needs a second look.
std::string_view TextScanner::scan_token(uint8_t stop) {
  skip_blanks();
  const uint8_t* start = cur_;
  for (;;) {
    while (cur_ != end_ && !kEndsToken[*cur_] && *cur_ != stop)
      ++cur_;
    if (cur_ == end_ || *cur_ != '\\' || stop == '\\' || at_continuation()) break;
    ++cur_;  // a backslash inside the token
  }
  last_token_ =
      std::string_view(reinterpret_cast<const char*>(start), static_cast<size_t>(cur_ - start));
  return last_token_;
}

std::string_view TextScanner::token() {
  return scan_token('\n');
}

std::string_view TextScanner::token_until(char stop) {
  return scan_token(static_cast<uint8_t>(stop));
}

NumberStatus TextScanner::read_float(float* out) {
  std::string_view text = token();
  return text.empty() ? NumberStatus::kMissing : parse_float(text, out);
}

NumberStatus TextScanner::read_double(double* out) {
  std::string_view text = token();
  return text.empty() ? NumberStatus::kMissing : parse_double(text, out);
}

NumberStatus TextScanner::read_int64(int64_t* out) {
  std::string_view text = token();
  return text.empty() ? NumberStatus::kMissing : parse_int64(text, out);
}

NumberStatus TextScanner::read_uint64(uint64_t* out) {
  std::string_view text = token();
  return text.empty() ? NumberStatus::kMissing : parse_uint64(text, out);
}

std::string TextScanner::number_error(NumberStatus status, const char* what) const {
  std::string message = "line " + std::to_string(line_) + ": ";
  switch (status) {
    case NumberStatus::kMissing:
      message += std::string("expected ") + what + ", found the end of the " +
                 (cur_ == end_ ? "file" : "line");
      break;
    case NumberStatus::kOutOfRange:
      message += std::string(what) + " " + quote_token(last_token_) + " is out of range";
      break;
    case NumberStatus::kMalformed:
    case NumberStatus::kOk:
      message += std::string("expected ") + what + ", found " + quote_token(last_token_);
      break;
  }
  return message;
}

Status prepare_text(const uint8_t** data, size_t* size, std::vector<uint8_t>* storage,
                    std::string* note) {
  const uint8_t* bytes = *data;
  size_t count = *size;
  if (count >= 3 && bytes[0] == 0xef && bytes[1] == 0xbb && bytes[2] == 0xbf) {
    bytes += 3;
    count -= 3;
  } else if (count >= 2 &&
             ((bytes[0] == 0xfe && bytes[1] == 0xff) || (bytes[0] == 0xff && bytes[1] == 0xfe))) {
    const bool big_endian = bytes[0] == 0xfe;
    if (count % 2 != 0)
      return invalid_input("UTF-16 text (byte-order mark " +
                           std::string(big_endian ? "big" : "little") +
                           "-endian) has an odd number of bytes");
    storage->clear();
    storage->reserve(count / 2 - 1);
    for (size_t i = 2; i < count; i += 2) {
      unsigned unit = big_endian ? (unsigned{bytes[i]} << 8 | bytes[i + 1])
                                 : (unsigned{bytes[i + 1]} << 8 | bytes[i]);
      if (unit == 0)
        return invalid_input("UTF-16 text contains a NUL character at byte " + std::to_string(i));
      storage->push_back(unit < 0x80 ? static_cast<uint8_t>(unit) : uint8_t{'?'});
    }
    *data = storage->data();
    *size = storage->size();
    *note = std::string("decoded UTF-16") + (big_endian ? "BE" : "LE") + " text";
    return Status::ok();
  }
  const void* nul = count == 0 ? nullptr : std::memchr(bytes, 0, count);
  if (nul != nullptr) {
    size_t at = static_cast<size_t>(static_cast<const uint8_t*>(nul) - *data);
    return invalid_input("binary data where text was expected: NUL byte at byte " +
                         std::to_string(at));
  }
  *data = bytes;
  *size = count;
  return Status::ok();
}

}  // namespace lodbake
