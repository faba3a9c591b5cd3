// Garland-Heckbert plane quadrics. Choices the paper leaves open:
// - face quadrics are weighted by the triangle's area (the plane's normal is
//   the unnormalised cross product halved, so the scaling is implicit);
// - the minimiser is solved with Eigen's closed-form 3x3 inverse (cofactors)
//   and rejected when the matrix's reciprocal condition number in the 1-norm,
//   exact from that inverse, falls below 1e-9 (flat or cylindrical
//   neighbourhoods): the caller then falls back to an endpoint or the
//   midpoint. Eigen's full-pivot LU with its condition estimate, used before,
//   made optimal placement 3 to 5 times slower for errors within 1 %
//   (docs/simplify.md, "Optimal placement").
#include "lib/simplify/quadric.h"

#include <Eigen/Dense>
#include <cmath>

namespace lodbake {

Quadric Quadric::from_plane(const Vec3d& n, double d, double w) {
  Quadric q;
  q.a00 = w * n[0] * n[0];
  q.a01 = w * n[0] * n[1];
  q.a02 = w * n[0] * n[2];
  q.a11 = w * n[1] * n[1];
  q.a12 = w * n[1] * n[2];
  q.a22 = w * n[2] * n[2];
  q.b0 = w * n[0] * d;
  q.b1 = w * n[1] * d;
  q.b2 = w * n[2] * d;
  q.c = w * d * d;
  q.weight = w;
  return q;
}

Quadric Quadric::from_triangle(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2) {
  const Vec3d e1{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const Vec3d e2{p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  Vec3d n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
          e1[0] * e2[1] - e1[1] * e2[0]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0)) return Quadric();
  n = {n[0] / len, n[1] / len, n[2] / len};
  const double d = -(n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2]);
  return from_plane(n, d, 0.5 * len);
}

double Quadric::mean_error(const Vec3d& p) const {
  return weight > 0 ? evaluate(p) / weight : 0;
}

bool Quadric::minimizer(Vec3d* p) const {
  Eigen::Matrix3d a;
  a << a00, a01, a02, a01, a11, a12, a02, a12, a22;
  Eigen::Matrix3d inverse;
  double determinant = 0;
  bool invertible = false;
  a.computeInverseAndDetWithCheck(inverse, determinant, invertible, 0.0);
  if (!invertible) return false;
  const double norm = a.cwiseAbs().colwise().sum().maxCoeff();
  const double inverse_norm = inverse.cwiseAbs().colwise().sum().maxCoeff();
  if (!(1 / (norm * inverse_norm) > 1e-9)) return false;
  const Eigen::Vector3d x = inverse * Eigen::Vector3d(-b0, -b1, -b2);
  if (!x.allFinite()) return false;
  *p = {x[0], x[1], x[2]};
  return true;
}

}  // namespace lodbake
