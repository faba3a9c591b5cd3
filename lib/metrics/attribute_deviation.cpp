// Attribute deviation between a scene and its simplification, Metro-style
// (Cignoni, Rocchini, Scopigno 1998) with the attributes read at the closest
// point, as the attribute-aware simplification papers measure their results
// (Garland & Heckbert 1998; Hoppe 1999): points are sampled on the input's
// world-space surface, each one's closest point on the output is found with
// a CGAL AABB tree, and TEXCOORD_0 and NORMAL interpolated there are
// compared with the input's at the sample.
//
// Choices, all fixed so that the result is reproducible bit for bit:
// - World space: the default scene's node trees (scene 0 without a default,
//   every parentless node without scenes), each node's matrix or TRS applied
//   to every mesh it uses; a mesh no reached node uses is taken once in its
//   own frame. Normals go through the inverse transpose and are normalised.
//   Skins and morph targets are not applied (the bind pose).
// - Samples: surface_sampling.h's pattern over all the input's world-space
//   triangles together (instances in traversal order), every referenced
//   vertex on top. Statistics are over the area samples, which follow the
//   area; a primitive that received none is represented by its vertices.
// - The closest point is sought among the output triangles whose material
//   JSON equals the sample's (a texture coordinate only means something on
//   its own material; numbers compared as the 32-bit floats they stand
//   for), all output triangles when no output material equals it. Where several output triangles
//   are equally near (within 1e-6 of the diagonal: a seam, a hard edge, a shared vertex, coincident
//   faces), the attribute deviation is the smallest among them, so a point
//   that carries two values on the output is compared with the nearer.
// - The Hausdorff distance ignores materials: input samples against all the
//   output's triangles, and as many output samples against all the input's.
// - Queries run in fixed blocks; each sample's result is stored at its index
//   and the statistics are reduced in sample order afterwards.
#include "lib/metrics/attribute_deviation.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "formats/mesh/vec3d.h"
#include "formats/scene/accessor_values.h"
#include "formats/scene/node_matrix.h"
#include "lib/metrics/surface_sampling.h"

namespace lodbake {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle3 = Kernel::Triangle_3;
using Sphere3 = Kernel::Sphere_3;
using TriangleIterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using PointAndId = Tree::Point_and_primitive_id;

using Vec2d = std::array<double, 2>;

constexpr size_t kBlockSamples = 4096;
constexpr uint64_t kMaxAreaSamples = uint64_t{1} << 30;
constexpr double kTieTolerance = 1e-6;  // of the diagonal
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool finite3(const Vec3d& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}
Point to_point(const Vec3d& p) {
  return Point(p[0], p[1], p[2]);
}

Vec3d transform_point(const Mat4& m, const Vec3d& p) {
  return {m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12],
          m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
          m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]};
}

// The inverse transpose of m's linear part (row-major 3x3): the cofactor
// matrix over the determinant. A singular part keeps the cofactors, which
// still map normals of the surviving directions.
std::array<double, 9> normal_matrix(const Mat4& m) {
  auto a = [&](int r, int c) { return m[c * 4 + r]; };
  std::array<double, 9> cof = {
      a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2),
      a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0), a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2),
      a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0), a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1),
      a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1), a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2),
      a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0)};
  const double det = a(0, 0) * cof[0] + a(0, 1) * cof[1] + a(0, 2) * cof[2];
  if (det != 0 && std::isfinite(det))
    for (double& c : cof)
      c /= det;
  return cof;
}

Vec3d unit(const Vec3d& v) {
  const double n = std::sqrt(dot(v, v));
  if (!(n > 0) || !std::isfinite(n)) return {0, 0, 0};
  return {v[0] / n, v[1] / n, v[2] / n};
}

// One primitive of one instance, in world space.
struct WorldPrimitive {
  uint32_t slot = 0;      // its PrimitiveDeviation (input) or 0 (output)
  int32_t material = -1;  // index into the scene's materials
  std::vector<Vec3d> positions;
  std::vector<Vec2d> uvs;      // empty: no TEXCOORD_0
  std::vector<Vec3d> normals;  // unit or zero; empty: no NORMAL
  std::vector<std::array<uint32_t, 3>> triangles;
};

