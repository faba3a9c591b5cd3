// weld_mesh_points(): shared points across a mesh's primitives by exact
// POSITION bytes. Bit equality, not a tolerance: the model must not merge
// what the file distinguishes, and -0.0 versus 0.0 or two NaN payloads are
// then distinct points, which is what a byte-level comparison of the
// streams would say too.
//
// Every import pays for this (it was two thirds of SheenCloth's read with
// a node-based std::unordered_map and a byte-wise hash), so the table is
// open-addressed, sized once for all vertices, and holds only 32-bit point
// numbers (a small table stays in cache; the keys, the element zero-padded
// to 16 bytes with its component type and normalization, sit in a second
// array by point number). Points are numbered in first-seen order, so the
// result does not depend on the hash.
#include <cstring>
#include <vector>

#include "lib/scene/scene_points.h"

namespace lodbake {
namespace {

struct Key {
  uint64_t lo = 0, hi = 0;  // the element's bytes, zero-padded to 16
  uint32_t tag = 0;         // component type, normalized in bit 16
  bool operator==(const Key& o) const { return lo == o.lo && hi == o.hi && tag == o.tag; }
};

constexpr uint32_t kEmpty = UINT32_MAX;

uint64_t mix(uint64_t h) {
  // MurmurHash3's 64-bit finalizer.
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ull;
  h ^= h >> 33;
  return h;
}

}  // namespace

void weld_mesh_points(SceneMesh* mesh) {
  mesh->point_of_vertex.assign(mesh->primitives.size(), {});
  std::vector<const AccessorData*> streams(mesh->primitives.size(), nullptr);
  uint64_t total = 0;
  for (size_t p = 0; p < mesh->primitives.size(); ++p) {
    const SceneAttribute* position = mesh->primitives[p].find("POSITION");
    if (position == nullptr) continue;
    const AccessorData& data = position->data;
    const uint32_t size = data.element_size();
    if (size > 16 || data.bytes.size() < uint64_t{data.count} * size) continue;
    streams[p] = &data;
    total += data.count;
  }
  size_t capacity = 16;
  while (capacity < 2 * total)
    capacity *= 2;
  // Point numbers by hash; the keys themselves by point number, in the
  // order they are first seen (written sequentially, read only on a match).
  std::vector<uint32_t> table(capacity, kEmpty);
  std::vector<Key> keys;
  keys.reserve(static_cast<size_t>(total));
  const size_t mask = capacity - 1;
  for (size_t p = 0; p < streams.size(); ++p) {
    const AccessorData* data = streams[p];
    if (data == nullptr) continue;
    const uint32_t size = data->element_size();
    Key key;
    key.tag = static_cast<uint32_t>(data->component_type) | (data->normalized ? 1u << 16 : 0u);
    std::vector<uint32_t>& out = mesh->point_of_vertex[p];
    out.resize(data->count);
    for (uint32_t v = 0; v < data->count; ++v) {
      uint8_t element[16] = {};
      std::memcpy(element, data->bytes.data() + size_t{v} * size, size);
      std::memcpy(&key.lo, element, 8);
      std::memcpy(&key.hi, element + 8, 8);
      size_t i = mix(key.lo ^ mix(key.hi ^ (uint64_t{key.tag} << 32))) & mask;
      while (table[i] != kEmpty && !(keys[table[i]] == key))
        i = (i + 1) & mask;
      if (table[i] == kEmpty) {
        table[i] = static_cast<uint32_t>(keys.size());
        keys.push_back(key);
      }
      out[v] = table[i];
    }
  }
  mesh->point_count = static_cast<uint32_t>(keys.size());
}

}  // namespace lodbake
