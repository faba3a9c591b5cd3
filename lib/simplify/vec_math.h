// Small double-precision vector helpers and the corner lookup shared by the
// collapse engine, the balanced hierarchy build and the split replays.
// Positions are float32 in the mesh; geometric tests run in double so that
// thin triangles do not lose their normals to rounding.
#pragma once

#include <cmath>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vec3d.h"
#include "lib/simplify/quadric.h"

namespace lodbake {

/// The corner (0, 1 or 2) of `t` that holds vertex `v`; 2 when `v` is not in `t`.
inline int corner_of(const Triangle& t, uint32_t v) {
  return t[0] == v ? 0 : (t[1] == v ? 1 : 2);
}

/// Whether moving corner `a` of triangle (a, b, c) to `p` keeps the triangle
/// usable: false when (p, b, c) is nearly degenerate (the sine of its angle at
/// p below 1e-10) or its normal turns from (a, b, c)'s by more than the angle
/// whose cosine is `cos_limit`; true when (a, b, c) itself has no normal.
inline bool keeps_orientation(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& p,
                              double cos_limit, Vec3d* new_normal = nullptr) {
  const Vec3d eb = sub(b, p);
  const Vec3d ec = sub(c, p);
  const Vec3d n_new = cross(eb, ec);
  if (new_normal) *new_normal = n_new;
  const double len_new = dot(n_new, n_new);
  if (!(len_new > 1e-20 * dot(eb, eb) * dot(ec, ec))) return false;
  const Vec3d n_old = cross(sub(b, a), sub(c, a));
  const double len_old = dot(n_old, n_old);
  if (!(len_old > 0)) return true;
  const double turn = dot(n_old, n_new);
  // With a limit of 90 degrees or more, a normal that turns less than 90
  // degrees passes whatever the lengths (the same answer as below, without
  // the square root: most faces of a collapse turn a little).
  if (cos_limit <= 0 && turn >= 0) return true;
  return !(turn < cos_limit * std::sqrt(len_old * len_new));
}

}  // namespace lodbake
