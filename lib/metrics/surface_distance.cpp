// Hausdorff and mean distance between two triangle meshes by sampling, in
// the manner of Metro (Cignoni, Rocchini, Scopigno, "Metro: measuring error
// on simplified surfaces", 1998): points are sampled on one surface and
// their distance to the other is the distance to its closest point, found
// with a CGAL AABB tree (a primitive per triangle index of the mesh,
// Simple_cartesian<double>).
//
// Choices where "sample the surface" is vague, all fixed so the result is
// reproducible bit for bit:
// - Samples of a mesh: every referenced vertex (where a simplification
//   moves the surface most, in half-edge placement), then `area_samples` points inside
//   the triangles. Triangle t receives round(C_t) - round(C_{t-1}) of them,
//   C_t being the running sum of area * area_samples / total_area in
//   triangle order, so the shares follow the area and add up to the budget.
//   Inside a triangle, sample 0 is the centroid and sample j >= 1 the j-th
//   point of the R2 low-discrepancy sequence (Roberts 2018, from the plastic
//   number) folded from the unit square into the triangle: a fixed pattern
//   that stays spread out for any count.
// - The maximum is over all samples; the mean over the area samples only,
//   which, being spread in proportion to area, estimates the area-weighted
//   mean distance (vertices would over-weight dense regions). A mesh without
//   area (or a zero budget) falls back to the mean over its vertices. The
//   symmetric mean is the plain average of the two one-sided means, so each
//   surface counts the same whatever its sample count.
// - Triangles with exactly zero area are left out of the AABB trees (their
//   closest-point projection is undefined); their vertices are still sampled.
// - A query starts from the previous query's closest point when that point
//   is within the target's typical edge length of it (consecutive samples on
//   a dense mesh), else from the tree's KD-tree hint (the nearest triangle
//   reference point). The hint only bounds the search: the answer is the
//   nearest point either way, up to ties between equally near triangles.
//   (Reusing the previous answer unconditionally was several times slower
//   on scans, whose vertex order jumps.)
// - The queries run in fixed blocks of samples on any number of threads;
//   each block keeps its own maximum and sum and the blocks are reduced in
//   order, so the thread count never changes a bit of the result.
#include "lib/metrics/surface_distance.h"

#include <CGAL/AABB_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iterator>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "lib/metrics/surface_sampling.h"

namespace lodbake {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle3 = Kernel::Triangle_3;

Point to_point(const Vec3f& p) {
  return Point(p[0], p[1], p[2]);
}

Triangle3 triangle_of(const TriangleMesh& mesh, uint32_t t) {
  const Triangle& tri = mesh.triangles[t];
  return Triangle3(to_point(mesh.positions[tri[0]]), to_point(mesh.positions[tri[1]]),
                   to_point(mesh.positions[tri[2]]));
}

// A tree's primitive is a triangle index of the mesh; its CGAL triangle is
// made from the float positions whenever the tree reads it. A stored copy
// (AABB_triangle_primitive over a vector of CGAL triangles) cost 72 bytes
// per triangle. Float to double is exact, so the triangles, and the tree,
// its hints and every distance, are the same.
struct TriangleMap {
  using key_type = uint32_t;
  using value_type = Triangle3;
  using reference = Triangle3;
  using category = boost::readable_property_map_tag;
  const TriangleMesh* mesh = nullptr;
  friend Triangle3 get(const TriangleMap& map, uint32_t t) { return triangle_of(*map.mesh, t); }
};
// The reference point (the KD-tree's hints): the first vertex, as
// AABB_triangle_primitive's.
struct FirstVertexMap {
  using key_type = uint32_t;
  using value_type = Point;
  using reference = Point;
  using category = boost::readable_property_map_tag;
  const TriangleMesh* mesh = nullptr;
  friend Point get(const FirstVertexMap& map, uint32_t t) {
    return to_point(map.mesh->positions[map.mesh->triangles[t][0]]);
  }
};
using Primitive =
    CGAL::AABB_primitive<uint32_t, TriangleMap, FirstVertexMap, CGAL::Tag_true, CGAL::Tag_false>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

// The reference points of primitives [p, ...), made as read, for the
// KD-tree of hints (forward, so that the KD-tree sizes its copy once).
class ReferencePoints {
 public:
  using iterator_category = std::forward_iterator_tag;
  using value_type = Point;
  using difference_type = std::ptrdiff_t;
  using pointer = const Point*;
  using reference = Point;

