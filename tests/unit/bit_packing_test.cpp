// Bit packing: widths, sizes, the LSB-first order byte for byte, round trips
// at every width, and a reader that never reads past its span.
#include "formats/support/bit_packing.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace lodbake {
namespace {

TEST(BitPacking, BitsForCount) {
  EXPECT_EQ(bits_for_count(0), 0);
  EXPECT_EQ(bits_for_count(1), 0);
  EXPECT_EQ(bits_for_count(2), 1);
  EXPECT_EQ(bits_for_count(3), 2);
  EXPECT_EQ(bits_for_count(4), 2);
  EXPECT_EQ(bits_for_count(5), 3);
  EXPECT_EQ(bits_for_count(256), 8);
  EXPECT_EQ(bits_for_count(257), 9);
  EXPECT_EQ(bits_for_count(uint64_t{1} << 32), 32);
  EXPECT_EQ(bits_for_count((uint64_t{1} << 32) + 1), 33);
}

TEST(BitPacking, PackedSizeBytes) {
  EXPECT_EQ(packed_size_bytes(0, 7), 0u);
  EXPECT_EQ(packed_size_bytes(10, 0), 0u);
  EXPECT_EQ(packed_size_bytes(1, 1), 1u);
  EXPECT_EQ(packed_size_bytes(8, 1), 1u);
  EXPECT_EQ(packed_size_bytes(9, 1), 2u);
  EXPECT_EQ(packed_size_bytes(3, 20), 8u);
  EXPECT_EQ(packed_size_bytes(3 * uint64_t{UINT32_MAX}, 32), 3 * uint64_t{UINT32_MAX} * 4);
  EXPECT_EQ(packed_size_bytes(UINT64_MAX / 2, 32), UINT64_MAX);
}

TEST(BitPacking, LeastSignificantBitFirst) {
  std::vector<uint8_t> out;
  BitWriter writer(&out);
  writer.write(5, 3);     // 101
  writer.write(3, 3);     // 011
  writer.write(0x3F, 6);  // 111111, crosses into the second byte
  writer.finish();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0], 0xDDu);  // 11 011 101
  EXPECT_EQ(out[1], 0x0Fu);  // zero padding above the last 4 bits
  BitReader reader(out.data(), out.size());
  uint32_t v = 0;
  ASSERT_TRUE(reader.read(3, &v));
  EXPECT_EQ(v, 5u);
  ASSERT_TRUE(reader.read(3, &v));
  EXPECT_EQ(v, 3u);
  ASSERT_TRUE(reader.read(6, &v));
  EXPECT_EQ(v, 0x3Fu);
  EXPECT_TRUE(reader.padding_is_zero());
  EXPECT_EQ(reader.bytes_consumed(), 2u);
  EXPECT_FALSE(reader.read(5, &v));  // only 4 bits left
  EXPECT_EQ(v, 0x3Fu);               // unchanged on failure
  ASSERT_TRUE(reader.read(4, &v));
  EXPECT_EQ(v, 0u);
  EXPECT_FALSE(reader.read(1, &v));
}

TEST(BitPacking, NonzeroPaddingIsDetected) {
  const uint8_t byte = 0x80;  // value bits 0..2 are 0, padding bit 7 set
  BitReader reader(&byte, 1);
  uint32_t v = 0;
  ASSERT_TRUE(reader.read(3, &v));
  EXPECT_EQ(v, 0u);
  EXPECT_FALSE(reader.padding_is_zero());
}

TEST(BitPacking, RoundTripEveryWidth) {
  std::mt19937 rng(3);
  for (int bits = 0; bits <= 32; ++bits) {
    std::vector<uint32_t> values(101);
    for (auto& v : values) {
      v = bits == 32 ? static_cast<uint32_t>(rng())
                     : static_cast<uint32_t>(rng() & ((uint64_t{1} << bits) - 1));
    }
    std::vector<uint8_t> out;
    BitWriter writer(&out);
    for (uint32_t v : values)
      writer.write(v, bits);
    writer.finish();
    ASSERT_EQ(out.size(), packed_size_bytes(values.size(), bits)) << bits;
    BitReader reader(out.data(), out.size());
    for (size_t i = 0; i < values.size(); ++i) {
      uint32_t v = 0;
      ASSERT_TRUE(reader.read(bits, &v));
      ASSERT_EQ(v, values[i]) << "bits " << bits << " value " << i;
    }
    EXPECT_TRUE(reader.padding_is_zero());
    EXPECT_EQ(reader.bytes_consumed(), out.size());
  }
}

TEST(BitPacking, ReaderRejectsBadWidths) {
  const uint8_t bytes[8] = {};
  BitReader reader(bytes, sizeof(bytes));
  uint32_t v = 0;
  EXPECT_FALSE(reader.read(33, &v));
  EXPECT_FALSE(reader.read(-1, &v));
  BitReader empty(nullptr, 0);
  EXPECT_TRUE(empty.read(0, &v));
  EXPECT_FALSE(empty.read(1, &v));
}

}  // namespace
}  // namespace lodbake
