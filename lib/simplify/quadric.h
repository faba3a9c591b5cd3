// Garland-Heckbert error quadrics (Garland & Heckbert 1997, "Surface
// simplification using quadric error metrics"): the sum of weighted squared
// distances to a set of planes, stored as the 10 coefficients of a symmetric
// 4x4 matrix in double, plus the total weight so that the error can be
// reported as a mean squared distance (a length squared, like meshoptimizer's).
// Shared by the edge-collapse engine and the fan-merge hierarchy.
#pragma once

#include <array>

#include "formats/mesh/vec3d.h"

namespace lodbake {

/// Q(p) = sum_i w_i * (n_i . p + d_i)^2 over the accumulated planes.
struct Quadric {
  // Upper triangle of the symmetric matrix [A b; b^T c]:
  // a00 a01 a02 a11 a12 a22, b0 b1 b2, c.
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
  double b0 = 0, b1 = 0, b2 = 0;
  double c = 0;
  double weight = 0;  // sum of the w_i (area for face planes)

  /// The plane n . p + d = 0 (n need not be unit: the quadric is scaled by
  /// |n|^2 then) with weight w.
  static Quadric from_plane(const Vec3d& n, double d, double w);
  /// The area-weighted plane of the triangle (p0, p1, p2); zero for a
  /// degenerate triangle.
  static Quadric from_triangle(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2);

  /// Inline, like evaluate(): every collapse and every face adds quadrics.
  Quadric& operator+=(const Quadric& o) {
    a00 += o.a00;
    a01 += o.a01;
    a02 += o.a02;
    a11 += o.a11;
    a12 += o.a12;
    a22 += o.a22;
    b0 += o.b0;
    b1 += o.b1;
    b2 += o.b2;
    c += o.c;
    weight += o.weight;
    return *this;
  }
  Quadric operator+(const Quadric& o) const {
    Quadric r = *this;
    r += o;
    return r;
  }
  Quadric& operator*=(double s) {
    a00 *= s;
    a01 *= s;
    a02 *= s;
    a11 *= s;
    a12 *= s;
    a22 *= s;
    b0 *= s;
    b1 *= s;
    b2 *= s;
    c *= s;
    weight *= s;
    return *this;
  }

  /// Q(p): the weighted sum of squared distances (never negative). Inline:
  /// the collapse engine evaluates quadrics millions of times.
  double evaluate(const Vec3d& p) const {
    const double x = p[0], y = p[1], z = p[2];
    const double r = a00 * x * x + a11 * y * y + a22 * z * z +
                     2 * (a01 * x * y + a02 * x * z + a12 * y * z) +
                     2 * (b0 * x + b1 * y + b2 * z) + c;
    // Rounding can take an exact zero slightly below.
    return r > 0 ? r : 0;
  }
  /// Q(p) / weight: the weighted mean squared distance; 0 when weight is 0.
  double mean_error(const Vec3d& p) const;
  /// The minimiser of Q, when the 3x3 system is well conditioned; false
  /// (and *p untouched) when it is singular or ill conditioned.
  bool minimizer(Vec3d* p) const;
};

}  // namespace lodbake
