// Index-level steps of the repair: building the cleaned soup, choosing the
// orientation of each piece after CGAL oriented it, and writing the soup back
// as a mesh with its attributes.
//
// Why these are not CGAL's repair_polygon_soup(): in CGAL 5.5 it always
// starts with merge_duplicate_points_in_polygon_soup(), which welds every pair
// of vertices at the same position (closing cracks the user may want, and
// welding vertices that are split on purpose at UV or normal seams); for
// std::array triangles it skips the removal of repeated-index triangles; and
// its duplicate-polygon and isolated-point removals move survivors around by
// swapping without saying where each went, so attributes could not follow.
// The steps here do the same removals with the semantics check_mesh() uses
// (exact zero area, duplicates in either winding, first copy kept) and keep
// the input order.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "lib/check/disjoint_sets.h"
#include "lib/check/exact_predicates.h"
#include "lib/repair/repair_soup.h"

namespace lodbake {
namespace {

constexpr size_t kMaxVertices = 0xFFFFFFFFu;

Status check_attribute(const MeshAttribute& attribute, const char* name, const TriangleMesh& mesh) {
  if (!attribute.present()) return Status::ok();
  if (attribute.components == 0 || attribute.values.size() % attribute.components != 0) {
    return invalid_input(std::string(name) + ": " + std::to_string(attribute.values.size()) +
                         " values do not make whole " + std::to_string(attribute.components) +
                         "-component entries");
  }
  const size_t count = attribute.value_count();
  if (attribute.binding == AttributeBinding::kPerVertex) {
    if (count != mesh.positions.size()) {
      return invalid_input(std::string(name) + ": " + std::to_string(count) +
                           " per-vertex values for " + std::to_string(mesh.positions.size()) +
                           " vertices");
    }
    return Status::ok();
  }
  if (attribute.corners.size() != mesh.triangles.size()) {
    return invalid_input(std::string(name) + ": " + std::to_string(attribute.corners.size()) +
                         " corner triples for " + std::to_string(mesh.triangles.size()) +
                         " triangles");
  }
  for (size_t t = 0; t < attribute.corners.size(); ++t) {
    for (uint32_t index : attribute.corners[t]) {
      if (index >= count) {
        return invalid_input(std::string(name) + ": triangle " + std::to_string(t) +
                             " uses value " + std::to_string(index) + " of " +
                             std::to_string(count));
      }
    }
  }
  return Status::ok();
}

double signed_volume_term(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  const double ax = a[0], ay = a[1], az = a[2];
  const double bx = b[0], by = b[1], bz = b[2];
  const double cx = c[0], cy = c[1], cz = c[2];
  return ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
}

// A triangle side as (smaller point, larger point, triangle); sorting brings
// the faces of one edge together.
struct Side {
  size_t lo;
  size_t hi;
  size_t triangle;
  bool operator<(const Side& o) const {
    if (lo != o.lo) return lo < o.lo;
    if (hi != o.hi) return hi < o.hi;
    return triangle < o.triangle;
  }
};

std::vector<Side> sorted_sides(const RepairSoup& soup) {
  std::vector<Side> sides;
  sides.reserve(3 * soup.triangles.size());
  for (size_t t = 0; t < soup.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      size_t a = soup.triangles[t][k];
      size_t b = soup.triangles[t][(k + 1) % 3];
      sides.push_back({std::min(a, b), std::max(a, b), t});
    }
  }
  std::sort(sides.begin(), sides.end());
  return sides;
}

void copy_attribute_values(const MeshAttribute& in, const std::vector<uint32_t>& origins,
                           MeshAttribute* out) {
  out->values.clear();
  out->values.reserve(origins.size() * in.components);
  for (uint32_t origin : origins) {
    const float* value = in.values.data() + size_t{origin} * in.components;
    out->values.insert(out->values.end(), value, value + in.components);
  }
}

}  // namespace

void RepairSoup::reverse(size_t t) {
  std::reverse(triangles[t].begin(), triangles[t].end());
  std::reverse(sources[t].corner.begin(), sources[t].corner.end());
}

Result<RepairSoup> build_clean_soup(const TriangleMesh& mesh, SoupRemovals* removals) {
  const size_t n = mesh.positions.size();
  if (n > kMaxVertices) {
    return invalid_input(std::to_string(n) + " vertices, more than 32-bit indices can address");
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (uint32_t v : mesh.triangles[t]) {
      if (v >= n) {
        return invalid_input("triangle " + std::to_string(t) + ": vertex index " +
                             std::to_string(v) + " out of range (" + std::to_string(n) +
                             " vertices)");
      }
    }
  }
  LODBAKE_RETURN_IF_ERROR(check_attribute(mesh.normals, "normals", mesh));
  LODBAKE_RETURN_IF_ERROR(check_attribute(mesh.texcoords, "texture coordinates", mesh));

  std::vector<uint8_t> finite(n);
  for (size_t v = 0; v < n; ++v) {
    const Vec3f& p = mesh.positions[v];
    finite[v] = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  }
  std::vector<uint64_t> kept;
  kept.reserve(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    if (!finite[tri[0]] || !finite[tri[1]] || !finite[tri[2]]) {
      ++removals->non_finite;
    } else if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] ||
               is_zero_area_triangle(mesh.positions[tri[0]], mesh.positions[tri[1]],
                                     mesh.positions[tri[2]])) {
      ++removals->degenerate;
    } else {
      kept.push_back(t);
    }
  }

  // Later copies of a vertex set go; sorting (set, index) puts the first
  // copy at the front of each run.
  struct Keyed {
    Triangle set;
    uint64_t triangle;
    bool operator<(const Keyed& o) const {
      return set != o.set ? set < o.set : triangle < o.triangle;
    }
  };
  std::vector<Keyed> keyed;
  keyed.reserve(kept.size());
  for (uint64_t t : kept) {
    Triangle set = mesh.triangles[t];
    std::sort(set.begin(), set.end());
    keyed.push_back({set, t});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint8_t> duplicate(mesh.triangles.size(), 0);
  for (size_t i = 1; i < keyed.size(); ++i) {
    if (keyed[i].set == keyed[i - 1].set) {
      duplicate[keyed[i].triangle] = 1;
      ++removals->duplicate;
    }
  }

  RepairSoup soup;
  soup.points = mesh.positions;
  soup.point_origin.resize(n);
  std::iota(soup.point_origin.begin(), soup.point_origin.end(), uint32_t{0});
  soup.triangles.reserve(kept.size() - removals->duplicate);
  soup.sources.reserve(kept.size() - removals->duplicate);
  for (uint64_t t : kept) {
    if (duplicate[t]) continue;
    const Triangle& tri = mesh.triangles[t];
    soup.triangles.push_back({tri[0], tri[1], tri[2]});
    soup.sources.push_back(CornerSource{t, {0, 1, 2}});
  }
  return soup;
}

