// The adaptive range coder of formats/support: every binarisation decodes
// to what was coded (bits at skewed and even probabilities, uniform values
// over small, 16-bit-crossing and 32-bit ranges, integers up to 2^40),
// carries through long 0xFF runs, costs close to the source's entropy, is
// deterministic, and a truncated, extended or bit-flipped stream is detected.
#include "formats/support/range_coder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace lodbake {
namespace {

struct Event {
  int kind;  // 0 adaptive bit, 1 direct bits, 2 uniform, 3 unsigned, 4 signed
  uint64_t value;
  uint64_t range;
};

std::vector<Event> random_events(uint32_t seed, size_t count) {
  std::mt19937_64 rng(seed);
  std::vector<Event> events;
  for (size_t i = 0; i < count; ++i) {
    Event e{static_cast<int>(rng() % 5), 0, 0};
    switch (e.kind) {
      case 0:
        e.value = (rng() % 100) < 90 ? 0 : 1;  // skewed: the model adapts
        break;
      case 1:
        e.range = rng() % 33;
        e.value = e.range == 32 ? (rng() & 0xFFFFFFFFu) : rng() & ((uint64_t{1} << e.range) - 1);
        break;
      case 2: {
        const uint64_t ranges[] = {1,     2,     3,       7,           65535,
                                   65536, 65537, 1000003, 0xFFFFFFFFu, uint64_t{1} << 32};
        e.range = ranges[rng() % 10];
        e.value = rng() % e.range;
        break;
      }
      case 3:
        e.value = rng() >> (24 + rng() % 40);  // below 2^40, many sizes
        break;
      default:
        e.value = static_cast<uint64_t>(static_cast<int64_t>(rng() >> (24 + rng() % 40)) *
                                        ((rng() & 1) != 0 ? -1 : 1));
    }
    events.push_back(e);
  }
  return events;
}

std::vector<uint8_t> encode(const std::vector<Event>& events) {
  std::vector<uint8_t> out;
  RangeEncoder rc(&out);
  BitModel bit = kBitModelHalf;
  AdaptiveIntModel ints(2);
  AdaptiveSignedModel signs(2);
  for (size_t i = 0; i < events.size(); ++i) {
    const Event& e = events[i];
    switch (e.kind) {
      case 0:
        rc.encode_bit(&bit, static_cast<int>(e.value));
        break;
      case 1:
        rc.encode_direct(static_cast<uint32_t>(e.value), static_cast<int>(e.range));
        break;
      case 2:
        rc.encode_uniform(static_cast<uint32_t>(e.value), e.range);
        break;
      case 3:
        ints.encode(&rc, i % 2, e.value);
        break;
      default:
        signs.encode(&rc, i % 2, static_cast<int64_t>(e.value));
    }
  }
  rc.finish();
  return out;
}

// Decodes `events` from `data`; false at the first difference.
bool decode_matches(const std::vector<uint8_t>& data, const std::vector<Event>& events,
                    RangeDecoder* rc) {
  BitModel bit = kBitModelHalf;
  AdaptiveIntModel ints(2);
  AdaptiveSignedModel signs(2);
  for (size_t i = 0; i < events.size(); ++i) {
    const Event& e = events[i];
    uint64_t got = 0;
    switch (e.kind) {
      case 0:
        got = static_cast<uint64_t>(rc->decode_bit(&bit));
        break;
      case 1:
        got = rc->decode_direct(static_cast<int>(e.range));
        break;
      case 2: {
        uint32_t v = 0;
        if (!rc->decode_uniform(e.range, &v)) return false;
        got = v;
        break;
      }
      case 3:
        if (!ints.decode(rc, i % 2, &got)) return false;
        break;
      default: {
        int64_t v = 0;
        if (!signs.decode(rc, i % 2, &v)) return false;
        got = static_cast<uint64_t>(v);
      }
    }
    if (got != e.value) return false;
  }
  (void)data;
  return true;
}

TEST(RangeCoder, EveryBinarisationRoundTrips) {
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    const std::vector<Event> events = random_events(seed, 3000);
    const std::vector<uint8_t> data = encode(events);
    RangeDecoder rc(data.data(), data.size());
    ASSERT_TRUE(rc.valid_start());
    EXPECT_TRUE(decode_matches(data, events, &rc)) << seed;
    EXPECT_TRUE(rc.at_end()) << seed;
    EXPECT_EQ(encode(events), data) << "deterministic";
  }
}

TEST(RangeCoder, EmptyStreamIsFiveBytes) {
  std::vector<uint8_t> out;
  RangeEncoder rc(&out);
  rc.finish();
  EXPECT_EQ(out.size(), 5u);
  RangeDecoder d(out.data(), out.size());
  EXPECT_TRUE(d.valid_start());
  EXPECT_TRUE(d.at_end());
}

