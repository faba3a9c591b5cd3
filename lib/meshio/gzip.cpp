// gzip decompression through zlib's inflate with gzip framing
// (windowBits 16 + MAX_WBITS, so zlib checks the header, CRC-32 and length).
// Choices where gzip leaves room: concatenated members are decompressed in
// order like `gzip -d` does; bytes after the last member that do not start
// another member are an error (gzip only warns), since a mesh file with a
// damaged tail is better refused than half-read. The output grows by
// doubling up to max_output + 1 bytes: producing that last byte proves the
// bound was exceeded without ever allocating more than the bound.
#include "lib/meshio/gzip.h"

#include <zlib.h>

#include <algorithm>
#include <climits>
#include <new>
#include <string>

namespace lodbake {
namespace {

// Deflate cannot expand data by more than about 1032:1, so the size recorded
// in a gzip trailer is only trusted as a reservation hint below that.
constexpr uint64_t kMaxDeflateRatio = 1032;
constexpr size_t kMinChunk = size_t{1} << 16;

class InflateStream {
 public:
  InflateStream() = default;
  InflateStream(const InflateStream&) = delete;
  InflateStream& operator=(const InflateStream&) = delete;
  ~InflateStream() {
    if (initialised_) inflateEnd(&stream_);
  }
  bool init() {
    initialised_ = inflateInit2(&stream_, 16 + MAX_WBITS) == Z_OK;
    return initialised_;
  }
  z_stream* get() { return &stream_; }

 private:
  z_stream stream_{};
  bool initialised_ = false;
};

uint64_t trailer_size_hint(const uint8_t* data, size_t size, uint64_t limit) {
  if (size < 18) return 0;
  const uint8_t* t = data + size - 4;
  uint64_t isize =
      uint64_t{t[0]} | uint64_t{t[1]} << 8 | uint64_t{t[2]} << 16 | uint64_t{t[3]} << 24;
  // One spare byte so that an exact hint ends without a needless regrowth.
  return std::min({isize + 1, limit, static_cast<uint64_t>(size) * kMaxDeflateRatio});
}

Result<Bytes> gunzip_impl(const uint8_t* data, size_t size, uint64_t max_output) {
  InflateStream inflater;
  if (!inflater.init()) return runtime_error("zlib could not start a gzip decoder");
  z_stream* zs = inflater.get();

  // One byte more than allowed, so that overflowing the bound is observable.
  const uint64_t limit = std::min<uint64_t>(max_output, static_cast<uint64_t>(SIZE_MAX) - 1) + 1;
  Bytes out;
  out.resize(static_cast<size_t>(std::max<uint64_t>(std::min<uint64_t>(kMinChunk, limit),
                                                    trailer_size_hint(data, size, limit))));
  size_t in_pos = 0;
  size_t produced = 0;
  for (;;) {
    if (produced == out.size()) {
      if (out.size() >= limit) {
        return invalid_input("gzip data decompresses to more than " + std::to_string(max_output) +
                             " bytes");
      }
      uint64_t grown = std::max<uint64_t>(uint64_t{out.size()} * 2, kMinChunk);
      out.resize(static_cast<size_t>(std::min(grown, limit)));
    }
    zs->next_in = const_cast<Bytef*>(data + in_pos);
    zs->avail_in = static_cast<uInt>(std::min<size_t>(size - in_pos, UINT_MAX));
    zs->next_out = out.data() + produced;
    zs->avail_out = static_cast<uInt>(std::min<size_t>(out.size() - produced, UINT_MAX));
    const uInt in_before = zs->avail_in;
    const uInt out_before = zs->avail_out;
    int rc = inflate(zs, Z_NO_FLUSH);
    in_pos += in_before - zs->avail_in;
    produced += out_before - zs->avail_out;

    if (rc == Z_STREAM_END) {
      if (in_pos == size) break;
      if (!is_gzip(data + in_pos, size - in_pos)) {
        return invalid_input(std::to_string(size - in_pos) +
                             " bytes after the end of the gzip stream at byte " +
                             std::to_string(in_pos) + " are not another gzip member");
      }
      if (inflateReset(zs) != Z_OK) return runtime_error("zlib could not restart its decoder");
      continue;
    }
    if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT) {
      return invalid_input("corrupt gzip data near input byte " + std::to_string(in_pos) + ": " +
                           (zs->msg != nullptr ? zs->msg : "invalid deflate stream"));
    }
    if (rc == Z_MEM_ERROR) return runtime_error("out of memory while decompressing gzip data");
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      return runtime_error("zlib inflate failed with code " + std::to_string(rc));
    }
    // Output room left but no input to fill it: the stream stops early.
    if (in_pos == size && produced < out.size()) {
      return invalid_input("gzip data is truncated: the stream ends at byte " +
                           std::to_string(size) + " before its end marker and checksum");
    }
  }
  // The last member may end exactly on the extra byte the buffer allowed.
  if (produced > max_output) {
    return invalid_input("gzip data decompresses to more than " + std::to_string(max_output) +
                         " bytes");
  }
  out.resize(produced);
  out.shrink_to_fit();
  return out;
}

}  // namespace

bool is_gzip(const uint8_t* data, size_t size) {
  return size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
}

bool is_gzip(const Bytes& bytes) {
  return is_gzip(bytes.data(), bytes.size());
}

Result<Bytes> gunzip(const uint8_t* data, size_t size, uint64_t max_output) {
  if (!is_gzip(data, size)) return invalid_input("not gzip data (no 1f 8b magic)");
  try {
    return gunzip_impl(data, size, max_output);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while decompressing gzip data");
  }
}

}  // namespace lodbake