uint64_t count_non_manifold_edges(const RepairSoup& soup) {
  std::vector<Side> sides = sorted_sides(soup);
  uint64_t count = 0;
  for (size_t i = 0; i < sides.size();) {
    size_t j = i + 1;
    while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi)
      ++j;
    if (j - i > 2) ++count;
    i = j;
  }
  return count;
}

void choose_piece_orientation(RepairSoup* soup) {
  const size_t m = soup->triangles.size();
  std::vector<Side> sides = sorted_sides(*soup);
  DisjointSets pieces(m);
  std::vector<uint8_t> has_boundary(m, 0);
  for (size_t i = 0; i < sides.size();) {
    size_t j = i + 1;
    while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi)
      ++j;
    if (j - i == 1) has_boundary[sides[i].triangle] = 1;
    for (size_t k = i + 1; k < j; ++k)
      pieces.unite(sides[i].triangle, sides[k].triangle);
    i = j;
  }

  struct Piece {
    size_t first = 0;  // the piece's first triangle
    uint64_t size = 0;
    uint64_t reversed = 0;
    bool closed = true;
    double volume = 0;
  };
  std::vector<Piece> stats(m);
  for (size_t t = 0; t < m; ++t) {
    Piece& piece = stats[pieces.find(t)];
    if (piece.size == 0) piece.first = t;
    ++piece.size;
    if (soup->reversed(t)) ++piece.reversed;
    if (has_boundary[t]) piece.closed = false;
    const auto& tri = soup->triangles[t];
    piece.volume +=
        signed_volume_term(soup->points[tri[0]], soup->points[tri[1]], soup->points[tri[2]]);
  }
  std::vector<uint8_t> flip(m, 0);
  for (size_t root = 0; root < m; ++root) {
    const Piece& piece = stats[root];
    if (piece.reversed == 0) continue;  // untouched pieces keep the user's winding
    if (piece.closed && piece.volume != 0) {
      flip[root] = piece.volume < 0;
    } else if (2 * piece.reversed != piece.size) {
      flip[root] = 2 * piece.reversed > piece.size;
    } else {
      flip[root] = soup->reversed(piece.first);
    }
  }
  for (size_t t = 0; t < m; ++t) {
    if (flip[pieces.find(t)]) soup->reverse(t);
  }
}

Result<uint64_t> soup_to_mesh(RepairSoup* soup, const TriangleMesh& input, TriangleMesh* out) {
  const size_t point_count = soup->points.size();
  std::vector<uint32_t> new_index(point_count, 0);
  std::vector<uint8_t> used(point_count, 0);
  for (const auto& tri : soup->triangles) {
    for (size_t p : tri)
      used[p] = 1;
  }
  const size_t used_count = static_cast<size_t>(std::count(used.begin(), used.end(), 1));
  if (used_count > kMaxVertices) {
    return runtime_error("splitting non-manifold vertices needs " + std::to_string(used_count) +
                         " vertices, more than 32-bit indices can address");
  }
  std::vector<uint32_t> origins;
  out->positions.clear();
  for (size_t p = 0; p < point_count; ++p) {
    if (!used[p]) continue;
    new_index[p] = static_cast<uint32_t>(out->positions.size());
    out->positions.push_back(soup->points[p]);
    origins.push_back(soup->point_origin[p]);
  }
  out->triangles.resize(soup->triangles.size());
  for (size_t t = 0; t < soup->triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k)
      out->triangles[t][k] = new_index[soup->triangles[t][k]];
  }

  const MeshAttribute* in_attributes[2] = {&input.normals, &input.texcoords};
  MeshAttribute* out_attributes[2] = {&out->normals, &out->texcoords};
  for (int a = 0; a < 2; ++a) {
    const MeshAttribute& in = *in_attributes[a];
    MeshAttribute& attribute = *out_attributes[a];
    attribute = MeshAttribute();
    if (!in.present()) continue;
    attribute.binding = in.binding;
    attribute.components = in.components;
    if (in.binding == AttributeBinding::kPerVertex) {
      copy_attribute_values(in, origins, &attribute);
      continue;
    }
    // Per-corner values stay as they are; only the corner triples follow.
    attribute.values = in.values;
    attribute.corners.resize(soup->triangles.size());
    for (size_t t = 0; t < soup->triangles.size(); ++t) {
      const CornerSource& source = soup->sources[t];
      for (int k = 0; k < 3; ++k) {
        attribute.corners[t][k] = in.corners[source.triangle][source.corner[k]];
      }
    }
  }
  return uint64_t{point_count - out->positions.size()};
}

}  // namespace lodbake
