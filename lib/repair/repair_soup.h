// The working state of repair_mesh(): a triangle soup in the form CGAL's
// polygon soup functions take, plus where every point and every corner came
// from, so attributes can follow through removals, splits and flips.
// Internal to lib/repair.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

struct CornerSource {
  uint64_t triangle = 0;                   // index of the input triangle
  std::array<uint8_t, 3> corner{0, 1, 2};  // input corner that ends at each position
};

struct RepairSoup {
  std::vector<Vec3f> points;
  std::vector<uint32_t> point_origin;  // input vertex of each point (copies share it)
  std::vector<std::array<std::size_t, 3>> triangles;
  std::vector<CornerSource> sources;  // parallel to triangles

  // Reverses triangle t, keeping its corner sources in step, the same way
  // CGAL does it (std::reverse: (a, b, c) becomes (c, b, a)).
  void reverse(size_t t);
  bool reversed(size_t t) const { return sources[t].corner[0] != 0; }
};

/// Counts of what the index-level steps removed.
struct SoupRemovals {
  uint64_t non_finite = 0;
  uint64_t degenerate = 0;
  uint64_t duplicate = 0;
};

/// Checks the vertex count, indices and attribute bindings, then builds the soup of the
/// triangles that survive: no non-finite corner, three distinct indices,
/// non-zero area (exact), first copy of each vertex set.
Result<RepairSoup> build_clean_soup(const TriangleMesh& mesh, SoupRemovals* removals);

/// Edges with more than two faces.
uint64_t count_non_manifold_edges(const RepairSoup& soup);

/// After orientation: for every edge-connected piece in which some triangle
/// was flipped, keeps the outward orientation if the piece is closed and
/// encloses a non-zero volume, else the one agreeing with more input
/// triangles (ties: the piece's first triangle keeps its input winding).
void choose_piece_orientation(RepairSoup* soup);

/// Drops points no triangle uses (keeping the order of the rest) and writes
/// the soup back as a mesh with `input`'s attributes following their
/// vertices and corners. Returns the number of dropped points; fails when
/// more points are used than 32-bit indices can address.
Result<uint64_t> soup_to_mesh(RepairSoup* soup, const TriangleMesh& input, TriangleMesh* out);

}  // namespace lodbake
