// weld_mesh_points(): shared points across a mesh's primitives by exact
// POSITION bytes. Bit equality, not a tolerance: the model must not merge
// what the file distinguishes, and -0.0 versus 0.0 or two NaN payloads are
// then distinct points, which is what a byte-level comparison of the
// streams would say too.
#include <cstring>
#include <vector>

#include "lib/scene/exact_key_numbering.h"
#include "lib/scene/scene_points.h"

namespace lodbake {

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
  ExactKeyNumbering points(total);
  for (size_t p = 0; p < streams.size(); ++p) {
    const AccessorData* data = streams[p];
    if (data == nullptr) continue;
    const uint32_t size = data->element_size();
    // The element's bytes with its type, so that a float and an int16
    // stream (or a normalized one) never share a point.
    ExactKey key;
    key.tag = static_cast<uint32_t>(data->component_type) | (data->normalized ? 1u << 16 : 0u);
    std::vector<uint32_t>& out = mesh->point_of_vertex[p];
    out.resize(data->count);
    for (uint32_t v = 0; v < data->count; ++v) {
      uint8_t element[16] = {};
      std::memcpy(element, data->bytes.data() + size_t{v} * size, size);
      std::memcpy(&key.lo, element, 8);
      std::memcpy(&key.hi, element + 8, 8);
      out[v] = points.number(key);
    }
  }
  mesh->point_count = points.size();
}

}  // namespace lodbake
