// Splitting vertices so that per-corner attributes become per-vertex; the
// numbering rule is documented in corner_split.h.
#include "lib/meshio/corner_split.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace lodbake {
namespace {

constexpr uint32_t kUnset = std::numeric_limits<uint32_t>::max();

// A vertex's attribute combination: indices into the normal and texture
// coordinate values (kUnset when that attribute is absent).
struct Key {
  uint32_t normal = kUnset;
  uint32_t texcoord = kUnset;
  bool operator==(const Key& o) const { return normal == o.normal && texcoord == o.texcoord; }
};

uint32_t value_of(const MeshAttribute& a, const Triangle& vertices, size_t t, int k) {
  if (a.binding == AttributeBinding::kPerCorner) return a.corners[t][k];
  if (a.binding == AttributeBinding::kPerVertex) return vertices[k];
  return kUnset;
}

void copy_value(const MeshAttribute& from, uint32_t index, std::vector<float>* to) {
  const uint32_t c = from.components;
  if (index == kUnset) {
    to->insert(to->end(), c, 0.0f);
  } else {
    to->insert(to->end(), from.values.begin() + static_cast<size_t>(index) * c,
               from.values.begin() + static_cast<size_t>(index + 1) * c);
  }
}

}  // namespace

TriangleMesh split_corner_attributes(const TriangleMesh& mesh) {
  std::vector<uint32_t> source;
  return split_corner_attributes(mesh, &source);
}

TriangleMesh split_corner_attributes(const TriangleMesh& mesh,
                                     std::vector<uint32_t>* source_vertex) {
  if (mesh.normals.binding != AttributeBinding::kPerCorner &&
      mesh.texcoords.binding != AttributeBinding::kPerCorner) {
    source_vertex->resize(mesh.positions.size());
    for (size_t i = 0; i < source_vertex->size(); ++i)
      (*source_vertex)[i] = static_cast<uint32_t>(i);
    return mesh;
  }
  const size_t v = mesh.positions.size();
  // keys[i] for i < v: the combination owning vertex i; for i >= v: the
  // duplicates, chained per source vertex through next_variant.
  std::vector<Key> keys(v);
  std::vector<bool> used(v, false);
  std::vector<uint32_t>& source = *source_vertex;
  source.resize(v);
  std::vector<uint32_t> next_variant(v, kUnset);
  for (size_t i = 0; i < v; ++i)
    source[i] = static_cast<uint32_t>(i);

  TriangleMesh out;
  out.triangles.resize(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const uint32_t vertex = tri[k];
      const Key key{value_of(mesh.normals, tri, t, k), value_of(mesh.texcoords, tri, t, k)};
      if (!used[vertex]) {
        used[vertex] = true;
        keys[vertex] = key;
        out.triangles[t][k] = vertex;
        continue;
      }
      uint32_t at = vertex;
      uint32_t last = vertex;
      while (at != kUnset && !(keys[at] == key)) {
        last = at;
        at = next_variant[at];
      }
      if (at == kUnset) {
        at = static_cast<uint32_t>(keys.size());
        keys.push_back(key);
        source.push_back(vertex);
        next_variant.push_back(kUnset);
        next_variant[last] = at;
      }
      out.triangles[t][k] = at;
    }
  }

  out.positions.reserve(keys.size());
  for (uint32_t s : source)
    out.positions.push_back(mesh.positions[s]);
  auto build = [&](const MeshAttribute& from, bool normal, MeshAttribute* to) {
    if (!from.present()) return;
    to->binding = AttributeBinding::kPerVertex;
    to->components = from.components;
    to->values.reserve(keys.size() * from.components);
    for (size_t i = 0; i < keys.size(); ++i) {
      uint32_t index = normal ? keys[i].normal : keys[i].texcoord;
      // Unused vertices of a per-vertex attribute keep their own value.
      if (i < v && !used[i] && from.binding == AttributeBinding::kPerVertex)
        index = static_cast<uint32_t>(i);
      copy_value(from, index, &to->values);
    }
  };
  build(mesh.normals, true, &out.normals);
  build(mesh.texcoords, false, &out.texcoords);
  return out;
}

}  // namespace lodbake
