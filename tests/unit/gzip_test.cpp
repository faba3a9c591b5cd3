// gunzip: the Stanford .ply.gz files of ../shared/data, streams made here
// with zlib's own compressor, and broken streams (truncated, corrupt,
// trailing bytes, over the size bound).
#include "lib/meshio/gzip.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>

#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::expect_rejected;
using testing_util::shared_file;

Bytes gzip(const Bytes& plain, int level = 6) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, level, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  Bytes out(deflateBound(&zs, static_cast<uLong>(plain.size())));
  zs.next_in = const_cast<Bytef*>(plain.data());
  zs.avail_in = static_cast<uInt>(plain.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

Bytes sample(size_t size) {
  Bytes out(size);
  uint32_t state = 12345;
  for (size_t i = 0; i < size; ++i) {
    state = state * 1103515245u + 12345u;
    // Mostly text-like bytes, so that deflate has something to compress.
    out[i] = static_cast<uint8_t>("0123456789 .-\n"[(state >> 16) % 14]);
  }
  return out;
}

Result<Bytes> gunzip_bytes(const Bytes& data, uint64_t max_output = kDefaultGunzipLimit) {
  return gunzip(data.data(), data.size(), max_output);
}

TEST(Gzip, RecognisesTheMagic) {
  EXPECT_TRUE(is_gzip(Bytes{0x1f, 0x8b}));
  EXPECT_FALSE(is_gzip(Bytes{0x1f}));
  EXPECT_FALSE(is_gzip(Bytes{}));
  EXPECT_FALSE(is_gzip(Bytes{'p', 'l', 'y'}));
  expect_rejected(gunzip_bytes(Bytes{'p', 'l', 'y'}), "not gzip data");
}

TEST(Gzip, StanfordPlyGzFilesDecompressToTheirTrailerSize) {
  for (const char* name : {"stanford_dragon_vrip_res4.ply.gz", "stanford_dragon_vrip_res3.ply.gz",
                           "stanford_dragon_vrip_res2.ply.gz"}) {
    SCOPED_TRACE(name);
    const Bytes packed = shared_file(std::string("meshes/") + name);
    ASSERT_TRUE(is_gzip(packed));
    Result<Bytes> plain = gunzip_bytes(packed);
    ASSERT_TRUE(plain.is_ok()) << plain.status().message();
    const uint8_t* t = packed.data() + packed.size() - 4;
    uint32_t isize =
        uint32_t{t[0]} | uint32_t{t[1]} << 8 | uint32_t{t[2]} << 16 | uint32_t{t[3]} << 24;
    EXPECT_EQ(plain.value().size(), isize);
    EXPECT_EQ(std::string(plain.value().begin(), plain.value().begin() + 4), "ply\n");
  }
}

TEST(Gzip, RoundTripsAndConcatenatesMembers) {
  for (size_t size : {size_t{0}, size_t{1}, size_t{1000}, size_t{300000}}) {
    Bytes plain = sample(size);
    Result<Bytes> back = gunzip_bytes(gzip(plain));
    ASSERT_TRUE(back.is_ok()) << back.status().message();
    EXPECT_EQ(back.value(), plain);
  }
  Bytes a = sample(5000);
  Bytes b = sample(7);
  Bytes both = gzip(a);
  Bytes second = gzip(b, 0);
  both.insert(both.end(), second.begin(), second.end());
  Result<Bytes> joined = gunzip_bytes(both);
  ASSERT_TRUE(joined.is_ok()) << joined.status().message();
  Bytes expected = a;
  expected.insert(expected.end(), b.begin(), b.end());
  EXPECT_EQ(joined.value(), expected);
}

TEST(Gzip, OutputIsBoundedBeforeItIsAllocated) {
  Bytes zeros(1 << 20, 0);
  Bytes packed = gzip(zeros, 9);
  ASSERT_LT(packed.size(), 2000u);
  EXPECT_TRUE(gunzip_bytes(packed, zeros.size()).is_ok());
  expect_rejected(gunzip_bytes(packed, zeros.size() - 1),
                  "gzip data decompresses to more than 1048575 bytes");
  expect_rejected(gunzip_bytes(packed, 0), "decompresses to more than 0 bytes");
  // A forged trailer claiming 4 GiB - 1 bytes is only a hint: no 4 GiB buffer.
  Bytes forged = packed;
  for (size_t i = forged.size() - 4; i < forged.size(); ++i)
    forged[i] = 0xff;
  expect_rejected(gunzip_bytes(forged), "corrupt gzip data");
}

TEST(Gzip, EveryTruncationIsRejected) {
  Bytes packed = gzip(sample(4000));
  for (size_t length = 2; length < packed.size(); ++length) {
    Result<Bytes> result = gunzip(packed.data(), length, kDefaultGunzipLimit);
    ASSERT_FALSE(result.is_ok()) << "length " << length;
    EXPECT_EQ(result.status().kind(), ErrorKind::kInvalidInput);
  }
  expect_rejected(gunzip(packed.data(), packed.size() - 3, kDefaultGunzipLimit),
                  "gzip data is truncated");
}

TEST(Gzip, CorruptionAndTrailingBytesAreRejected) {
  Bytes packed = gzip(sample(4000));
  Bytes flipped = packed;
  flipped[flipped.size() - 6] ^= 0x40;  // inside the CRC-32
  expect_rejected(gunzip_bytes(flipped), "corrupt gzip data");
  Bytes bad_method = packed;
  bad_method[2] = 7;  // compression method other than deflate
  expect_rejected(gunzip_bytes(bad_method), "corrupt gzip data near input byte");
  Bytes trailing = packed;
  trailing.push_back('x');
  trailing.push_back('y');
  expect_rejected(gunzip_bytes(trailing), "2 bytes after the end of the gzip stream");
  // Flipping any single byte never crashes; most are caught by the CRC.
  for (size_t i = 0; i < packed.size(); ++i) {
    Bytes copy = packed;
    copy[i] ^= 0xa5;
    Result<Bytes> result = gunzip_bytes(copy, 1 << 20);
    if (result.is_ok()) {
      EXPECT_LE(result.value().size(), size_t{1} << 20);
    }
  }
}

}  // namespace
}  // namespace lodbake