  ReferencePoints() = default;
  ReferencePoints(const Primitive* p, FirstVertexMap map) : p_(p), map_(map) {}
  Point operator*() const { return get(map_, p_->id()); }
  ReferencePoints& operator++() {
    ++p_;
    return *this;
  }
  ReferencePoints operator++(int) {
    ReferencePoints old = *this;
    ++p_;
    return old;
  }
  bool operator==(const ReferencePoints& o) const { return p_ == o.p_; }
  bool operator!=(const ReferencePoints& o) const { return p_ != o.p_; }

 private:
  const Primitive* p_ = nullptr;
  FirstVertexMap map_;
};

// The tree's primitives in its own (built) order, which is the order of
// the leaves from left to right: true when they lie contiguously from the
// leftmost leaf's first primitive, as CGAL 5's tree stores them. `range`
// is how many primitives lie under `node`; `next` the one expected next.
using TreeNode = CGAL::AABB_node<CGAL::AABB_traits<Kernel, Primitive>>;
bool leaves_in_order(const TreeNode& node, size_t range, const Primitive** next) {
  auto leaf = [next](const Primitive& p) {
    if (*next && &p != *next) return false;
    *next = &p + 1;
    return true;
  };
  switch (range) {
    case 2:
      return leaf(node.left_data()) && leaf(node.right_data());
    case 3:
      return leaf(node.left_data()) && leaves_in_order(node.right_child(), 2, next);
    default:
      return leaves_in_order(node.left_child(), range / 2, next) &&
             leaves_in_order(node.right_child(), range - range / 2, next);
  }
}

using HintSearch = CGAL::Orthogonal_k_neighbor_search<CGAL::Search_traits_3<Kernel>>;

// A mesh's AABB tree and the KD-tree of its reference points, whose nearest
// point to a query is the hint a query starts from. CGAL's own KD-tree
// (accelerate_distance_queries()) stores each point with its id and is
// built from two copies of them, the second grown by doubling: about 200
// bytes per triangle at its peak on the 3.5M-triangle dragon. This one is
// CGAL's KD-tree of the same points in the same order, with the same
// splitter and search, without the ids (a hint is a point) and sized once,
// so every hint, and every distance, is the same.
class Target {
 public:
  Target(const TriangleMesh& mesh, std::vector<uint32_t>* triangles) {
    tree_.rebuild(triangles->begin(), triangles->end(), TriangleMap{&mesh}, FirstVertexMap{&mesh});
    // The tree holds its own copy of the indices.
    *triangles = std::vector<uint32_t>();
    const Primitive* end = nullptr;
    if (tree_.size() > 1 && leaves_in_order(*tree_.root_node(), tree_.size(), &end) && end) {
      tree_.do_not_accelerate_distance_queries();
      const FirstVertexMap map{&mesh};
      hints_ = std::make_unique<HintSearch::Tree>(ReferencePoints(end - tree_.size(), map),
                                                  ReferencePoints(end, map));
      // Built here, not lazily by the first (concurrent) query.
      hints_->build();
    } else {
      tree_.accelerate_distance_queries();
    }
  }

  // The closest point of the surface to q, the search started from the
  // hint.
  Point closest_point(const Point& q) const {
    if (!hints_) return tree_.closest_point(q);
    const HintSearch search(*hints_, q, 1);
    return tree_.closest_point(q, search.begin()->first);
  }
  // Likewise, started from `hint`.
  Point closest_point(const Point& q, const Point& hint) const {
    return tree_.closest_point(q, hint);
  }

