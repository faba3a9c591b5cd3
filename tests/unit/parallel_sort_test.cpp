// sort_in_chunks(): sorted, and the same order for every thread count, even
// under a comparison that ties (the chunks are fixed, the merges stable).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "lib/core/parallel_sort.h"

namespace lodbake {
namespace {

using Item = std::pair<int, int>;  // key, then the position it was made at

std::vector<Item> random_items(size_t count) {
  std::mt19937 rng(7);
  std::vector<Item> items(count);
  for (size_t i = 0; i < count; ++i)
    items[i] = {static_cast<int>(rng() % 1000), static_cast<int>(i)};
  return items;
}

TEST(ParallelSort, SortsLikeStdSortUnderATotalOrder) {
  for (size_t count : {0u, 1u, 99u, 100u, 101u, 1000u, 12345u}) {
    std::vector<Item> expected = random_items(count);
    std::sort(expected.begin(), expected.end());
    for (unsigned threads : {1u, 2u, 7u}) {
      std::vector<Item> items = random_items(count);
      sort_in_chunks(ParallelScope(threads), &items, 100, std::less<Item>());
      EXPECT_EQ(items, expected) << count << " items, " << threads << " threads";
    }
  }
}

TEST(ParallelSort, TiedKeysComeOutInTheSameOrderForEveryThreadCount) {
  auto by_key = [](const Item& a, const Item& b) { return a.first < b.first; };
  std::vector<Item> one = random_items(20000);
  sort_in_chunks(ParallelScope(1), &one, 256, by_key);
  ASSERT_TRUE(std::is_sorted(one.begin(), one.end(), by_key));
  for (unsigned threads : {2u, 7u}) {
    std::vector<Item> items = random_items(20000);
    sort_in_chunks(ParallelScope(threads), &items, 256, by_key);
    EXPECT_EQ(items, one) << threads << " threads";
  }
}

}  // namespace
}  // namespace lodbake
