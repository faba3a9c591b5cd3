// Double-precision 3-vectors and the few operations every geometric test
// needs. Positions are float32 in the mesh; tests run in double so that thin
// triangles do not lose their normals to rounding.
#pragma once

#include <array>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

using Vec3d = std::array<double, 3>;

/// `p` widened to double.
inline Vec3d to_d(const Vec3f& p) {
  return {p[0], p[1], p[2]};
}

/// a - b.
inline Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

/// a x b.
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// a . b.
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace lodbake
