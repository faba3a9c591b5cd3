// Oriented triangles in one canonical form, so that two triangle lists can
// be compared as multisets: each triangle rotated to start at its smallest
// corner (the cyclic order, so the orientation, is kept), the list sorted.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

/// `t` rotated so that its smallest index comes first: the least of its
/// three rotations, which also settles ties in a repeated index.
inline Triangle canonical_triangle(const Triangle& t) {
  return std::min({t, Triangle{t[1], t[2], t[0]}, Triangle{t[2], t[0], t[1]}});
}

/// Rotates every triangle of `triangles` to canonical_triangle() and sorts
/// the list lexicographically. A counting sort on the first corner, then
/// small sorts per corner, so linear in practice: the SETS replay checks
/// hundreds of thousands of triangles at thousands of LoDs this way.
void sort_canonical_triangles(std::vector<Triangle>* triangles);

}  // namespace lodbake