struct WorldScene {
  std::vector<WorldPrimitive> primitives;            // instances in traversal order
  std::vector<std::pair<uint32_t, uint32_t>> slots;  // (mesh, primitive) per slot
};

std::string where(const char* name, size_t mesh, size_t primitive) {
  return std::string(name) + ": mesh " + std::to_string(mesh) + " primitive " +
         std::to_string(primitive);
}

Status check_stream(const SceneAttribute* a, ElementType type, uint32_t vertices,
                    const std::string& at) {
  if (a == nullptr) return Status::ok();
  if (a->data.type != type || a->data.count != vertices ||
      a->data.bytes.size() != static_cast<size_t>(a->data.count) * a->data.element_size())
    return invalid_input(at + ": " + a->semantic + " does not match POSITION's vertices");
  return Status::ok();
}

// The instances (mesh, world transform) of `scene`, in traversal order.
Result<std::vector<std::pair<uint32_t, Mat4>>> instances_of(const Scene& scene, const char* name) {
  const size_t n = scene.nodes.size();
  std::vector<uint32_t> roots;
  if (!scene.scenes.empty()) {
    const int32_t chosen = scene.default_scene < 0 ? 0 : scene.default_scene;
    if (static_cast<size_t>(chosen) >= scene.scenes.size())
      return invalid_input(std::string(name) + ": the default scene " + std::to_string(chosen) +
                           " does not exist");
    roots = scene.scenes[static_cast<size_t>(chosen)].nodes;
  } else {
    std::vector<uint8_t> child(n, 0);
    for (const SceneNode& node : scene.nodes)
      for (uint32_t c : node.children)
        if (c < n) child[c] = 1;
    for (uint32_t i = 0; i < n; ++i)
      if (!child[i]) roots.push_back(i);
  }
  std::vector<std::pair<uint32_t, Mat4>> out;
  std::vector<uint8_t> reached(n, 0);
  std::vector<uint8_t> used(scene.meshes.size(), 0);
  std::vector<std::pair<uint32_t, Mat4>> stack;  // iterative: no recursion on file depth
  for (auto it = roots.rbegin(); it != roots.rend(); ++it)
    stack.emplace_back(*it, identity_matrix());
  while (!stack.empty()) {
    const auto [index, parent] = stack.back();
    stack.pop_back();
    if (index >= n)
      return invalid_input(std::string(name) + ": node " + std::to_string(index) +
                           " does not exist");
    if (reached[index])
      return invalid_input(std::string(name) + ": node " + std::to_string(index) +
                           " is reached twice (a cycle or two parents)");
    reached[index] = 1;
    const SceneNode& node = scene.nodes[index];
    const Mat4 world = multiply(parent, local_matrix(node));
    if (node.mesh >= 0) {
      if (static_cast<size_t>(node.mesh) >= scene.meshes.size())
        return invalid_input(std::string(name) + ": node " + std::to_string(index) + " uses mesh " +
                             std::to_string(node.mesh) + ", which does not exist");
      out.emplace_back(static_cast<uint32_t>(node.mesh), world);
      used[static_cast<size_t>(node.mesh)] = 1;
    }
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
      stack.emplace_back(*c, world);
  }
  for (uint32_t m = 0; m < scene.meshes.size(); ++m)
    if (!used[m]) out.emplace_back(m, identity_matrix());
  return out;
}

