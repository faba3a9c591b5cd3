// The spatial blocks of an out-of-core run: a fine uniform grid over the
// input's bounding box counts the triangles whose centroid falls in each
// cell (one streaming pass), then a k-d split of that grid along its longest
// side, at the count's median, until each block holds at most a budget of
// triangles. Blocks follow the mesh's density where a uniform grid of blocks
// would leave most of them empty or one of them too big; a single fine cell
// holding more than the budget stays one block.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

inline constexpr uint32_t kNoBlock = 0xffffffffu;

struct BlockGrid {
  std::array<double, 3> origin{};  // the box's low corner
  double cell = 1;                 // side of a fine cell
  std::array<uint32_t, 3> dims{1, 1, 1};
  std::vector<uint32_t> cell_block;  // per fine cell (x fastest), kNoBlock when empty
  uint32_t block_count = 0;

  size_t cell_count() const { return size_t{dims[0]} * dims[1] * dims[2]; }
  /// The fine cell of the triangle's centroid (clamped into the grid).
  uint32_t cell_of(const Vec3f& a, const Vec3f& b, const Vec3f& c) const;
  uint32_t block_of(const Vec3f& a, const Vec3f& b, const Vec3f& c) const {
    return cell_block[cell_of(a, b, c)];
  }
};

/// A grid of cubic cells over [lo, hi], `resolution` cells along the longest
/// side (at least one along each). No block assigned yet.
BlockGrid make_block_grid(const Vec3f& lo, const Vec3f& hi, uint32_t resolution);

/// Groups the cells into blocks of at most `budget` triangles each
/// (`counts`: triangles per cell), numbered in the k-d walk's order (low
/// side first); empty blocks get no number. Deterministic.
void partition_blocks(const std::vector<uint64_t>& counts, uint64_t budget, BlockGrid* grid);

}  // namespace lodbake
