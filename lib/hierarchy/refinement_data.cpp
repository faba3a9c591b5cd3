// Refinement data for Hoppe's (1997) view-dependent criteria on a balanced
// vertex hierarchy. Choices where the papers are vague:
// - the sphere of a node is centred at its position (where the vertex is
//   drawn) and holds the spheres of its children: r(p) = max over children
//   of |c - p| + r(c), leaves 0, so it bounds every leaf of the subtree;
// - the cone of normals: the axis is the area-weighted mean normal of the
//   faces around the subtree's leaves, the half-angle bounds the children's
//   cones (angle between axes + child half-angle), a leaf's cone bounds its
//   own faces' normals; a zero mean normal gives the full cone (pi);
// - the deviation space D(mu, delta) of Hoppe: delta is the largest
//   distance of a subtree leaf from the plane through the node's position
//   perpendicular to its cone axis (the part of the error that vanishes when
//   the surface is seen face-on), mu the largest collapse error in the
//   subtree (the quadric's RMS distance, which bounds the uniform part);
//   both squared as qrefine compares squares.
#include "lib/hierarchy/refinement_data.h"

#include <algorithm>
#include <cmath>
#include <new>

namespace lodbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
using V3 = std::array<double, 3>;

V3 to_d(const Vec3f& p) {
  return {p[0], p[1], p[2]};
}
V3 sub(const V3& a, const V3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double len(const V3& a) {
  return std::sqrt(dot(a, a));
}
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double angle(const V3& a, const V3& b) {
  const double la = len(a), lb = len(b);
  if (!(la > 0) || !(lb > 0)) return kPi;
  return std::atan2(len(cross(a, b)), dot(a, b));
}

}  // namespace

Result<std::vector<NodeRefinement>> compute_refinement_data(const VertexHierarchy& h,
                                                            const TriangleMesh& fine) {
  try {
    const size_t n = h.node_count();
    std::vector<uint32_t> leaf_of(fine.positions.size(), kNoNode);
    size_t leaves = 0;
    for (uint32_t i = 0; i < n; ++i) {
      if (!h.is_leaf(i)) continue;
      ++leaves;
      if (h.input_vertex[i] >= leaf_of.size())
        return invalid_input("leaf input vertex out of range");
      leaf_of[h.input_vertex[i]] = i;
    }
    if (leaves != fine.positions.size()) {
      return invalid_input("mesh has " + std::to_string(fine.positions.size()) +
                           " vertices, the hierarchy " + std::to_string(leaves) + " leaves");
    }
    auto face_normal = [&](const Triangle& t) {
      const V3 p0 = to_d(fine.positions[t[0]]);
      return cross(sub(to_d(fine.positions[t[1]]), p0), sub(to_d(fine.positions[t[2]]), p0));
    };
    std::vector<V3> normal_sum(n, V3{0, 0, 0});
    std::vector<uint8_t> has_face(n, 0);
    for (const Triangle& t : fine.triangles) {
      for (uint32_t v : t) {
        if (v >= fine.positions.size()) return invalid_input("triangle index out of range");
      }
      const V3 nrm = face_normal(t);
      for (uint32_t v : t) {
        const uint32_t leaf = leaf_of[v];
        for (int k = 0; k < 3; ++k)
          normal_sum[leaf][k] += nrm[k];
        has_face[leaf] = 1;
      }
    }
    // A leaf's cone: its faces' normals against its axis, in a second pass
    // over the faces instead of a list of normals per leaf (a heap block
    // per vertex, the largest part of this step's peak). The maximum skips
    // NaN angles either way, so the order of the faces does not matter.
    std::vector<double> leaf_angle(n, 0);
    for (const Triangle& t : fine.triangles) {
      const V3 nrm = face_normal(t);
      for (uint32_t v : t) {
        const uint32_t leaf = leaf_of[v];
        leaf_angle[leaf] = std::max(leaf_angle[leaf], angle(normal_sum[leaf], nrm));
      }
    }
    std::vector<NodeRefinement> out(n);
    // The cone axis is the normal sum itself: no copy of it.
    const std::vector<V3>& axis = normal_sum;
    // Children have larger indices than parents: one backward sweep is bottom-up.
    for (size_t i = n; i-- > 0;) {
      if (h.is_leaf(static_cast<uint32_t>(i))) {
        if (!has_face[i] || !(len(axis[i]) > 0)) leaf_angle[i] = kPi;
        continue;
      }
      const uint32_t c0 = h.first_child[i];
      for (int k = 0; k < 3; ++k)
        normal_sum[i][k] = normal_sum[c0][k] + normal_sum[c0 + 1][k];
      double a = 0, r = 0, mu = h.error[i];
      for (uint32_t c : {c0, c0 + 1}) {
        a = std::max(a, angle(axis[i], axis[c]) + leaf_angle[c]);
        r = std::max(r, len(sub(to_d(h.position[c]), to_d(h.position[i]))) + out[c].radius);
        mu = std::max(mu, std::sqrt(double{out[c].mu2}));
      }
      leaf_angle[i] = len(axis[i]) > 0 ? std::min(kPi, a) : kPi;
      out[i].radius = static_cast<float>(r);
      out[i].mu2 = static_cast<float>(mu * mu);
    }
    for (size_t i = 0; i < n; ++i) {
      const double l = len(axis[i]);
      out[i].cone_axis =
          l > 0 ? Vec3f{static_cast<float>(axis[i][0] / l), static_cast<float>(axis[i][1] / l),
                        static_cast<float>(axis[i][2] / l)}
                : Vec3f{0, 0, 1};
      out[i].cone_half_angle = static_cast<float>(leaf_angle[i]);
    }
    // delta: each leaf against every ancestor's tangent plane (depth <= 64).
    std::vector<V3>().swap(normal_sum);
    std::vector<uint8_t>().swap(has_face);
    std::vector<double> delta = std::move(leaf_angle);
    std::fill(delta.begin(), delta.end(), 0.0);
    for (uint32_t leaf = 0; leaf < n; ++leaf) {
      if (!h.is_leaf(leaf)) continue;
      const V3 q = to_d(h.position[leaf]);
      for (uint32_t a = h.parent[leaf]; a != kNoNode; a = h.parent[a]) {
        const V3 ax = to_d(out[a].cone_axis);
        delta[a] = std::max(delta[a], std::fabs(dot(sub(q, to_d(h.position[a])), ax)));
      }
    }
    for (size_t i = 0; i < n; ++i)
      out[i].delta2 = static_cast<float>(delta[i] * delta[i]);
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory computing refinement data");
  }
}

}  // namespace lodbake
