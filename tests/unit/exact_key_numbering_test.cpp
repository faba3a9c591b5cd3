// ExactKeyNumbering: first-seen numbers by exact key, whether the caller's
// size hint is right or far too small (the table grows).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>
#include <vector>

#include "lib/scene/exact_key_numbering.h"

namespace lodbake {
namespace {

std::vector<ExactKey> keys_with_repeats() {
  std::vector<ExactKey> keys;
  for (uint32_t i = 0; i < 20000; ++i) {
    ExactKey k;
    k.lo = (i * 7919u) % 5003;  // repeats
    k.hi = i % 3 == 0 ? 0 : uint64_t{1} << 63;
    k.tag = i % 2;
    keys.push_back(k);
  }
  return keys;
}

std::vector<uint32_t> reference(const std::vector<ExactKey>& keys) {
  std::map<std::tuple<uint64_t, uint64_t, uint32_t>, uint32_t> seen;
  std::vector<uint32_t> out;
  for (const ExactKey& k : keys) {
    const auto found =
        seen.emplace(std::make_tuple(k.lo, k.hi, k.tag), static_cast<uint32_t>(seen.size()));
    out.push_back(found.first->second);
  }
  return out;
}

TEST(ExactKeyNumbering, FirstSeenNumbersWithAnyHint) {
  const std::vector<ExactKey> keys = keys_with_repeats();
  const std::vector<uint32_t> expected = reference(keys);
  uint32_t distinct = 0;
  for (uint32_t n : expected)
    distinct = std::max(distinct, n + 1);
  ASSERT_GT(distinct, 10000u);
  ASSERT_LT(distinct, keys.size());
  for (const uint64_t hint : {uint64_t{0}, uint64_t{100}, uint64_t{keys.size()}}) {
    SCOPED_TRACE(hint);
    ExactKeyNumbering numbering(hint);
    std::vector<uint32_t> got;
    for (const ExactKey& k : keys)
      got.push_back(numbering.number(k));
    EXPECT_EQ(got, expected);
    EXPECT_EQ(numbering.size(), distinct);
  }
}

}  // namespace
}  // namespace lodbake
