// Fuzz target for gunzip with a 16 MiB output bound. On success the output
// respects the bound and compressing it again with zlib and decompressing
// gives it back; input without the gzip magic must fail. On failure the
// message must be one non-empty line.
#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <string>

#include "lib/meshio/gzip.h"

namespace {

constexpr uint64_t kLimit = uint64_t{1} << 24;

void require(bool condition) {
  if (!condition) std::abort();
}

lodbake::Bytes compress(const lodbake::Bytes& plain) {
  z_stream zs{};
  require(deflateInit2(&zs, 1, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) == Z_OK);
  lodbake::Bytes out(deflateBound(&zs, static_cast<uLong>(plain.size())));
  zs.next_in = const_cast<Bytef*>(plain.data());
  zs.avail_in = static_cast<uInt>(plain.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  require(deflate(&zs, Z_FINISH) == Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::Result<lodbake::Bytes> result = lodbake::gunzip(data, size, kLimit);
  if (!result.is_ok()) {
    const std::string& message = result.status().message();
    require(!message.empty() && message.find('\n') == std::string::npos);
    return 0;
  }
  require(lodbake::is_gzip(data, size));
  const lodbake::Bytes& plain = result.value();
  require(plain.size() <= kLimit);
  lodbake::Bytes packed = compress(plain);
  lodbake::Result<lodbake::Bytes> again = lodbake::gunzip(packed.data(), packed.size(), kLimit);
  require(again.is_ok() && again.value() == plain);
  return 0;
}