// Every triangle primitive of every instance of `scene` in world space.
Result<WorldScene> flatten(const Scene& scene, const char* name) {
  WorldScene world;
  std::vector<std::vector<int64_t>> slot(scene.meshes.size());
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    for (uint32_t p = 0; p < scene.meshes[m].primitives.size(); ++p) {
      const bool triangles = scene.meshes[m].primitives[p].mode == PrimitiveMode::kTriangles ||
                             scene.meshes[m].primitives[p].mode == PrimitiveMode::kTriangleStrip ||
                             scene.meshes[m].primitives[p].mode == PrimitiveMode::kTriangleFan;
      slot[m].push_back(triangles ? static_cast<int64_t>(world.slots.size()) : -1);
      if (triangles) world.slots.emplace_back(m, p);
    }
  }
  const size_t materials = scene.materials.is_array() ? scene.materials.size() : 0;
  LODBAKE_ASSIGN_OR_RETURN(const auto instances, instances_of(scene, name));
  for (const auto& [mesh, transform] : instances) {
    const std::array<double, 9> nm = normal_matrix(transform);
    for (uint32_t p = 0; p < scene.meshes[mesh].primitives.size(); ++p) {
      if (slot[mesh][p] < 0) continue;
      const ScenePrimitive& prim = scene.meshes[mesh].primitives[p];
      const std::string at = where(name, mesh, p);
      WorldPrimitive wp;
      wp.slot = static_cast<uint32_t>(slot[mesh][p]);
      wp.material = prim.material;
      if (prim.material >= 0 && static_cast<size_t>(prim.material) >= materials)
        return invalid_input(at + ": material " + std::to_string(prim.material) +
                             " does not exist");
      const SceneAttribute* position = prim.find("POSITION");
      const uint32_t vertices = prim.vertex_count();
      if (position != nullptr) {
        if (position->data.type != ElementType::kVec3 ||
            position->data.bytes.size() !=
                static_cast<size_t>(position->data.count) * position->data.element_size())
          return invalid_input(at + ": POSITION is not a VEC3 stream");
      }
      const SceneAttribute* uv = prim.find("TEXCOORD_0");
      const SceneAttribute* normal = prim.find("NORMAL");
      LODBAKE_RETURN_IF_ERROR(check_stream(uv, ElementType::kVec2, vertices, at));
      LODBAKE_RETURN_IF_ERROR(check_stream(normal, ElementType::kVec3, vertices, at));
      if (prim.indices)
        for (uint32_t i : *prim.indices)
          if (i >= vertices)
            return invalid_input(at + ": index " + std::to_string(i) + " out of range (" +
                                 std::to_string(vertices) + " vertices)");
      wp.triangles = primitive_triangles(prim);
      if (wp.triangles.empty()) continue;
      std::vector<uint8_t> referenced(vertices, 0);
      for (const auto& t : wp.triangles)
        referenced[t[0]] = referenced[t[1]] = referenced[t[2]] = 1;
      wp.positions.resize(vertices);
      if (uv != nullptr) wp.uvs.resize(vertices);
      if (normal != nullptr) wp.normals.resize(vertices);
      for (uint32_t v = 0; v < vertices; ++v) {
        if (!referenced[v]) continue;
        const Vec3d local = {float_value(position->data, v, 0), float_value(position->data, v, 1),
                             float_value(position->data, v, 2)};
        wp.positions[v] = transform_point(transform, local);
        if (!finite3(local) || !finite3(wp.positions[v]))
          return invalid_input(at + ": vertex " + std::to_string(v) + " has a non-finite position");
        if (uv != nullptr) {
          wp.uvs[v] = {float_value(uv->data, v, 0), float_value(uv->data, v, 1)};
          if (!std::isfinite(wp.uvs[v][0]) || !std::isfinite(wp.uvs[v][1]))
            return invalid_input(at + ": vertex " + std::to_string(v) +
                                 " has a non-finite TEXCOORD_0");
        }
        if (normal != nullptr) {
          const Vec3d n = {float_value(normal->data, v, 0), float_value(normal->data, v, 1),
                           float_value(normal->data, v, 2)};
          if (!finite3(n))
            return invalid_input(at + ": vertex " + std::to_string(v) + " has a non-finite NORMAL");
          wp.normals[v] = unit({nm[0] * n[0] + nm[1] * n[1] + nm[2] * n[2],
                                nm[3] * n[0] + nm[4] * n[1] + nm[5] * n[2],
                                nm[6] * n[0] + nm[7] * n[1] + nm[8] * n[2]});
        }
      }
      world.primitives.push_back(std::move(wp));
    }
  }
  return world;
}

