// CRC-32C: published check values (RFC 3720 B.4), the incremental API, and
// the slicing-by-8 path against a bit-at-a-time reference at every alignment.
#include "formats/support/crc32c.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace lodbake {
namespace {

uint32_t reference_crc32c(const uint8_t* data, size_t size) {
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit)
      crc = (crc >> 1) ^ ((crc & 1u) ? 0x82F63B78u : 0u);
  }
  return ~crc;
}

TEST(Crc32c, CheckValue) {
  const char* text = "123456789";
  EXPECT_EQ(crc32c(reinterpret_cast<const uint8_t*>(text), 9), 0xE3069283u);
}

TEST(Crc32c, Rfc3720Vectors) {
  std::vector<uint8_t> zeros(32, 0x00);
  std::vector<uint8_t> ones(32, 0xFF);
  std::vector<uint8_t> ascending(32);
  std::vector<uint8_t> descending(32);
  for (int i = 0; i < 32; ++i) {
    ascending[i] = static_cast<uint8_t>(i);
    descending[i] = static_cast<uint8_t>(31 - i);
  }
  EXPECT_EQ(crc32c(zeros.data(), zeros.size()), 0x8A9136AAu);
  EXPECT_EQ(crc32c(ones.data(), ones.size()), 0x62A8AB43u);
  EXPECT_EQ(crc32c(ascending.data(), ascending.size()), 0x46DD794Eu);
  EXPECT_EQ(crc32c(descending.data(), descending.size()), 0x113FDB5Cu);
}

TEST(Crc32c, EmptyInputIsZero) {
  EXPECT_EQ(crc32c(nullptr, 0), 0u);
  EXPECT_EQ(crc32c_extend(0x12345678u, nullptr, 0), 0x12345678u);
}

TEST(Crc32c, MatchesBitwiseReferenceAtEveryAlignmentAndLength) {
  std::mt19937 rng(7);
  std::vector<uint8_t> data(300);
  for (auto& b : data)
    b = static_cast<uint8_t>(rng());
  for (size_t start = 0; start < 16; ++start) {
    for (size_t length = 0; start + length <= data.size(); length += 7) {
      ASSERT_EQ(crc32c(data.data() + start, length), reference_crc32c(data.data() + start, length))
          << "start " << start << " length " << length;
    }
  }
}

TEST(Crc32c, IncrementalEqualsOneShotAtEverySplit) {
  std::mt19937 rng(11);
  std::vector<uint8_t> data(100);
  for (auto& b : data)
    b = static_cast<uint8_t>(rng());
  const uint32_t whole = crc32c(data.data(), data.size());
  for (size_t split = 0; split <= data.size(); ++split) {
    Crc32c crc;
    crc.update(data.data(), split);
    crc.update(data.data() + split, data.size() - split);
    ASSERT_EQ(crc.value(), whole) << "split " << split;
    ASSERT_EQ(crc32c_extend(crc32c(data.data(), split), data.data() + split, data.size() - split),
              whole);
  }
}

}  // namespace
}  // namespace lodbake
