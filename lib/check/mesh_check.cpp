// Mesh check: exact counts on the index structure of a triangle mesh.
//
// Definitions (chosen to reproduce ../shared/data/meshes/MANIFEST.md):
// - Topology triangles: all three indices in range and pairwise distinct.
//   Triangles with an out-of-range or repeated index are counted as problems
//   but left out of every topology count (edges, boundary, manifoldness,
//   components, genus), as MANIFEST does. Zero-area and duplicate triangles
//   are topology triangles.
// - Referenced vertex: used by a triangle whose indices are all in range
//   (a triangle with a repeated index still references its vertices).
// - Edge: unordered pair of vertices joined by a topology triangle side. An
//   edge with one face is a boundary edge, with more than two a non-manifold
//   edge; an edge with exactly two faces that both walk it in the same
//   direction is an inconsistent-orientation edge.
// - Boundary loops: connected components of the graph formed by the boundary
//   edges. Where boundaries touch at a non-manifold vertex they count as one
//   loop (a half-edge structure could count two; the graph definition needs
//   no choice of how to pair boundary edges at such a vertex).
// - Non-manifold vertex: group the topology triangles around vertex v, two of
//   them joined when they share an edge v-w (any number of faces on it);
//   v is non-manifold when there is more than one group, i.e. the triangles
//   around it form several fans that only meet at v (bow-tie, two cones on
//   one apex). Non-manifold edges are reported separately, so a vertex whose
//   faces are held together only through a non-manifold edge is not also
//   counted here.
// - Component: topology triangles connected through shared vertices.
// - Zero area: the three corners are exactly collinear (exact predicate on
//   the float coordinates, see exact_predicates.cpp); tested only for
//   topology triangles whose corners are finite.
// - Duplicate: a topology triangle with the same vertex set as an earlier
//   one, either winding.
// - Genus: from V - E + F = 2 - 2g over the topology triangles and the
//   vertices they use, only when closed, free of non-manifold edges and
//   vertices, consistently oriented and one component.
//
// Everything is sort- and array-based (counting-sort buckets per vertex, then
// small per-bucket sorts, no maps), so the cost is linear up to the
// per-vertex sorts; the 871k-triangle dragon takes about 0.2 s.
#include "lib/check/mesh_check.h"

#include <algorithm>
#include <cmath>

#include "lib/check/disjoint_sets.h"
#include "lib/check/exact_predicates.h"

namespace lodbake {
namespace {

constexpr size_t kMaxSamples = MeshCheckSamples::kMaxSamples;

// Records `value` if fewer than kMaxSamples were recorded; callers offer
// values in increasing order, so the samples are the smallest ones.
template <typename T>
void add_sample(std::vector<T>* samples, const T& value) {
  if (samples->size() < kMaxSamples) samples->push_back(value);
}

// Bucket offsets for a counting sort: offsets[k]..offsets[k+1] is bucket k.
std::vector<uint64_t> prefix_offsets(const std::vector<uint64_t>& counts) {
  std::vector<uint64_t> offsets(counts.size() + 1, 0);
  for (size_t i = 0; i < counts.size(); ++i)
    offsets[i + 1] = offsets[i] + counts[i];
  return offsets;
}

enum class TriangleKind : uint8_t { kTopology, kOutOfRange, kRepeatedIndex };

struct Classified {
  std::vector<TriangleKind> kinds;
  std::vector<uint8_t> referenced;  // per vertex
  uint64_t topology_triangles = 0;
};

Classified classify_triangles(const TriangleMesh& mesh, MeshCheckReport* r) {
  const size_t n = mesh.positions.size();
  Classified c;
  c.kinds.resize(mesh.triangles.size());
  c.referenced.assign(n, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
      c.kinds[t] = TriangleKind::kOutOfRange;
      ++r->out_of_range_triangles;
      add_sample(&r->samples.out_of_range_triangles, uint64_t{t});
      continue;
    }
    for (uint32_t v : tri)
      c.referenced[v] = 1;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      c.kinds[t] = TriangleKind::kRepeatedIndex;
      ++r->repeated_index_triangles;
      add_sample(&r->samples.repeated_index_triangles, uint64_t{t});
      continue;
    }
    c.kinds[t] = TriangleKind::kTopology;
    ++c.topology_triangles;
  }
  return c;
}

