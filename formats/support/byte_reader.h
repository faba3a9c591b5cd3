// Bounded reading and writing of fixed-size little- and big-endian values.
// ByteReader never reads past its span: every read checks the remaining
// length first and reports failure instead of touching memory, so parsers
// of hostile files stay in bounds by construction.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace lodbake {

enum class Endian { kLittle, kBig };

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  size_t position() const { return pos_; }
  size_t size() const { return size_; }
  size_t remaining() const { return size_ - pos_; }
  bool at_end() const { return pos_ == size_; }
  const uint8_t* current() const { return data_ + pos_; }

  // Moves to an absolute offset; false (and no move) when it is past the end.
  bool seek(uint64_t offset) {
    if (offset > size_) return false;
    pos_ = static_cast<size_t>(offset);
    return true;
  }
  bool skip(uint64_t count) {
    if (count > remaining()) return false;
    pos_ += static_cast<size_t>(count);
    return true;
  }
  bool read_bytes(void* out, size_t count) {
    if (count > remaining()) return false;
    if (count != 0) std::memcpy(out, data_ + pos_, count);
    pos_ += count;
    return true;
  }

  // Reads an arithmetic value stored with the given byte order.
  template <typename T>
  bool read(T* out, Endian endian = Endian::kLittle) {
    static_assert(std::is_arithmetic<T>::value, "read() takes arithmetic types");
    uint8_t raw[sizeof(T)];
    if (!read_bytes(raw, sizeof(T))) return false;
    if (endian == Endian::kBig) reverse(raw);
    std::memcpy(out, raw, sizeof(T));
    return true;
  }

 private:
  template <size_t N>
  static void reverse(uint8_t (&raw)[N]) {
    for (size_t i = 0; i < N / 2; ++i)
      std::swap(raw[i], raw[N - 1 - i]);
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

// Appends little-endian values to a byte vector (all lodbake files are
// little-endian; the host is assumed little-endian, checked at compile time).
class ByteWriter {
 public:
  explicit ByteWriter(std::vector<uint8_t>* out) : out_(out) {}

  template <typename T>
  void write(T value) {
    static_assert(std::is_arithmetic<T>::value, "write() takes arithmetic types");
    // Grown, then filled: a range insert into an empty vector, once inlined,
    // trips g++ 12's -Wstringop-overflow (a false positive).
    const size_t at = out_->size();
    out_->resize(at + sizeof(T));
    std::memcpy(out_->data() + at, &value, sizeof(T));
  }
  void write_bytes(const void* data, size_t count) {
    const auto* bytes = static_cast<const uint8_t*>(data);
    out_->insert(out_->end(), bytes, bytes + count);
  }
  size_t size() const { return out_->size(); }

 private:
  std::vector<uint8_t>* out_;
};

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "lodbake assumes a little-endian host (x86-64, AArch64)");

}  // namespace lodbake
