// weld_mesh_points(): shared points across a mesh's primitives by exact
// POSITION bytes. Bit equality, not a tolerance: the model must not merge
// what the file distinguishes, and -0.0 versus 0.0 or two NaN payloads are
// then distinct points, which is what a byte-level comparison of the
// streams would say too.
#include <array>
#include <cstring>
#include <unordered_map>

#include "lib/scene/scene_points.h"

namespace lodbake {
namespace {

// A POSITION element: up to 4 components of up to 4 bytes (VEC3 normally),
// with its type so that a float and an int16 stream never collide.
struct PointKey {
  std::array<uint8_t, 16> bytes{};
  uint16_t component_type = 0;
  bool normalized = false;
  bool operator==(const PointKey& o) const {
    return bytes == o.bytes && component_type == o.component_type && normalized == o.normalized;
  }
};

struct PointKeyHash {
  size_t operator()(const PointKey& k) const {
    // FNV-1a over the key's bytes.
    uint64_t h = 1469598103934665603ull;
    auto mix = [&h](uint8_t b) {
      h ^= b;
      h *= 1099511628211ull;
    };
    for (uint8_t b : k.bytes)
      mix(b);
    mix(static_cast<uint8_t>(k.component_type));
    mix(static_cast<uint8_t>(k.component_type >> 8));
    mix(k.normalized ? 1 : 0);
    return static_cast<size_t>(h);
  }
};

}  // namespace

void weld_mesh_points(SceneMesh* mesh) {
  mesh->point_of_vertex.assign(mesh->primitives.size(), {});
  std::unordered_map<PointKey, uint32_t, PointKeyHash> points;
  uint32_t next = 0;
  for (size_t p = 0; p < mesh->primitives.size(); ++p) {
    const SceneAttribute* position = mesh->primitives[p].find("POSITION");
    if (position == nullptr) continue;
    const AccessorData& data = position->data;
    const uint32_t size = data.element_size();
    if (size > 16 || data.bytes.size() < uint64_t{data.count} * size) continue;
    std::vector<uint32_t>& out = mesh->point_of_vertex[p];
    out.resize(data.count);
    PointKey key;
    key.component_type = static_cast<uint16_t>(data.component_type);
    key.normalized = data.normalized;
    for (uint32_t v = 0; v < data.count; ++v) {
      std::memcpy(key.bytes.data(), data.bytes.data() + size_t{v} * size, size);
      const auto inserted = points.emplace(key, next);
      if (inserted.second) ++next;
      out[v] = inserted.first->second;
    }
  }
  mesh->point_count = next;
}

}  // namespace lodbake
