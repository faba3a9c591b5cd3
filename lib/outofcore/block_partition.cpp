#include "lib/outofcore/block_partition.h"

#include <algorithm>
#include <cmath>

namespace lodbake {
namespace {

// Sums over boxes of the fine grid from a summed-volume table.
class BoxSums {
 public:
  BoxSums(const std::vector<uint64_t>& counts, const std::array<uint32_t, 3>& dims)
      : nx_(dims[0] + 1), ny_(dims[1] + 1), table_(size_t{nx_} * ny_ * (dims[2] + 1), 0) {
    for (uint32_t z = 1; z <= dims[2]; ++z)
      for (uint32_t y = 1; y <= dims[1]; ++y)
        for (uint32_t x = 1; x <= dims[0]; ++x) {
          const uint64_t c = counts[(size_t{z - 1} * dims[1] + (y - 1)) * dims[0] + (x - 1)];
          at(x, y, z) = c + at(x - 1, y, z) + at(x, y - 1, z) + at(x, y, z - 1) -
                        at(x - 1, y - 1, z) - at(x - 1, y, z - 1) - at(x, y - 1, z - 1) +
                        at(x - 1, y - 1, z - 1);
        }
  }

  // Triangles in cells [lo, hi) along each axis.
  uint64_t sum(const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi) const {
    return get(hi[0], hi[1], hi[2]) - get(lo[0], hi[1], hi[2]) - get(hi[0], lo[1], hi[2]) -
           get(hi[0], hi[1], lo[2]) + get(lo[0], lo[1], hi[2]) + get(lo[0], hi[1], lo[2]) +
           get(hi[0], lo[1], lo[2]) - get(lo[0], lo[1], lo[2]);
  }

 private:
  uint64_t& at(uint32_t x, uint32_t y, uint32_t z) {
    return table_[(size_t{z} * ny_ + y) * nx_ + x];
  }
  uint64_t get(uint32_t x, uint32_t y, uint32_t z) const {
    return table_[(size_t{z} * ny_ + y) * nx_ + x];
  }
  uint32_t nx_, ny_;
  std::vector<uint64_t> table_;
};

void split(const BoxSums& sums, uint64_t budget, std::array<uint32_t, 3> lo,
           std::array<uint32_t, 3> hi, BlockGrid* grid) {
  const uint64_t total = sums.sum(lo, hi);
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  if (total <= budget || hi[axis] - lo[axis] == 1) {
    if (total == 0) return;
    const uint32_t block = grid->block_count++;
    for (uint32_t z = lo[2]; z < hi[2]; ++z)
      for (uint32_t y = lo[1]; y < hi[1]; ++y)
        for (uint32_t x = lo[0]; x < hi[0]; ++x)
          grid->cell_block[(size_t{z} * grid->dims[1] + y) * grid->dims[0] + x] = block;
    return;
  }
  // The first plane with at least half the triangles below it, leaving a
  // cell on each side.
  uint32_t at = lo[axis] + 1;
  for (; at + 1 < hi[axis]; ++at) {
    std::array<uint32_t, 3> below = hi;
    below[axis] = at;
    if (2 * sums.sum(lo, below) >= total) break;
  }
  std::array<uint32_t, 3> mid_hi = hi, mid_lo = lo;
  mid_hi[axis] = at;
  mid_lo[axis] = at;
  split(sums, budget, lo, mid_hi, grid);
  split(sums, budget, mid_lo, hi, grid);
}

}  // namespace

uint32_t BlockGrid::cell_of(const Vec3f& a, const Vec3f& b, const Vec3f& c) const {
  size_t index = 0;
  size_t stride = 1;
  for (int k = 0; k < 3; ++k) {
    const double centroid = (double{a[k]} + b[k] + c[k]) / 3.0;
    const double f = std::floor((centroid - origin[k]) / cell);
    const uint32_t i =
        f <= 0 ? 0 : static_cast<uint32_t>(std::min<double>(f, static_cast<double>(dims[k] - 1)));
    index += i * stride;
    stride *= dims[k];
  }
  return static_cast<uint32_t>(index);
}

BlockGrid make_block_grid(const Vec3f& lo, const Vec3f& hi, uint32_t resolution) {
  BlockGrid grid;
  double longest = 0;
  for (int k = 0; k < 3; ++k) {
    grid.origin[k] = lo[k];
    longest = std::max(longest, double{hi[k]} - lo[k]);
  }
  resolution = std::max<uint32_t>(resolution, 1);
  grid.cell = longest > 0 ? longest / resolution : 1;
  for (int k = 0; k < 3; ++k) {
    const double cells = std::ceil((double{hi[k]} - lo[k]) / grid.cell);
    grid.dims[k] = static_cast<uint32_t>(std::clamp(cells, 1.0, static_cast<double>(resolution)));
  }
  grid.cell_block.assign(grid.cell_count(), kNoBlock);
  return grid;
}

void partition_blocks(const std::vector<uint64_t>& counts, uint64_t budget, BlockGrid* grid) {
  grid->cell_block.assign(grid->cell_count(), kNoBlock);
  grid->block_count = 0;
  const BoxSums sums(counts, grid->dims);
  split(sums, std::max<uint64_t>(budget, 1), {0, 0, 0}, grid->dims, grid);
}

}  // namespace lodbake