void check_vertices(const TriangleMesh& mesh, const Classified& c, MeshCheckReport* r,
                    std::vector<uint8_t>* finite) {
  const size_t n = mesh.positions.size();
  finite->assign(n, 1);
  bool have_box = false;
  for (size_t v = 0; v < n; ++v) {
    const Vec3f& p = mesh.positions[v];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      (*finite)[v] = 0;
      ++r->non_finite_coordinates;
      add_sample(&r->samples.non_finite_vertices, uint64_t{v});
    }
    if (!c.referenced[v]) {
      ++r->unreferenced_vertices;
      add_sample(&r->samples.unreferenced_vertices, uint64_t{v});
      continue;
    }
    if (!(*finite)[v]) continue;
    for (int k = 0; k < 3; ++k) {
      r->bbox_min[k] = have_box ? std::min(r->bbox_min[k], p[k]) : p[k];
      r->bbox_max[k] = have_box ? std::max(r->bbox_max[k], p[k]) : p[k];
    }
    have_box = true;
  }
}

void check_zero_area(const TriangleMesh& mesh, const Classified& c,
                     const std::vector<uint8_t>& finite, MeshCheckReport* r) {
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (c.kinds[t] != TriangleKind::kTopology) continue;
    const Triangle& tri = mesh.triangles[t];
    if (!finite[tri[0]] || !finite[tri[1]] || !finite[tri[2]]) continue;
    if (is_zero_area_triangle(mesh.positions[tri[0]], mesh.positions[tri[1]],
                              mesh.positions[tri[2]])) {
      ++r->zero_area_triangles;
      add_sample(&r->samples.zero_area_triangles, uint64_t{t});
    }
  }
}

// Edges, bucketed by their smaller vertex. Each entry is (larger << 1 | d),
// d = 1 when the triangle walks the edge from the larger to the smaller
// vertex, so one sort per bucket groups the faces of each edge.
void check_edges(const TriangleMesh& mesh, const Classified& c, MeshCheckReport* r) {
  const size_t n = mesh.positions.size();
  std::vector<uint64_t> counts(n, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (c.kinds[t] != TriangleKind::kTopology) continue;
    const Triangle& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
      ++counts[std::min(tri[k], tri[(k + 1) % 3])];
  }
  std::vector<uint64_t> offsets = prefix_offsets(counts);
  std::vector<uint64_t> entries(offsets[n]);
  std::vector<uint64_t> fill(offsets.begin(), offsets.end() - 1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (c.kinds[t] != TriangleKind::kTopology) continue;
    const Triangle& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      uint32_t from = tri[k];
      uint32_t to = tri[(k + 1) % 3];
      uint32_t lo = std::min(from, to);
      uint64_t hi = std::max(from, to);
      entries[fill[lo]++] = (hi << 1) | (from > to ? 1u : 0u);
    }
  }

  DisjointSets boundary_sets(n);
  std::vector<uint8_t> on_boundary(n, 0);
  for (size_t lo = 0; lo < n; ++lo) {
    auto begin = entries.begin() + static_cast<std::ptrdiff_t>(offsets[lo]);
    auto end = entries.begin() + static_cast<std::ptrdiff_t>(offsets[lo + 1]);
    std::sort(begin, end);
    for (auto it = begin; it != end;) {
      uint64_t hi = *it >> 1;
      uint64_t faces = 0;
      uint64_t reversed = 0;
      for (; it != end && (*it >> 1) == hi; ++it) {
        ++faces;
        reversed += *it & 1;
      }
      ++r->edges;
      VertexPair edge{static_cast<uint32_t>(lo), static_cast<uint32_t>(hi)};
      if (faces == 1) {
        ++r->boundary_edges;
        boundary_sets.unite(edge[0], edge[1]);
        on_boundary[edge[0]] = on_boundary[edge[1]] = 1;
      } else if (faces > 2) {
        ++r->non_manifold_edges;
        add_sample(&r->samples.non_manifold_edges, edge);
      } else if (reversed != 1) {
        ++r->inconsistent_orientation_edges;
        add_sample(&r->samples.inconsistent_orientation_edges, edge);
      }
    }
  }
  for (size_t v = 0; v < n; ++v) {
    if (on_boundary[v] && boundary_sets.find(v) == v) ++r->boundary_loops;
  }
}

