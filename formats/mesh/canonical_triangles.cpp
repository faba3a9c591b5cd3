#include "formats/mesh/canonical_triangles.h"

#include <algorithm>
#include <cstdint>

namespace lodbake {

void sort_canonical_triangles(std::vector<Triangle>* triangles) {
  std::vector<Triangle>& list = *triangles;
  uint64_t buckets = 0;
  for (Triangle& t : list) {
    t = canonical_triangle(t);
    buckets = std::max<uint64_t>(buckets, uint64_t{t[0]} + 1);
  }
  // Indices far sparser than the triangles (hand-made or hostile lists) would
  // make the bucket array the cost; an ordinary sort is linearithmic anyway.
  if (list.size() < 64 || list.size() > UINT32_MAX || buckets > 4 * uint64_t{list.size()} + 1024) {
    std::sort(list.begin(), list.end());
    return;
  }
  std::vector<uint32_t> offsets(buckets + 1, 0);
  for (const Triangle& t : list)
    ++offsets[t[0] + 1];
  for (uint64_t b = 0; b < buckets; ++b)
    offsets[b + 1] += offsets[b];
  std::vector<Triangle> sorted(list.size());
  std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
  for (const Triangle& t : list)
    sorted[fill[t[0]]++] = t;
  for (uint64_t b = 0; b < buckets; ++b) {
    auto begin = sorted.begin() + offsets[b];
    auto end = sorted.begin() + offsets[b + 1];
    if (end - begin > 1) std::sort(begin, end);
  }
  list.swap(sorted);
}

}  // namespace lodbake
