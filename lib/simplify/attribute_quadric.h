// Appearance quadrics after Hoppe 1999 ("New quadric metric for simplifying
// meshes with appearance attributes"): on each face, an attribute component
// s is the linear field s(p) = g . p + d that interpolates its corners; the
// error of giving a point p the value s is the area-weighted (s - g.p - d)^2,
// summed over the faces a wedge's corners belong to.
//
// Hoppe adds these terms to the geometric quadric of a vertex and solves for
// p and s together; lodbake collapses half edges, so p is the surviving
// vertex's point and s a surviving wedge's value, and the terms are only
// evaluated (lib/simplify/wedge_collapse.h).
#pragma once

#include "lib/simplify/quadric.h"

namespace lodbake {

// Expanded over u = (p, s, 1), a component's term splits into a part in p
// alone, which the components of one wedge sum into one plane-like
// quadric (`Quadric`, its weight unused), and the parts with s: Hoppe's
// memory-efficient form, and a third of the work per evaluation.
struct ComponentTerms {
  double ss = 0;                     // s^2
  double sp0 = 0, sp1 = 0, sp2 = 0;  // 2 s p_i
  double s1 = 0;                     // 2 s

  ComponentTerms& operator+=(const ComponentTerms& o) {
    ss += o.ss;
    sp0 += o.sp0;
    sp1 += o.sp1;
    sp2 += o.sp2;
    s1 += o.s1;
    return *this;
  }
};

/// Adds, for one face with corners p[0..2] (area `area`, unit normal
/// `normal`) and component values s[0..2], the term area * (s - g.p - d)^2
/// to `position` and `component`. A face without area adds nothing.
inline void add_attribute_term(Quadric* position, ComponentTerms* component, const Vec3d (&p)[3],
                               const double (&s)[3], const Vec3d& normal, double area) {
  if (!(area > 0)) return;
  const Vec3d e1{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
  const Vec3d e2{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
  // The gradient lies in the face's plane with g.e1 = s1 - s0 and
  // g.e2 = s2 - s0: the dual basis of (e1, e2) there is
  // (e2 x n, n x e1) / (2 * area).
  const Vec3d a{e2[1] * normal[2] - e2[2] * normal[1], e2[2] * normal[0] - e2[0] * normal[2],
                e2[0] * normal[1] - e2[1] * normal[0]};
  const Vec3d b{normal[1] * e1[2] - normal[2] * e1[1], normal[2] * e1[0] - normal[0] * e1[2],
                normal[0] * e1[1] - normal[1] * e1[0]};
  const double d1 = s[1] - s[0], d2 = s[2] - s[0];
  const double inv = 1.0 / (2.0 * area);
  const Vec3d g{(d1 * a[0] + d2 * b[0]) * inv, (d1 * a[1] + d2 * b[1]) * inv,
                (d1 * a[2] + d2 * b[2]) * inv};
  const double d = s[0] - (g[0] * p[0][0] + g[1] * p[0][1] + g[2] * p[0][2]);
  // (s - g.p - d)^2 = (g.p + d)^2 - 2 s (g.p + d) + s^2.
  *position += Quadric::from_plane(g, d, area);
  position->weight -= area;  // the weight is the geometric quadric's to keep
  component->ss += area;
  component->sp0 -= 2 * area * g[0];
  component->sp1 -= 2 * area * g[1];
  component->sp2 -= 2 * area * g[2];
  component->s1 -= 2 * area * d;
}

/// The p part of a wedge's terms at p, without the clamp of
/// Quadric::evaluate (the s parts may bring the sum back up).
inline double evaluate_position_part(const Quadric& q, const Vec3d& p) {
  const double x = p[0], y = p[1], z = p[2];
  return q.a00 * x * x + q.a11 * y * y + q.a22 * z * z +
         2 * (q.a01 * x * y + q.a02 * x * z + q.a12 * y * z) +
         2 * (q.b0 * x + q.b1 * y + q.b2 * z) + q.c;
}

/// One component's s part at (p, s).
inline double evaluate_component(const ComponentTerms& t, const Vec3d& p, double s) {
  return s * (t.ss * s + t.sp0 * p[0] + t.sp1 * p[1] + t.sp2 * p[2] + t.s1);
}

}  // namespace lodbake