// A closest-point target: some triangles of a scene, each remembered as
// (world primitive, triangle), in an AABB tree.
struct Target {
  std::vector<Triangle3> triangles;
  std::vector<std::pair<uint32_t, uint32_t>> source;
  Tree tree;
  double spacing = 0;  // typical edge length: when the previous answer helps
};

void add_triangles(const WorldScene& world, size_t w, Target* target) {
  const WorldPrimitive& wp = world.primitives[w];
  for (uint32_t t = 0; t < wp.triangles.size(); ++t) {
    const auto& tri = wp.triangles[t];
    Triangle3 t3(to_point(wp.positions[tri[0]]), to_point(wp.positions[tri[1]]),
                 to_point(wp.positions[tri[2]]));
    if (!(t3.squared_area() > 0)) continue;  // no defined projection
    target->triangles.push_back(t3);
    target->source.emplace_back(static_cast<uint32_t>(w), t);
  }
}

void build(Target* target) {
  double area = 0;
  for (const Triangle3& t : target->triangles)
    area += std::sqrt(t.squared_area());
  target->spacing = std::sqrt(2.0 * area / static_cast<double>(target->triangles.size()));
  target->tree.rebuild(target->triangles.begin(), target->triangles.end());
  target->tree.accelerate_distance_queries();
}

// The closest point of triangle abc to p and its barycentric weights
// (Ericson, "Real-Time Collision Detection", 5.1.5).
std::pair<Vec3d, std::array<double, 3>> closest_on_triangle(const Vec3d& p, const Vec3d& a,
                                                            const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  std::array<double, 3> w;
  if (d1 <= 0 && d2 <= 0) {
    w = {1, 0, 0};
  } else {
    const Vec3d bp = sub(p, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    const Vec3d cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    const double vc = d1 * d4 - d3 * d2;
    const double vb = d5 * d2 - d1 * d6;
    const double va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) {
      w = {0, 1, 0};
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      const double v = d1 / (d1 - d3);
      w = {1 - v, v, 0};
    } else if (d6 >= 0 && d5 <= d6) {
      w = {0, 0, 1};
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      const double t = d2 / (d2 - d6);
      w = {1 - t, 0, t};
    } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      w = {0, 1 - t, t};
    } else {
      const double denom = 1.0 / (va + vb + vc);
      const double v = vb * denom, t = vc * denom;
      w = {1 - v - t, v, t};
    }
  }
  Vec3d q;
  for (int k = 0; k < 3; ++k)
    q[k] = w[0] * a[k] + w[1] * b[k] + w[2] * c[k];
  return {q, w};
}

// TEXCOORD_0 and NORMAL of a world primitive at barycentric `w` of
// triangle `t`; NaN where it has none (or the normals cancel out).
struct Attributes {
  Vec2d uv = {kNaN, kNaN};
  Vec3d normal = {kNaN, kNaN, kNaN};
};

Attributes attributes_at(const WorldPrimitive& wp, uint32_t t, const std::array<double, 3>& w) {
  Attributes out;
  const auto& tri = wp.triangles[t];
  if (!wp.uvs.empty()) {
    for (int k = 0; k < 2; ++k)
      out.uv[k] = w[0] * wp.uvs[tri[0]][k] + w[1] * wp.uvs[tri[1]][k] + w[2] * wp.uvs[tri[2]][k];
  }
  if (!wp.normals.empty()) {
    Vec3d n;
    for (int k = 0; k < 3; ++k)
      n[k] = w[0] * wp.normals[tri[0]][k] + w[1] * wp.normals[tri[1]][k] +
             w[2] * wp.normals[tri[2]][k];
    n = unit(n);
    if (n[0] != 0 || n[1] != 0 || n[2] != 0) out.normal = n;
  }
  return out;
}