 private:
  Tree tree_;
  std::unique_ptr<HintSearch::Tree> hints_;
};

constexpr size_t kBlockSamples = 4096;
constexpr uint64_t kMaxAreaSamples = uint64_t{1} << 30;

Status validate(const TriangleMesh& mesh, const char* name) {
  if (mesh.triangles.empty()) return invalid_input(std::string(name) + " has no triangles");
  const size_t n = mesh.positions.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (uint32_t v : mesh.triangles[t]) {
      if (v >= n) {
        return invalid_input(std::string(name) + ": triangle " + std::to_string(t) +
                             " has vertex index " + std::to_string(v) + " out of range (" +
                             std::to_string(n) + " vertices)");
      }
      const Vec3f& p = mesh.positions[v];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
        return invalid_input(std::string(name) + ": vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
      }
    }
  }
  return Status::ok();
}

std::vector<uint32_t> referenced_vertices(const TriangleMesh& mesh) {
  std::vector<uint8_t> used(mesh.positions.size(), 0);
  for (const Triangle& t : mesh.triangles)
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
  std::vector<uint32_t> list;
  for (size_t v = 0; v < used.size(); ++v) {
    if (used[v]) list.push_back(static_cast<uint32_t>(v));
  }
  return list;
}

// The triangles with non-zero area, by index, for the tree.
std::vector<uint32_t> tree_triangles(const TriangleMesh& mesh) {
  std::vector<uint32_t> out;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (triangle_of(mesh, static_cast<uint32_t>(t)).squared_area() > 0)
      out.push_back(static_cast<uint32_t>(t));
  }
  return out;
}

struct Samples {
  std::vector<Point> points;
  size_t vertex_count = 0;  // points[0, vertex_count) are vertices, the rest area samples
};

Samples make_samples(const TriangleMesh& mesh, uint64_t budget) {
  Samples samples;
  const std::vector<uint32_t> vertices = referenced_vertices(mesh);
  std::vector<double> areas(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    areas[t] =
        std::sqrt(Triangle3(to_point(mesh.positions[tri[0]]), to_point(mesh.positions[tri[1]]),
                            to_point(mesh.positions[tri[2]]))
                      .squared_area());
  }
  const std::vector<uint64_t> counts = metrics::samples_per_triangle(areas, budget);
  uint64_t placed = 0;
  for (uint64_t c : counts)
    placed += c;
  samples.points.reserve(vertices.size() + placed);
  for (uint32_t v : vertices)
    samples.points.push_back(to_point(mesh.positions[v]));
  samples.vertex_count = samples.points.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3f& p0 = mesh.positions[mesh.triangles[t][0]];
    const Vec3f& p1 = mesh.positions[mesh.triangles[t][1]];
    const Vec3f& p2 = mesh.positions[mesh.triangles[t][2]];
    for (uint64_t j = 0; j < counts[t]; ++j) {
      const auto [w, u, v] = metrics::triangle_sample(j);
      samples.points.emplace_back(w * p0[0] + u * p1[0] + v * p2[0],
                                  w * p0[1] + u * p1[1] + v * p2[1],
                                  w * p0[2] + u * p1[2] + v * p2[2]);
    }
  }
  return samples;
}

struct BlockResult {
  double max = 0;
  double vertex_sum = 0;
  double area_sum = 0;
};

// The target's typical edge length, sqrt(2 * mean triangle area): a hint
// that close to the next query bounds its search about as tightly as the
// KD-tree's nearest vertex, without the KD-tree search.
double typical_spacing(const TriangleMesh& mesh, const std::vector<uint32_t>& triangles) {
  double area = 0;
  for (uint32_t t : triangles)
    area += std::sqrt(triangle_of(mesh, t).squared_area());
  return std::sqrt(2.0 * area / static_cast<double>(triangles.size()));
}

