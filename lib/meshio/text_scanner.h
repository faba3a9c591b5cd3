// TextScanner: a bounded cursor over the bytes of a text mesh file (OBJ, OFF,
// ASCII PLY, ASCII STL), shared by every text reader so that they all skip,
// tokenize and parse numbers the same way and never read past the end.
//
// Choices made where the formats are vague:
// - Line ends are "\n", "\r\n" and a lone "\r"; each counts as one line, so
//   line numbers in messages match what editors show for all three styles.
// - Blanks are space, tab, vertical tab and form feed. A "\\" right before a
//   line end joins the lines only when the reader enables it (OBJ does).
// - Numbers are parsed with std::from_chars (locale-independent, exact:
//   reading a float printed by std::to_chars gives the same float back). A
//   leading '+' is accepted. The spellings nan, inf and infinity (any case,
//   signed, "nan(...)") are parsed into NaN and infinity rather than reported
//   as malformed, so the caller can say precisely what is wrong ("non-finite
//   coordinate") or leave them for the mesh check; the OBJ and OFF readers
//   reject them. Decimal values too small for a float become 0 or a
//   subnormal; values too large for a float are kOutOfRange.
// - Integers report overflow as kOutOfRange instead of wrapping.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "formats/support/status.h"

namespace lodbake {

/// Why a number could not be read.
enum class NumberStatus {
  kOk,
  kMissing,     // no token: the line (or the file) ended first
  kMalformed,   // the token is not a number of the requested kind
  kOutOfRange,  // a number, but it does not fit the requested type
};

/// Parses all of `text` (no surrounding blanks) as a number. `text` must be
/// the whole token: "1.5x" is kMalformed.
NumberStatus parse_float(std::string_view text, float* out);
NumberStatus parse_double(std::string_view text, double* out);
NumberStatus parse_int64(std::string_view text, int64_t* out);
NumberStatus parse_uint64(std::string_view text, uint64_t* out);

/// `text` quoted for an error message: non-printable bytes as \xNN, cut to
/// at most 32 characters (with "..." appended when cut).
std::string quote_token(std::string_view text);

class TextScanner {
 public:
  /// Scans `size` bytes at `data`; the bytes must outlive the scanner.
  TextScanner(const uint8_t* data, size_t size);

  /// Enables "\\" + line end as a blank (OBJ line continuation).
  void set_line_continuation(bool enabled) { line_continuation_ = enabled; }

  bool at_end() const { return cur_ == end_; }
  /// Byte offset of the cursor from the start of the text.
  size_t offset() const { return static_cast<size_t>(cur_ - begin_); }
  size_t remaining() const { return static_cast<size_t>(end_ - cur_); }
  /// 1-based line number of the cursor.
  uint64_t line() const { return line_; }
  /// Numbers the line at the cursor `line` (a scanner over a later part of
  /// a file, as the streaming readers make).
  void set_line(uint64_t line) { line_ = line; }
  /// The byte at the cursor, or 0 at the end.
  char peek() const { return cur_ == end_ ? '\0' : static_cast<char>(*cur_); }
  /// True at a line end or at the end of the text.
  bool at_line_end() const { return cur_ == end_ || *cur_ == '\n' || *cur_ == '\r'; }

  /// Skips blanks (not line ends).
  void skip_blanks();
  /// Skips blanks and line ends.
  void skip_whitespace();
  /// Moves past the next line end (or to the end of the text).
  void skip_line();
  /// Skips whitespace and comments: a `comment` byte where a token would
  /// start runs to its line end.
  void skip_whitespace_and_comments(char comment);
  /// Moves one byte forward (no-op at the end). Consumes a line end as one
  /// line ("\r\n" together).
  void advance();

  /// Skips blanks, then returns the bytes up to the next blank, line end or
  /// end of text; empty when the line has no more tokens. Never crosses a
  /// line end.
  std::string_view token();
  /// Like token() but also stops before `stop` (e.g. '#' for an OFF comment
  /// right after a number).
  std::string_view token_until(char stop);

  /// Skips blanks, then reads one token and parses it whole. On failure the
  /// cursor is after the token and last_token() holds it for the message.
  NumberStatus read_float(float* out);
  NumberStatus read_double(double* out);
  NumberStatus read_int64(int64_t* out);
  NumberStatus read_uint64(uint64_t* out);

  /// The token the last read_*() or token() call looked at.
  std::string_view last_token() const { return last_token_; }

  /// A message for a failed read: "line 7: expected <what>, found 'abc'",
  /// "line 7: expected <what>, found the end of the line", or
  /// "line 7: <what> 1e99 is out of range".
  std::string number_error(NumberStatus status, const char* what) const;

 private:
  using ByteTable = std::array<bool, 256>;
  static const ByteTable kEndsToken;
  // token() and token_until(): `stop` is '\n' for none.
  std::string_view scan_token(uint8_t stop);
  bool is_blank(uint8_t c) const { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
  // True when a line continuation ("\\" + line end) starts at the cursor.
  bool at_continuation() const;

  const uint8_t* begin_;
  const uint8_t* cur_;
  const uint8_t* end_;
  uint64_t line_ = 1;
  bool line_continuation_ = false;
  std::string_view last_token_;
};

/// Prepares the bytes of a text mesh file for TextScanner: skips a UTF-8
/// byte-order mark; decodes UTF-16 (little- or big-endian, recognised by its
/// byte-order mark) into `storage` when every code unit is ASCII, replacing
/// others by '?' (they can only occur in comments and names, which the
/// readers ignore); rejects any other text containing a NUL byte as binary
/// data. On success `*data` and `*size` describe the text to scan and, when
/// it was decoded, `*note` says so (otherwise it is left empty).
Status prepare_text(const uint8_t** data, size_t* size, std::vector<uint8_t>* storage,
                    std::string* note);

}  // namespace lodbake