double uv_distance(const Vec2d& a, const Vec2d& b) {
  const double du = a[0] - b[0], dv = a[1] - b[1];
  return std::sqrt(du * du + dv * dv);
}

// Angle between two unit vectors, accurate near 0 (acos is not).
double angle_degrees(const Vec3d& a, const Vec3d& b) {
  const Vec3d c = cross(a, b);
  return std::atan2(std::sqrt(dot(c, c)), dot(a, b)) * (180.0 / 3.14159265358979323846);
}

// A point on a world triangle: primitive, triangle, barycentric weights.
struct Sample {
  uint32_t primitive = 0;
  uint32_t triangle = 0;
  std::array<double, 3> w{};
  bool vertex = false;
};

// Every referenced vertex (one per primitive and vertex), then `budget`
// area samples over all the triangles together.
std::vector<Sample> make_samples(const WorldScene& world, uint64_t budget) {
  std::vector<Sample> samples;
  std::vector<double> areas;
  for (uint32_t p = 0; p < world.primitives.size(); ++p) {
    const WorldPrimitive& wp = world.primitives[p];
    std::vector<uint8_t> seen(wp.positions.size(), 0);
    for (uint32_t t = 0; t < wp.triangles.size(); ++t) {
      const auto& tri = wp.triangles[t];
      for (int k = 0; k < 3; ++k) {
        if (seen[tri[k]]) continue;
        seen[tri[k]] = 1;
        Sample s{p, t, {0, 0, 0}, true};
        s.w[k] = 1;
        samples.push_back(s);
      }
      const Vec3d c = cross(sub(wp.positions[tri[1]], wp.positions[tri[0]]),
                            sub(wp.positions[tri[2]], wp.positions[tri[0]]));
      areas.push_back(0.5 * std::sqrt(dot(c, c)));
    }
  }
  const std::vector<uint64_t> counts = metrics::samples_per_triangle(areas, budget);
  size_t flat = 0;
  for (uint32_t p = 0; p < world.primitives.size(); ++p) {
    for (uint32_t t = 0; t < world.primitives[p].triangles.size(); ++t, ++flat) {
      for (uint64_t j = 0; j < counts[flat]; ++j)
        samples.push_back(Sample{p, t, metrics::triangle_sample(j), false});
    }
  }
  return samples;
}

Vec3d sample_point(const WorldScene& world, const Sample& s) {
  const WorldPrimitive& wp = world.primitives[s.primitive];
  const auto& tri = wp.triangles[s.triangle];
  Vec3d p;
  for (int k = 0; k < 3; ++k)
    p[k] = s.w[0] * wp.positions[tri[0]][k] + s.w[1] * wp.positions[tri[1]][k] +
           s.w[2] * wp.positions[tri[2]][k];
  return p;
}

// Closest-point queries of one block that reuse the previous answer as a
// hint when it is near (as measure_surface_distance does).
class HintedQuery {
 public:
  explicit HintedQuery(const Target& target) : target_(target) {}
  PointAndId closest(const Point& q) {
    const double r2 = target_.spacing * target_.spacing;
    last_ = has_last_ && CGAL::squared_distance(q, last_.first) <= r2
                ? target_.tree.closest_point_and_primitive(q, last_)
                : target_.tree.closest_point_and_primitive(q);
    has_last_ = true;
    return last_;
  }

 private:
  const Target& target_;
  PointAndId last_;
  bool has_last_ = false;
};

struct SampleResult {
  double distance = 0;  // to the material's triangles
  double surface = 0;   // to all the output's triangles
  double uv = kNaN;
  double normal = kNaN;
};

