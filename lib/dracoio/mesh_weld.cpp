// Exact-position welding for glTF import. glTF has one index stream, so a
// vertex on a normal or texture seam is stored once per side; the topology
// algorithms need one vertex per position, so equal positions are merged and
// attributes that then disagree become per-corner values. Exact equality only:
// a tolerance would also merge distinct vertices of fine meshes.
#include "lib/dracoio/mesh_weld.h"

#include <cstring>
#include <unordered_map>
#include <utility>

namespace lodbake {
namespace dracoio {
namespace {

struct PositionKey {
  uint32_t bits[3];
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = 1469598103934665603ull;
    for (uint32_t b : k.bits)
      h = (h ^ b) * 1099511628211ull;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

PositionKey key_of(const Vec3f& p) {
  PositionKey key;
  for (int i = 0; i < 3; ++i) {
    // -0 and +0 compare equal as floats, so they weld too.
    const float value = p[i] == 0.0f ? 0.0f : p[i];
    std::memcpy(&key.bits[i], &value, sizeof(float));
  }
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

}  // namespace

TriangleMesh weld_exact_positions(RawMesh raw, uint64_t* welded) {
  TriangleMesh mesh;
  std::vector<uint32_t> remap(raw.positions.size());
  std::vector<uint32_t> first_raw;  // welded vertex -> its first raw vertex
  {
    // Lookup only: the output order comes from the raw order, never from the map.
    std::unordered_map<PositionKey, uint32_t, PositionKeyHash> index;
    index.reserve(raw.positions.size());
    for (size_t i = 0; i < raw.positions.size(); ++i) {
      const auto inserted =
          index.emplace(key_of(raw.positions[i]), static_cast<uint32_t>(first_raw.size()));
      if (inserted.second) {
        first_raw.push_back(static_cast<uint32_t>(i));
        mesh.positions.push_back(raw.positions[i]);
      }
      remap[i] = inserted.first->second;
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

}  // namespace dracoio
}  // namespace lodbake
