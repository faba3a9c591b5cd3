// The per-face quadric terms that the collapse engine and the balanced
// hierarchy build both accumulate at the vertices.
#pragma once

#include <cmath>

#include "lib/simplify/quadric.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {

/// The plane quadric of triangle (p0, p1, p2) weighted by sqrt(area), a
/// length (meshoptimizer's choice): area weights let a few large faces
/// outvote many small ones in a vertex's mean error, and a small curved
/// feature then looks flat.
inline Quadric sqrt_area_triangle_quadric(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2) {
  Quadric q = Quadric::from_triangle(p0, p1, p2);
  if (q.weight > 0) q *= std::sqrt(q.weight) / q.weight;
  return q;
}

/// The plane quadric of triangle (p0, p1, p2) with weight 1, as in Garland
/// and Heckbert's paper and CGAL's plane policies: every face counts alike
/// however small. Zero for a degenerate triangle.
inline Quadric unit_triangle_quadric(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2) {
  Quadric q = Quadric::from_triangle(p0, p1, p2);
  if (q.weight > 0) q *= 1 / q.weight;
  return q;
}

/// How a boundary edge's constraint plane is weighted.
enum class BoundaryWeighting {
  kTimesLength,  // weight * |edge|, a length like the sqrt-area face weight
  kPerEdge,      // weight alone, beside unit face weights
};

/// The quadric of the plane through the boundary edge pa -> pb that is
/// perpendicular to its face (whose unnormalised normal is `face_normal`),
/// weighted by `weight` as `weighting` says, into `out`. False (and `out`
/// untouched) when the edge is degenerate or parallel to the normal.
inline bool boundary_edge_quadric(const Vec3d& pa, const Vec3d& pb, const Vec3d& face_normal,
                                  double weight, BoundaryWeighting weighting, Quadric* out) {
  const Vec3d e = sub(pb, pa);
  Vec3d pn = cross(e, face_normal);
  const double len = std::sqrt(dot(pn, pn));
  if (!(len > 0)) return false;
  pn = {pn[0] / len, pn[1] / len, pn[2] / len};
  const double w =
      weighting == BoundaryWeighting::kTimesLength ? weight * std::sqrt(dot(e, e)) : weight;
  *out = Quadric::from_plane(pn, -dot(pn, pa), w);
  return true;
}

}  // namespace lodbake
