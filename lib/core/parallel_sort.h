// A sort on a ParallelScope whose result does not depend on the thread
// count: fixed chunks (their size depends on the caller alone) are sorted
// apart, then merged pairwise, round by round, with a stable merge. So
// every thread count runs the same comparisons on the same ranges, and the
// order comes out the same even when `less` is not a strict weak order
// (a NaN key); under a strict total order it is the one order there is.
#pragma once

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

#include "lib/core/parallel.h"

namespace lodbake {

/// Sorts `items` by `less` in chunks of `chunk_size` items, then merges.
/// \pre chunk_size > 0
template <typename T, typename Less>
void sort_in_chunks(const ParallelScope& scope, std::vector<T>* items, size_t chunk_size,
                    Less less) {
  const size_t count = items->size();
  if (count <= chunk_size) {
    std::sort(items->begin(), items->end(), less);
    return;
  }
  scope.for_each_chunk(count, chunk_size, [&](size_t, IndexRange range) {
    std::sort(items->begin() + static_cast<std::ptrdiff_t>(range.begin),
              items->begin() + static_cast<std::ptrdiff_t>(range.end), less);
  });
  std::vector<T> merged(count);
  std::vector<T>* from = items;
  std::vector<T>* to = &merged;
  for (size_t width = chunk_size; width < count; width *= 2) {
    const size_t pairs = (count + 2 * width - 1) / (2 * width);
    scope.for_each_part(pairs, [&](size_t p) {
      const size_t begin = 2 * width * p;
      const size_t middle = std::min(count, begin + width);
      const size_t end = std::min(count, begin + 2 * width);
      auto at = [](std::vector<T>* v, size_t i) {
        return v->begin() + static_cast<std::ptrdiff_t>(i);
      };
      std::merge(std::make_move_iterator(at(from, begin)),
                 std::make_move_iterator(at(from, middle)),
                 std::make_move_iterator(at(from, middle)), std::make_move_iterator(at(from, end)),
                 at(to, begin), less);
    });
    std::swap(from, to);
  }
  if (from != items) *items = std::move(*from);
}

}  // namespace lodbake