// One input sample against its target: the distance, and the attribute
// deviations at the nearest of the equally near output triangles.
SampleResult measure_sample(const WorldScene& input, const WorldScene& output, const Sample& s,
                            const Target& target, HintedQuery* query, double tie) {
  const WorldPrimitive& wp = input.primitives[s.primitive];
  const Vec3d q = sample_point(input, s);
  const Point qp = to_point(q);
  const PointAndId found = query->closest(qp);
  const double d = std::sqrt(CGAL::squared_distance(qp, found.first));
  SampleResult r;
  r.distance = r.surface = d;
  const bool wants_uv = !wp.uvs.empty();
  const bool wants_normal = !wp.normals.empty();
  if (!wants_uv && !wants_normal) return r;
  const Attributes mine = attributes_at(wp, s.triangle, s.w);

  std::vector<size_t> candidates = {static_cast<size_t>(found.second - target.triangles.begin())};
  std::vector<PointAndId::second_type> near;
  target.tree.all_intersected_primitives(Sphere3(qp, (d + tie) * (d + tie)),
                                         std::back_inserter(near));
  for (const auto& id : near)
    candidates.push_back(static_cast<size_t>(id - target.triangles.begin()));
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

  struct Candidate {
    double distance;
    Attributes at;
  };
  std::vector<Candidate> found_at;
  double nearest = HUGE_VAL;
  for (size_t c : candidates) {
    const auto [w_index, t] = target.source[c];
    const WorldPrimitive& op = output.primitives[w_index];
    const auto& tri = op.triangles[t];
    const auto [point, w] =
        closest_on_triangle(q, op.positions[tri[0]], op.positions[tri[1]], op.positions[tri[2]]);
    const Vec3d delta = sub(point, q);
    const double dist = std::sqrt(dot(delta, delta));
    nearest = std::min(nearest, dist);
    found_at.push_back({dist, attributes_at(op, t, w)});
  }
  r.distance = std::min(d, nearest);
  for (const Candidate& c : found_at) {
    if (c.distance > r.distance + tie) continue;
    if (wants_uv && std::isfinite(c.at.uv[0])) {
      const double du = uv_distance(mine.uv, c.at.uv);
      r.uv = std::isnan(r.uv) ? du : std::min(r.uv, du);
    }
    if (wants_normal && std::isfinite(mine.normal[0]) && std::isfinite(c.at.normal[0])) {
      const double dn = angle_degrees(mine.normal, c.at.normal);
      r.normal = std::isnan(r.normal) ? dn : std::min(r.normal, dn);
    }
  }
  return r;
}

// Mean and nearest-rank 95th percentile (the ceil(0.95 n)-th smallest).
DeviationStats stats_of(std::vector<double> values) {
  DeviationStats s;
  s.samples = values.size();
  if (values.empty()) return s;
  double sum = 0;
  for (double v : values)
    sum += v;
  s.mean = sum / static_cast<double>(values.size());
  const size_t rank = (values.size() * 95 + 99) / 100;  // ceil(0.95 n), >= 1
  std::nth_element(values.begin(), values.begin() + static_cast<ptrdiff_t>(rank - 1), values.end());
  s.p95 = values[rank - 1];
  return s;
}

double diagonal_of(const WorldScene& world) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  double hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const WorldPrimitive& wp : world.primitives)
    for (const auto& t : wp.triangles)
      for (uint32_t v : t)
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], wp.positions[v][k]);
          hi[k] = std::max(hi[k], wp.positions[v][k]);
        }
  const Vec3d d = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  return std::sqrt(dot(d, d));
}

// JSON equality with numbers compared as 32-bit floats: writers print a
// material's factors at different lengths (gltfpack writes 0.0405062996
// for an input's 0.04050629958510399, the same float).
bool same_json(const SceneJson& a, const SceneJson& b) {
  if (a.is_number() && b.is_number())
    return static_cast<float>(a.get<double>()) == static_cast<float>(b.get<double>());
  if (a.is_array() && b.is_array()) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
      if (!same_json(a[i], b[i])) return false;
    return true;
  }
  if (a.is_object() && b.is_object()) {
    if (a.size() != b.size()) return false;
    for (auto it = a.begin(); it != a.end(); ++it) {
      const auto other = b.find(it.key());
      if (other == b.end() || !same_json(it.value(), *other)) return false;
    }
    return true;
  }
  return a == b;
}

