// Merges corners with exactly equal positions into one vertex, for formats
// that store triangle soups (STL). Vertices are numbered in order of first
// appearance, so the result depends only on the input order, never on hash
// table layout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

class PositionWelder {
 public:
  /// Prepares for about `expected_corners` add() calls (a reservation hint;
  /// the caller bounds it by the input size).
  explicit PositionWelder(size_t expected_corners = 0);

  /// The index of the vertex at `p`, appending a new vertex when no earlier
  /// corner had exactly this position. +0.0 and -0.0 are the same position
  /// (the first one seen is kept); NaNs are equal when their bits are.
  uint32_t add(const Vec3f& p);

  size_t vertex_count() const { return positions_.size(); }
  /// Corners that reused an earlier vertex.
  uint64_t welded() const { return welded_; }
  /// Moves the welded positions out; the welder is empty afterwards.
  std::vector<Vec3f> take_positions();

 private:
  void rehash(size_t capacity);
  size_t find_slot(const Vec3f& p) const;

  std::vector<Vec3f> positions_;
  std::vector<uint32_t> table_;  // vertex index per slot, kEmptySlot when free
  size_t mask_ = 0;
  uint64_t welded_ = 0;
};

}  // namespace lodbake
