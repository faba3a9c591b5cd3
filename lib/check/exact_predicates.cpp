// Exact zero-area test for triangles with float32 corners.
//
// Three points are collinear exactly when all three 2D orientation
// determinants (the components of the 3D cross product) vanish. Each
// determinant is first evaluated in double with Shewchuk's error bound for
// orient2d ("Adaptive Precision Floating-Point Arithmetic and Fast Robust
// Geometric Predicates", 1997): when |det| exceeds the bound its sign, hence
// non-zero-ness, is certain. Otherwise it is recomputed exactly as a sum of
// 16 doubles (two_diff for the coordinate differences, FMA-based two_product
// for the products) accumulated into a non-overlapping expansion with
// grow_expansion; the exact value is zero iff that expansion is empty.
// Float inputs keep every intermediate far from double overflow (|x| < 2^128,
// products < 2^258) and underflow (all values are multiples of 2^-149, so
// products and their error terms are multiples of 2^-298), so the
// error-free transformations are exact.
#include "lib/check/exact_predicates.h"

#include <cmath>

namespace lodbake {
namespace {

struct Pair {
  double hi;
  double lo;
};

Pair two_sum(double a, double b) {
  double x = a + b;
  double b_virtual = x - a;
  double a_virtual = x - b_virtual;
  double b_round = b - b_virtual;
  double a_round = a - a_virtual;
  return {x, a_round + b_round};
}

Pair two_diff(double a, double b) {
  return two_sum(a, -b);
}

Pair two_product(double a, double b) {
  double x = a * b;
  return {x, std::fma(a, b, -x)};
}

// Adds `b` to the non-overlapping expansion e[0..n) (increasing magnitude),
// dropping zero components; returns the new length.
int grow_expansion(double* e, int n, double b) {
  double q = b;
  int out = 0;
  for (int i = 0; i < n; ++i) {
    Pair s = two_sum(q, e[i]);
    q = s.hi;
    if (s.lo != 0.0) e[out++] = s.lo;
  }
  if (q != 0.0) e[out++] = q;
  return out;
}

// Exact test of (ax - cx)(by - cy) - (ay - cy)(bx - cx) == 0.
bool orient2d_exactly_zero(double ax, double ay, double bx, double by, double cx, double cy) {
  Pair acx = two_diff(ax, cx);
  Pair acy = two_diff(ay, cy);
  Pair bcx = two_diff(bx, cx);
  Pair bcy = two_diff(by, cy);
  const double left[2] = {acx.hi, acx.lo};
  const double left2[2] = {bcy.hi, bcy.lo};
  const double right[2] = {acy.hi, acy.lo};
  const double right2[2] = {bcx.hi, bcx.lo};
  double expansion[32];
  int n = 0;
  for (double l : left) {
    for (double l2 : left2) {
      Pair p = two_product(l, l2);
      n = grow_expansion(expansion, n, p.lo);
      n = grow_expansion(expansion, n, p.hi);
    }
  }
  for (double r : right) {
    for (double r2 : right2) {
      Pair p = two_product(r, r2);
      n = grow_expansion(expansion, n, -p.lo);
      n = grow_expansion(expansion, n, -p.hi);
    }
  }
  return n == 0;
}

bool orient2d_is_zero(double ax, double ay, double bx, double by, double cx, double cy) {
  constexpr double kEpsilon = 1.1102230246251565e-16;  // 2^-53
  constexpr double kErrorBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
  double left = (ax - cx) * (by - cy);
  double right = (ay - cy) * (bx - cx);
  double det = left - right;
  double bound = kErrorBound * (std::fabs(left) + std::fabs(right));
  if (std::fabs(det) > bound) return false;
  return orient2d_exactly_zero(ax, ay, bx, by, cx, cy);
}

}  // namespace

bool is_zero_area_triangle(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  // Cross product components: z from the xy projection, x from yz, y from zx.
  return orient2d_is_zero(a[0], a[1], b[0], b[1], c[0], c[1]) &&
         orient2d_is_zero(a[1], a[2], b[1], b[2], c[1], c[2]) &&
         orient2d_is_zero(a[2], a[0], b[2], b[0], c[2], c[0]);
}

}  // namespace lodbake
