// Value source for the body of an ASCII PLY file, used by ply_reader.cpp's
// element readers. Values are whitespace-separated tokens; line breaks are
// not significant (some writers wrap long lists), but they are counted so
// that messages name the line. Integer values must fit their declared type.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "formats/support/status.h"
#include "lib/meshio/ply_header.h"
#include "lib/meshio/text_scanner.h"

namespace lodbake {

class PlyAsciiSource {
 public:
  PlyAsciiSource(const uint8_t* data, size_t size, size_t body_offset, uint64_t body_first_line)
      : scanner_(data + body_offset, size - body_offset), line_offset_(body_first_line - 1) {}

  bool read_float(PlyType type, float* out) {
    scanner_.skip_whitespace();
    if (type == PlyType::kFloat32) {
      status_ = scanner_.read_float(out);
    } else if (type == PlyType::kFloat64) {
      double wide = 0;
      status_ = scanner_.read_double(&wide);
      if (status_ == NumberStatus::kOk) {
        *out = static_cast<float>(wide);
        if (std::isfinite(wide) && !std::isfinite(*out)) status_ = NumberStatus::kOutOfRange;
      }
    } else {
      int64_t value = 0;
      if (!read_int(type, &value)) return false;
      *out = static_cast<float>(value);
    }
    expected_ = type;
    return status_ == NumberStatus::kOk;
  }

  bool read_int(PlyType type, int64_t* out) {
    scanner_.skip_whitespace();
    status_ = scanner_.read_int64(out);
    if (status_ == NumberStatus::kOk && !fits(type, *out)) status_ = NumberStatus::kOutOfRange;
    expected_ = type;
    return status_ == NumberStatus::kOk;
  }

  /// Reads and drops a value, still checking that it is a number of `type`.
  bool skip(PlyType type) {
    if (ply_type_is_integer(type)) {
      int64_t ignored;
      return read_int(type, &ignored);
    }
    if (type == PlyType::kFloat64) {
      // Any double is fine here, even one that a float cannot hold.
      scanner_.skip_whitespace();
      double ignored;
      status_ = scanner_.read_double(&ignored);
      expected_ = type;
      return status_ == NumberStatus::kOk;
    }
    float ignored;
    return read_float(type, &ignored);
  }
  bool skip_values(PlyType type, uint64_t count) {
    for (uint64_t i = 0; i < count; ++i) {
      if (!skip(type)) return false;
    }
    return true;
  }

  /// The most values a list could still hold: each takes at least one
  /// character and one separator (the last one may end the file).
  uint64_t max_values(PlyType /*type*/) const { return (uint64_t{scanner_.remaining()} + 1) / 2; }
  uint64_t remaining() const { return scanner_.remaining(); }

  /// A cheap handle on the position of the next value (its line number).
  uint64_t mark() {
    scanner_.skip_whitespace();
    return line();
  }
  static std::string where(uint64_t mark) { return "line " + std::to_string(mark); }

  /// The error for the last failed read in `context` (e.g. "vertex 4 of 8").
  Status read_failure(const std::string& context) const {
    std::string message = where(line()) + ": ";
    switch (status_) {
      case NumberStatus::kMissing:
        message += "the file ends inside " + context;
        break;
      case NumberStatus::kOutOfRange:
        message += quote_token(scanner_.last_token()) + " does not fit type " +
                   ply_type_name(expected_) + " (" + context + ")";
        break;
      case NumberStatus::kMalformed:
      case NumberStatus::kOk:
        message += std::string("expected ") +
                   (ply_type_is_integer(expected_) ? "an integer" : "a number") + ", found " +
                   quote_token(scanner_.last_token()) + " (" + context + ")";
        break;
    }
    return invalid_input(message);
  }

  /// Non-blank bytes after the last element, or 0.
  uint64_t trailing_bytes() {
    scanner_.skip_whitespace();
    return scanner_.remaining();
  }

 private:
  uint64_t line() const { return scanner_.line() + line_offset_; }

  static bool fits(PlyType type, int64_t v) {
    switch (type) {
      case PlyType::kInt8:
        return v >= -128 && v <= 127;
      case PlyType::kUint8:
        return v >= 0 && v <= 255;
      case PlyType::kInt16:
        return v >= -32768 && v <= 32767;
      case PlyType::kUint16:
        return v >= 0 && v <= 65535;
      case PlyType::kInt32:
        return v >= INT32_MIN && v <= INT32_MAX;
      case PlyType::kUint32:
        return v >= 0 && v <= UINT32_MAX;
      case PlyType::kFloat32:
      case PlyType::kFloat64:
        return false;
    }
    return false;
  }

  TextScanner scanner_;
  uint64_t line_offset_;
  NumberStatus status_ = NumberStatus::kOk;
  PlyType expected_ = PlyType::kFloat32;
};

}  // namespace lodbake
