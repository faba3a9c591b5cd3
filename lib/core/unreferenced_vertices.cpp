#include "lib/core/unreferenced_vertices.h"

#include <limits>
#include <vector>

namespace lodbake {
namespace {

void compact_attribute(MeshAttribute& attribute, const std::vector<uint32_t>& new_index,
                       size_t kept) {
  if (attribute.binding != AttributeBinding::kPerVertex) return;
  const size_t c = attribute.components;
  std::vector<float> values(kept * c);
  for (size_t v = 0; v < new_index.size(); ++v) {
    if (new_index[v] == std::numeric_limits<uint32_t>::max()) continue;
    for (size_t k = 0; k < c; ++k)
      values[new_index[v] * c + k] = attribute.values[v * c + k];
  }
  attribute.values = std::move(values);
}

}  // namespace

uint64_t remove_unreferenced_vertices(TriangleMesh& mesh) {
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> new_index(mesh.positions.size(), kUnused);
  for (const Triangle& t : mesh.triangles)
    for (uint32_t v : t)
      new_index[v] = 0;
  uint32_t kept = 0;
  for (uint32_t& slot : new_index)
    if (slot != kUnused) slot = kept++;
  const uint64_t removed = mesh.positions.size() - kept;
  if (removed == 0) return 0;
  std::vector<Vec3f> positions(kept);
  for (size_t v = 0; v < new_index.size(); ++v)
    if (new_index[v] != kUnused) positions[new_index[v]] = mesh.positions[v];
  mesh.positions = std::move(positions);
  for (Triangle& t : mesh.triangles)
    for (uint32_t& v : t)
      v = new_index[v];
  compact_attribute(mesh.normals, new_index, kept);
  compact_attribute(mesh.texcoords, new_index, kept);
  return removed;
}

}  // namespace lodbake