// For every vertex, the triangles around it grouped through the edges at the
// vertex (see the definition above). Also counts the vertices that topology
// triangles use (for the Euler characteristic).
uint64_t check_vertex_fans(const TriangleMesh& mesh, const Classified& c, MeshCheckReport* r) {
  const size_t n = mesh.positions.size();
  std::vector<uint64_t> counts(n, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (c.kinds[t] != TriangleKind::kTopology) continue;
    for (uint32_t v : mesh.triangles[t])
      ++counts[v];
  }
  std::vector<uint64_t> offsets = prefix_offsets(counts);
  // The two other corners of each triangle around the vertex.
  std::vector<VertexPair> others(offsets[n]);
  std::vector<uint64_t> fill(offsets.begin(), offsets.end() - 1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (c.kinds[t] != TriangleKind::kTopology) continue;
    const Triangle& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
      others[fill[tri[k]]++] = {tri[(k + 1) % 3], tri[(k + 2) % 3]};
  }

  uint64_t used_vertices = 0;
  struct Side {  // the other end of an edge at v, and which triangle of the fan has it
    uint32_t other;
    uint64_t triangle;
    bool operator<(const Side& o) const {
      return other != o.other ? other < o.other : triangle < o.triangle;
    }
  };
  std::vector<Side> local;
  DisjointSets groups(0);
  for (size_t v = 0; v < n; ++v) {
    const uint64_t begin = offsets[v];
    const uint64_t degree = offsets[v + 1] - begin;
    if (degree == 0) continue;
    ++used_vertices;
    if (degree == 1) continue;
    local.clear();
    for (uint64_t j = 0; j < degree; ++j) {
      for (uint32_t w : others[begin + j])
        local.push_back({w, j});
    }
    std::sort(local.begin(), local.end());
    groups.reset(degree);
    uint64_t group_count = degree;
    for (size_t i = 1; i < local.size(); ++i) {
      if (local[i].other == local[i - 1].other &&
          groups.unite(local[i - 1].triangle, local[i].triangle)) {
        --group_count;
      }
    }
    if (group_count > 1) {
      ++r->non_manifold_vertices;
      add_sample(&r->samples.non_manifold_vertices, uint64_t{v});
    }
  }
  return used_vertices;
}

uint64_t count_components(const TriangleMesh& mesh, const Classified& c) {
  const size_t n = mesh.positions.size();
  DisjointSets sets(n);
  std::vector<uint8_t> used(n, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (c.kinds[t] != TriangleKind::kTopology) continue;
    const Triangle& tri = mesh.triangles[t];
    sets.unite(tri[0], tri[1]);
    sets.unite(tri[0], tri[2]);
    used[tri[0]] = used[tri[1]] = used[tri[2]] = 1;
  }
  uint64_t components = 0;
  for (size_t v = 0; v < n; ++v) {
    if (used[v] && sets.find(v) == v) ++components;
  }
  return components;
}

