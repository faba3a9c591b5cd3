// Value source for the body of a binary PLY file (either byte order), used
// by ply_reader.cpp's element readers. Every read is bounds-checked through
// ByteReader; a failed read means the body ended early.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "formats/support/byte_reader.h"
#include "formats/support/status.h"
#include "lib/meshio/ply_header.h"

namespace lodbake {

class PlyBinarySource {
 public:
  PlyBinarySource(const uint8_t* data, size_t size, size_t body_offset, Endian endian)
      : reader_(data, size), endian_(endian) {
    reader_.seek(body_offset);
  }

  /// Reads one value of `type` converted to float (double values are rounded
  /// to the nearest float).
  bool read_float(PlyType type, float* out) {
    switch (type) {
      case PlyType::kFloat32:
        return reader_.read(out, endian_);
      case PlyType::kFloat64: {
        double d;
        if (!reader_.read(&d, endian_)) return false;
        *out = static_cast<float>(d);
        return true;
      }
      default: {
        int64_t i;
        if (!read_int(type, &i)) return false;
        *out = static_cast<float>(i);
        return true;
      }
    }
  }

  /// Reads one value of integer `type`.
  bool read_int(PlyType type, int64_t* out) {
    switch (type) {
      case PlyType::kInt8:
        return read_as<int8_t>(out);
      case PlyType::kUint8:
        return read_as<uint8_t>(out);
      case PlyType::kInt16:
        return read_as<int16_t>(out);
      case PlyType::kUint16:
        return read_as<uint16_t>(out);
      case PlyType::kInt32:
        return read_as<int32_t>(out);
      case PlyType::kUint32:
        return read_as<uint32_t>(out);
      case PlyType::kFloat32:
      case PlyType::kFloat64:
        break;
    }
    return false;
  }

  bool skip(PlyType type) { return reader_.skip(ply_type_size(type)); }
  /// Skips `count` values of `type` (count is already bounded by remaining()).
  bool skip_values(PlyType type, uint64_t count) {
    return reader_.skip(count * ply_type_size(type));
  }

  /// The most entries of `type` a list could still hold.
  uint64_t max_values(PlyType type) const { return reader_.remaining() / ply_type_size(type); }
  uint64_t remaining() const { return reader_.remaining(); }
  /// A cheap handle on the current position, turned into text by where()
  /// only when a message needs it.
  uint64_t mark() const { return reader_.position(); }
  static std::string where(uint64_t mark) { return "byte " + std::to_string(mark); }
  /// The error for a failed read in `context` (e.g. "face 3 of 4").
  Status read_failure(const std::string& context) const {
    return invalid_input("binary body ends at byte " + std::to_string(reader_.size()) + " inside " +
                         context);
  }
  /// Bytes after the last element, or 0.
  uint64_t trailing_bytes() const { return reader_.remaining(); }

 private:
  template <typename T>
  bool read_as(int64_t* out) {
    T value;
    if (!reader_.read(&value, endian_)) return false;
    *out = static_cast<int64_t>(value);
    return true;
  }

  ByteReader reader_;
  Endian endian_;
};

}  // namespace lodbake