Result<OneSidedDistance> one_sided(const Samples& samples, const Target& target, double spacing,
                                   unsigned threads) {
  const double reuse_radius2 = spacing * spacing;
  const size_t n = samples.points.size();
  const size_t blocks = (n + kBlockSamples - 1) / kBlockSamples;
  std::vector<BlockResult> results(blocks);
  const bool ok = metrics::run_blocks(blocks, threads, [&](size_t b) {
    BlockResult r;
    const size_t begin = b * kBlockSamples;
    const size_t end = std::min(n, begin + kBlockSamples);
    Point closest;
    for (size_t i = begin; i < end; ++i) {
      const Point& q = samples.points[i];
      closest = i > begin && CGAL::squared_distance(q, closest) <= reuse_radius2
                    ? target.closest_point(q, closest)
                    : target.closest_point(q);
      const double d = std::sqrt(CGAL::squared_distance(q, closest));
      r.max = std::max(r.max, d);
      (i < samples.vertex_count ? r.vertex_sum : r.area_sum) += d;
    }
    results[b] = r;
  });
  if (!ok) return runtime_error("a distance query failed (out of memory or a CGAL error)");
  OneSidedDistance out;
  double vertex_sum = 0;
  double area_sum = 0;
  for (const BlockResult& r : results) {
    out.max = std::max(out.max, r.max);
    vertex_sum += r.vertex_sum;
    area_sum += r.area_sum;
  }
  out.vertex_samples = samples.vertex_count;
  out.area_samples = n - samples.vertex_count;
  if (out.area_samples > 0) {
    out.mean = area_sum / static_cast<double>(out.area_samples);
  } else if (out.vertex_samples > 0) {
    out.mean = vertex_sum / static_cast<double>(out.vertex_samples);
  }
  return out;
}

double diagonal_of(const TriangleMesh& mesh) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  double hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Triangle& t : mesh.triangles) {
    for (uint32_t v : t) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], static_cast<double>(mesh.positions[v][k]));
        hi[k] = std::max(hi[k], static_cast<double>(mesh.positions[v][k]));
      }
    }
  }
  const double dx = hi[0] - lo[0];
  const double dy = hi[1] - lo[1];
  const double dz = hi[2] - lo[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

Result<SurfaceDistance> measure(const TriangleMesh& a, const TriangleMesh& b,
                                const DistanceOptions& options) {
  LODBAKE_RETURN_IF_ERROR(validate(a, "first mesh"));
  LODBAKE_RETURN_IF_ERROR(validate(b, "second mesh"));
  if (options.area_samples > kMaxAreaSamples) {
    return invalid_input("area_samples " + std::to_string(options.area_samples) +
                         " exceeds the limit of " + std::to_string(kMaxAreaSamples));
  }
  const unsigned threads = options.threads;

  std::vector<uint32_t> a_triangles = tree_triangles(a);
  std::vector<uint32_t> b_triangles = tree_triangles(b);
  if (a_triangles.empty()) return invalid_input("first mesh has no triangle with non-zero area");
  if (b_triangles.empty()) return invalid_input("second mesh has no triangle with non-zero area");

  // One direction after the other: each tree (with its KD-tree) and the
  // samples queried against it are freed before the other's are made, so
  // the input's tree never coexists with the input's samples. Queries on a
  // built tree are read-only, so the workers share it.
  SurfaceDistance out;
  auto direction = [threads](const TriangleMesh& from, const TriangleMesh& to,
                             std::vector<uint32_t>* to_triangles, uint64_t budget,
                             OneSidedDistance* result) -> Status {
    const double spacing = typical_spacing(to, *to_triangles);
    const Target target(to, to_triangles);
    const Samples samples = make_samples(from, budget);
    LODBAKE_ASSIGN_OR_RETURN(*result, one_sided(samples, target, spacing, threads));
    return Status::ok();
  };
  LODBAKE_RETURN_IF_ERROR(direction(a, b, &b_triangles, options.area_samples, &out.a_to_b));
  LODBAKE_RETURN_IF_ERROR(direction(b, a, &a_triangles, options.area_samples, &out.b_to_a));
  out.hausdorff = std::max(out.a_to_b.max, out.b_to_a.max);
  out.mean = 0.5 * (out.a_to_b.mean + out.b_to_a.mean);
  out.diagonal = diagonal_of(a);
  if (out.diagonal > 0) {
    out.hausdorff_relative = out.hausdorff / out.diagonal;
    out.mean_relative = out.mean / out.diagonal;
  }
  return out;
}

}  // namespace

Result<SurfaceDistance> measure_surface_distance(const TriangleMesh& a, const TriangleMesh& b,
                                                 const DistanceOptions& options) {
  try {
    return measure(a, b, options);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while measuring the surface distance");
  } catch (const std::exception& e) {
    return runtime_error(std::string("measuring the surface distance failed: ") + e.what());
  }
}

}  // namespace lodbake