// Duplicates, bucketed by the smallest vertex of each triangle.
void check_duplicates(const TriangleMesh& mesh, const Classified& c, MeshCheckReport* r) {
  struct Entry {
    uint32_t mid;
    uint32_t high;
    uint64_t triangle;
    bool operator<(const Entry& o) const {
      if (mid != o.mid) return mid < o.mid;
      if (high != o.high) return high < o.high;
      return triangle < o.triangle;
    }
  };
  const size_t n = mesh.positions.size();
  auto sorted = [](Triangle tri) {
    std::sort(tri.begin(), tri.end());
    return tri;
  };
  std::vector<uint64_t> counts(n, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (c.kinds[t] == TriangleKind::kTopology) ++counts[sorted(mesh.triangles[t])[0]];
  }
  std::vector<uint64_t> offsets = prefix_offsets(counts);
  std::vector<Entry> entries(offsets[n]);
  std::vector<uint64_t> fill(offsets.begin(), offsets.end() - 1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (c.kinds[t] != TriangleKind::kTopology) continue;
    Triangle s = sorted(mesh.triangles[t]);
    entries[fill[s[0]]++] = {s[1], s[2], t};
  }
  std::vector<uint64_t> later_copies;
  for (size_t v = 0; v < n; ++v) {
    auto begin = entries.begin() + static_cast<std::ptrdiff_t>(offsets[v]);
    auto end = entries.begin() + static_cast<std::ptrdiff_t>(offsets[v + 1]);
    std::sort(begin, end);
    for (auto it = begin; it != end && it + 1 != end; ++it) {
      if (it[1].mid == it[0].mid && it[1].high == it[0].high) {
        ++r->duplicate_triangles;
        later_copies.push_back(it[1].triangle);
      }
    }
  }
  std::sort(later_copies.begin(), later_copies.end());
  for (uint64_t t : later_copies)
    add_sample(&r->samples.duplicate_triangles, t);
}

}  // namespace

MeshCheckReport check_mesh(const TriangleMesh& mesh, const PartRunner& run_parts) {
  MeshCheckReport r;
  r.vertices = mesh.positions.size();
  r.triangles = mesh.triangles.size();
  Classified c = classify_triangles(mesh, &r);
  std::vector<uint8_t> finite;
  check_vertices(mesh, c, &r, &finite);
  // The checks below read the mesh and write report fields of their own.
  // The edges run beside the zero areas and components, which need little
  // memory; the fans and duplicates follow one at a time, since each of the
  // three heavy ones holds an entry per corner (side by side they raised a
  // 3.5M-triangle import's peak by a third).
  uint64_t used_vertices = 0;
  const std::function<void(size_t)> check_part = [&](size_t part) {
    switch (part) {
      case 0:
        check_edges(mesh, c, &r);
        break;
      case 1:
        check_zero_area(mesh, c, finite, &r);
        break;
      default:
        r.components = count_components(mesh, c);
        break;
    }
  };
  if (run_parts) {
    run_parts(3, check_part);
  } else {
    for (size_t part = 0; part < 3; ++part)
      check_part(part);
  }
  used_vertices = check_vertex_fans(mesh, c, &r);
  check_duplicates(mesh, c, &r);
  r.degenerate_triangles = r.repeated_index_triangles + r.zero_area_triangles;

  if (r.components == 1 && r.closed() && r.manifold() && r.inconsistent_orientation_edges == 0) {
    int64_t euler = static_cast<int64_t>(used_vertices) - static_cast<int64_t>(r.edges) +
                    static_cast<int64_t>(c.topology_triangles);
    if (euler <= 2 && (2 - euler) % 2 == 0) r.genus = (2 - euler) / 2;
  }
  return r;
}

MeshCheckReport check_triangulation(const TriangleMesh& mesh) {
  MeshCheckReport r;
  r.vertices = mesh.positions.size();
  r.triangles = mesh.triangles.size();
  Classified c = classify_triangles(mesh, &r);
  r.degenerate_triangles = r.repeated_index_triangles;
  check_edges(mesh, c, &r);
  check_duplicates(mesh, c, &r);
  return r;
}

}  // namespace lodbake
