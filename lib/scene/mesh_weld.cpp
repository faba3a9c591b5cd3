// Welding for glTF import. glTF has one index stream, so a vertex on a
// normal or texture seam is stored once per side; the topology algorithms
// need one vertex per surface point, so equal positions are merged and
// attributes that then disagree become per-corner values. Exact equality
// only: a tolerance would also merge distinct vertices of fine meshes.
//
// Merging every equal position would undo what lodbake's repair does
// (splitting a non-manifold vertex into one vertex per fan, at the same
// position), so lodbake's own GLB files say how to weld them (asset.extras,
// docs/import.md): not at all, or only across manifold edges. The second
// closes every seam of a manifold mesh, because the two sides of a seam
// share an edge that two triangles use in opposite directions, and never
// merges two fans that only touch at a point or meet at an edge of three
// or more triangles.
#include "lib/scene/mesh_weld.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <utility>

#include "lib/scene/exact_key_numbering.h"

namespace lodbake {
namespace {

// A position as an exact key: -0 and +0 compare equal as floats, so they
// weld too; any other value by its bits.
ExactKey key_of(const Vec3f& p) {
  uint32_t bits[3];
  for (int i = 0; i < 3; ++i) {
    const float value = p[i] == 0.0f ? 0.0f : p[i];
    std::memcpy(&bits[i], &value, sizeof(float));
  }
  ExactKey key;
  key.lo = bits[0] | uint64_t{bits[1]} << 32;
  key.hi = bits[2];
  return key;
}

// Moves a raw per-vertex attribute onto the welded vertices, or makes it per
// corner when merged vertices disagree.
MeshAttribute weld_attribute(std::vector<float> raw_values, uint32_t components,
                             const std::vector<uint32_t>& remap,
                             const std::vector<uint32_t>& first_raw,
                             const std::vector<Triangle>& raw_triangles) {
  MeshAttribute attribute;
  if (raw_values.empty()) return attribute;
  attribute.components = components;
  bool consistent = true;
  for (size_t i = 0; i < remap.size() && consistent; ++i) {
    const uint32_t rep = first_raw[remap[i]];
    consistent = std::memcmp(&raw_values[size_t{rep} * components], &raw_values[i * components],
                             components * sizeof(float)) == 0;
  }
  if (consistent) {
    attribute.binding = AttributeBinding::kPerVertex;
    attribute.values.resize(first_raw.size() * components);
    for (size_t w = 0; w < first_raw.size(); ++w) {
      std::memcpy(&attribute.values[w * components], &raw_values[size_t{first_raw[w]} * components],
                  components * sizeof(float));
    }
  } else {
    attribute.binding = AttributeBinding::kPerCorner;
    attribute.values = std::move(raw_values);
    attribute.corners = raw_triangles;
  }
  return attribute;
}

// Raw vertex -> the first raw vertex with a bit-equal position key.
std::vector<uint32_t> first_at_position(const std::vector<Vec3f>& positions) {
  std::vector<uint32_t> first(positions.size());
  std::vector<uint32_t> first_of_point;  // by point number, in first-seen order
  ExactKeyNumbering points(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const uint32_t point = points.number(key_of(positions[i]));
    if (point == first_of_point.size()) first_of_point.push_back(static_cast<uint32_t>(i));
    first[i] = first_of_point[point];
  }
  return first;
}

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

void unite(std::vector<uint32_t>& parent, uint32_t a, uint32_t b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  // The smaller raw index stays the root, so roots are first occurrences.
  if (a < b) {
    parent[b] = a;
  } else if (b < a) {
    parent[a] = b;
  }
}

// Raw vertex -> its representative raw vertex under kManifoldEdges.
std::vector<uint32_t> manifold_edge_classes(const RawMesh& raw) {
  const std::vector<uint32_t> at = first_at_position(raw.positions);
  std::vector<uint32_t> parent(raw.positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<uint8_t> shared(raw.positions.size(), 0);  // position held by 2+ raw vertices
  for (size_t i = 0; i < at.size(); ++i) {
    if (at[i] != i) shared[i] = shared[at[i]] = 1;
  }
  // Triangle edges in positions (by first raw vertex), with the raw vertex
  // at each end; only edges touching a shared position can join anything.
  struct Edge {
    uint32_t low, high;          // positions, low < high
    uint32_t raw_low, raw_high;  // the triangle's raw vertices there
    uint32_t triangle;
    bool forward;  // the triangle goes low -> high
    bool operator<(const Edge& o) const {
      return low != o.low ? low < o.low : high != o.high ? high < o.high : triangle < o.triangle;
    }
  };
  std::vector<Edge> edges;
  std::vector<uint8_t> used(raw.positions.size(), 0);
  for (size_t t = 0; t < raw.triangles.size(); ++t) {
    const Triangle& tri = raw.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = tri[k], b = tri[(k + 1) % 3];
      used[a] = 1;
      const uint32_t pa = at[a], pb = at[b];
      if (pa == pb || (!shared[a] && !shared[b])) continue;
      if (pa < pb) {
        edges.push_back({pa, pb, a, b, static_cast<uint32_t>(t), true});
      } else {
        edges.push_back({pb, pa, b, a, static_cast<uint32_t>(t), false});
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high)
      ++j;
    if (j - i == 2 && edges[i].forward != edges[i + 1].forward) {
      unite(parent, edges[i].raw_low, edges[i + 1].raw_low);
      unite(parent, edges[i].raw_high, edges[i + 1].raw_high);
    }
    i = j;
  }
  // A vertex no triangle uses has no topology to keep: it joins the first
  // vertex at its position.
  for (size_t i = 0; i < at.size(); ++i) {
    if (!used[i]) unite(parent, static_cast<uint32_t>(i), at[i]);
  }
  for (size_t i = 0; i < parent.size(); ++i)
    parent[i] = find_root(parent, static_cast<uint32_t>(i));
  return parent;
}

}  // namespace

TriangleMesh weld_vertices(RawMesh raw, WeldMode mode, uint64_t* welded) {
  // Each raw vertex's representative: a raw vertex whose own representative
  // is itself and whose index is the smallest of its class.
  std::vector<uint32_t> rep;
  switch (mode) {
    case WeldMode::kExactPositions:
      rep = first_at_position(raw.positions);
      break;
    case WeldMode::kManifoldEdges:
      rep = manifold_edge_classes(raw);
      break;
    case WeldMode::kNone:
      rep.resize(raw.positions.size());
      std::iota(rep.begin(), rep.end(), 0u);
      break;
  }
  TriangleMesh mesh;
  std::vector<uint32_t> remap(raw.positions.size());
  std::vector<uint32_t> first_raw;  // welded vertex -> its first raw vertex
  for (size_t i = 0; i < raw.positions.size(); ++i) {
    if (rep[i] == i) {
      remap[i] = static_cast<uint32_t>(first_raw.size());
      first_raw.push_back(static_cast<uint32_t>(i));
      mesh.positions.push_back(raw.positions[i]);
    } else {
      remap[i] = remap[rep[i]];  // rep[i] < i: already numbered
    }
  }
  mesh.triangles.reserve(raw.triangles.size());
  for (const Triangle& t : raw.triangles) {
    mesh.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  }
  mesh.normals = weld_attribute(std::move(raw.normals), 3, remap, first_raw, raw.triangles);
  mesh.texcoords = weld_attribute(std::move(raw.texcoords), 2, remap, first_raw, raw.triangles);
  if (welded != nullptr) *welded = raw.positions.size() - mesh.positions.size();
  return mesh;
}

}  // namespace lodbake