bool same_material(const Scene& a, int32_t ma, const Scene& b, int32_t mb) {
  static const SceneJson kNone;
  const SceneJson& ja = ma < 0 ? kNone : a.materials[static_cast<size_t>(ma)];
  const SceneJson& jb = mb < 0 ? kNone : b.materials[static_cast<size_t>(mb)];
  return same_json(ja, jb);
}

Result<SceneDeviation> measure(const Scene& input, const Scene& output,
                               const DeviationOptions& options) {
  if (options.area_samples > kMaxAreaSamples)
    return invalid_input("area_samples " + std::to_string(options.area_samples) +
                         " exceeds the limit of " + std::to_string(kMaxAreaSamples));
  const unsigned threads = options.threads;
  LODBAKE_ASSIGN_OR_RETURN(const WorldScene in, flatten(input, "input"));
  LODBAKE_ASSIGN_OR_RETURN(const WorldScene out, flatten(output, "output"));
  if (in.primitives.empty()) return invalid_input("input has no triangles");
  if (out.primitives.empty()) return invalid_input("output has no triangles");

  // Targets: one per distinct output material, and all the output's
  // triangles (the material targets' union, reused when there is one).
  std::vector<std::unique_ptr<Target>> groups;
  std::vector<int32_t> group_material;  // a material of `output` standing for the group
  for (size_t w = 0; w < out.primitives.size(); ++w) {
    const int32_t m = out.primitives[w].material;
    size_t g = 0;
    while (g < groups.size() && !same_material(output, group_material[g], output, m))
      ++g;
    if (g == groups.size()) {
      groups.push_back(std::make_unique<Target>());
      group_material.push_back(m);
    }
    add_triangles(out, w, groups[g].get());
  }
  const bool one_group = groups.size() == 1;
  auto all_output = std::make_unique<Target>();
  if (!one_group)
    for (size_t w = 0; w < out.primitives.size(); ++w)
      add_triangles(out, w, all_output.get());
  const Target* surface = one_group ? groups[0].get() : all_output.get();
  auto all_input = std::make_unique<Target>();
  for (size_t w = 0; w < in.primitives.size(); ++w)
    add_triangles(in, w, all_input.get());
  if (all_input->triangles.empty())
    return invalid_input("input has no triangle with non-zero area");
  if (surface->triangles.empty()) return invalid_input("output has no triangle with non-zero area");
  std::vector<Target*> to_build = {all_input.get()};
  if (!one_group) to_build.push_back(all_output.get());
  for (auto& g : groups)
    if (!g->triangles.empty()) to_build.push_back(g.get());
  if (!metrics::run_blocks(to_build.size(), threads, [&](size_t i) { build(to_build[i]); }))
    return runtime_error("building the AABB trees failed (out of memory)");

  // Each input primitive's target.
  std::vector<const Target*> target_of(in.primitives.size(), surface);
  for (size_t w = 0; w < in.primitives.size(); ++w)
    for (size_t g = 0; g < groups.size(); ++g)
      if (!groups[g]->triangles.empty() &&
          same_material(input, in.primitives[w].material, output, group_material[g]))
        target_of[w] = groups[g].get();

  SceneDeviation result;
  result.diagonal = diagonal_of(in);
  const double tie = kTieTolerance * result.diagonal;

  const std::vector<Sample> samples = make_samples(in, options.area_samples);
  std::vector<SampleResult> results(samples.size());
  const size_t blocks = (samples.size() + kBlockSamples - 1) / kBlockSamples;
  if (!metrics::run_blocks(blocks, threads, [&](size_t b) {
        const size_t begin = b * kBlockSamples;
        const size_t end = std::min(samples.size(), begin + kBlockSamples);
        HintedQuery surface_query(*surface);
        std::vector<std::unique_ptr<HintedQuery>> queries(groups.size());
        for (size_t i = begin; i < end; ++i) {
          const Target* target = target_of[samples[i].primitive];
          size_t g = 0;
          while (g < groups.size() && groups[g].get() != target)
            ++g;
          HintedQuery* query = &surface_query;
          if (g < groups.size()) {
            if (!queries[g]) queries[g] = std::make_unique<HintedQuery>(*target);
            query = queries[g].get();
          }
          results[i] = measure_sample(in, out, samples[i], *target, query, tie);
          if (target != surface)
            results[i].surface = std::sqrt(CGAL::squared_distance(
                to_point(sample_point(in, samples[i])),
                surface_query.closest(to_point(sample_point(in, samples[i]))).first));
        }
      }))
    return runtime_error("a distance query failed (out of memory or a CGAL error)");

  // The other side of the Hausdorff distance: output samples to the input.
  const std::vector<Sample> back = make_samples(out, options.area_samples);
  std::vector<double> back_max((back.size() + kBlockSamples - 1) / kBlockSamples, 0);
  if (!metrics::run_blocks(back_max.size(), threads, [&](size_t b) {
        const size_t begin = b * kBlockSamples;
        const size_t end = std::min(back.size(), begin + kBlockSamples);
        HintedQuery query(*all_input);
        for (size_t i = begin; i < end; ++i) {
          const Point q = to_point(sample_point(out, back[i]));
          back_max[b] =
              std::max(back_max[b], std::sqrt(CGAL::squared_distance(q, query.closest(q).first)));
        }
      }))
    return runtime_error("a distance query failed (out of memory or a CGAL error)");

  // Statistics in sample order: the area samples, or a primitive's vertex
  // samples when it received no area sample.
  const size_t slots = in.slots.size();
  std::vector<uint8_t> has_area(slots, 0);
  for (const Sample& s : samples)
    if (!s.vertex) has_area[in.primitives[s.primitive].slot] = 1;
  std::vector<std::vector<double>> distance(slots), uv(slots), normal(slots);
  std::vector<double> all_distance, all_uv, all_normal;
  std::vector<double> max_distance(slots, 0);
  double hausdorff = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const uint32_t slot = in.primitives[samples[i].primitive].slot;
    const SampleResult& r = results[i];
    max_distance[slot] = std::max(max_distance[slot], r.distance);
    hausdorff = std::max(hausdorff, r.surface);
    if (samples[i].vertex && has_area[slot]) continue;
    distance[slot].push_back(r.distance);
    all_distance.push_back(r.distance);
    if (!std::isnan(r.uv)) {
      uv[slot].push_back(r.uv);
      all_uv.push_back(r.uv);
    }
    if (!std::isnan(r.normal)) {
      normal[slot].push_back(r.normal);
      all_normal.push_back(r.normal);
    }
  }
  for (double m : back_max)
    hausdorff = std::max(hausdorff, m);
  for (size_t s = 0; s < slots; ++s) {
    PrimitiveDeviation p;
    p.mesh = in.slots[s].first;
    p.primitive = in.slots[s].second;
    p.distance = stats_of(std::move(distance[s]));
    p.max_distance = max_distance[s];
    p.uv = stats_of(std::move(uv[s]));
    p.normal_degrees = stats_of(std::move(normal[s]));
    result.primitives.push_back(p);
  }
  result.distance = stats_of(std::move(all_distance));
  result.uv = stats_of(std::move(all_uv));
  result.normal_degrees = stats_of(std::move(all_normal));
  result.hausdorff = hausdorff;
  if (result.diagonal > 0) {
    result.hausdorff_relative = hausdorff / result.diagonal;
    result.mean_relative = result.distance.mean / result.diagonal;
  }
  return result;
}

}  // namespace

Result<SceneDeviation> measure_scene_deviation(const Scene& input, const Scene& output,
                                               const DeviationOptions& options) {
  try {
    return measure(input, output, options);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while measuring the attribute deviation");
  } catch (const std::exception& e) {
    return runtime_error(std::string("measuring the attribute deviation failed: ") + e.what());
  }
}

}  // namespace lodbake