// Bits that are almost always 1 push the low end towards the top of the
// range, producing runs of 0xFF bytes that a later carry must ripple through.
TEST(RangeCoder, CarriesThroughRunsOfFF) {
  std::vector<uint8_t> out;
  RangeEncoder rc(&out);
  std::vector<int> bits;
  std::mt19937 rng(7);
  for (int i = 0; i < 200000; ++i)
    bits.push_back(rng() % 1000 == 0 ? 0 : 1);
  BitModel model = kBitModelHalf;
  for (int b : bits)
    rc.encode_bit(&model, b);
  rc.finish();
  size_t ff_runs = 0;
  for (size_t i = 1; i < out.size(); ++i)
    ff_runs += out[i] == 0xFF && out[i - 1] == 0xFF;
  EXPECT_GT(ff_runs, 0u);
  RangeDecoder d(out.data(), out.size());
  BitModel back = kBitModelHalf;
  for (size_t i = 0; i < bits.size(); ++i)
    ASSERT_EQ(d.decode_bit(&back), bits[i]) << i;
  EXPECT_TRUE(d.at_end());
}

TEST(RangeCoder, CostsCloseToTheEntropy) {
  std::mt19937 rng(3);
  std::vector<uint8_t> out;
  RangeEncoder rc(&out);
  BitModel model = kBitModelHalf;
  const double p = 0.05;
  const int n = 100000;
  for (int i = 0; i < n; ++i)
    rc.encode_bit(&model, (rng() % 1000) < 50 ? 1 : 0);
  rc.finish();
  const double entropy = n * -(p * std::log2(p) + (1 - p) * std::log2(1 - p));
  // Adapting by 1/32 follows the noise of the last few dozen bits: a few
  // percent over the entropy.
  EXPECT_LT(rc.cost_bits(), 1.08 * entropy);
  EXPECT_LT(8.0 * out.size(), 1.08 * entropy);
  EXPECT_LT(8.0 * out.size(), rc.cost_bits() + 64);
  EXPECT_GT(8.0 * out.size(), rc.cost_bits() - 8);
}

TEST(RangeCoder, TruncationsAndTrailingBytesAreDetected) {
  const std::vector<Event> events = random_events(11, 500);
  const std::vector<uint8_t> data = encode(events);
  for (size_t n = 0; n < data.size(); ++n) {
    RangeDecoder rc(data.data(), n);
    const bool decoded = rc.valid_start() && decode_matches(data, events, &rc);
    EXPECT_FALSE(decoded && rc.at_end()) << n;
  }
  // Any flipped bit changes the events or leaves a nonzero code: the stream
  // is the only one for its events.
  for (size_t i = 0; i < data.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> flipped = data;
      flipped[i] ^= static_cast<uint8_t>(1u << bit);
      RangeDecoder rc(flipped.data(), flipped.size());
      const bool same = rc.valid_start() && decode_matches(flipped, events, &rc) && rc.at_end();
      EXPECT_FALSE(same) << i << " " << bit;
    }
  }
  std::vector<uint8_t> longer = data;
  longer.push_back(0);
  RangeDecoder rc(longer.data(), longer.size());
  ASSERT_TRUE(decode_matches(longer, events, &rc));
  EXPECT_FALSE(rc.at_end());
  EXPECT_FALSE(rc.overrun());
}

TEST(RangeCoder, BadStartsAndOutOfRangeValuesFail) {
  const uint8_t nonzero[] = {1, 0, 0, 0, 0};
  EXPECT_FALSE(RangeDecoder(nonzero, 5).valid_start());
  const uint8_t full[] = {0, 0xFF, 0xFF, 0xFF, 0xFF};
  EXPECT_FALSE(RangeDecoder(full, 5).valid_start());
  EXPECT_FALSE(RangeDecoder(nullptr, 0).valid_start());
  // A code in the range's top sliver (2^32 - 1 is not a multiple of 2^16)
  // holds no value below 2^16.
  const uint8_t high[] = {0, 0xFF, 0xFF, 0xFF, 0xFE};
  RangeDecoder rc(high, 5);
  ASSERT_TRUE(rc.valid_start());
  uint32_t v = 0;
  EXPECT_FALSE(rc.decode_uniform(65536, &v));
  EXPECT_FALSE(RangeDecoder(high, 5).decode_uniform(0, &v));
  // A length above 40 bits is refused: a bit tree of all-ones lengths.
  std::vector<uint8_t> out;
  RangeEncoder enc(&out);
  BitTreeModel lengths(6);
  lengths.encode(&enc, 63);
  enc.finish();
  RangeDecoder d(out.data(), out.size());
  AdaptiveIntModel ints(1);
  uint64_t x = 0;
  EXPECT_FALSE(ints.decode(&d, 0, &x));
}

}  // namespace
}  // namespace lodbake
