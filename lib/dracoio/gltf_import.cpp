// parse_gltf(): a glTF asset as one merged mesh is the scene reader's scene
// (read_gltf_scene(), gltf_scene_import.cpp) flattened (flatten_scene(),
// lib/scene/scene_flatten.h), so the two can never read a file differently.
//
// Why not draco::GltfDecoder (Draco 1.5.5, Debian 12)? Checked on this
// machine: DecodeFromBuffer reads only GLB, flattens every scene instead of
// the default one, fails the whole file on a LINES primitive, ignores a node
// rotation of exactly [0, 0, 1, 0] (it mistakes it for the identity), reads
// out of bounds on an index past the vertex count and overflows the stack on
// a cycle of node children. So lodbake parses the JSON itself (bounded, see
// gltf_document.cpp, gltf_accessor_data.cpp, gltf_nodes.cpp) and uses Draco
// for KHR_draco_mesh_compression primitives, .drc files and GLB export.
//
// Instancing can multiply geometry: the flattening caps decoded and
// instanced vertices plus triangles at max(2^22, 64 x input bytes).
#include <algorithm>

#include "lib/dracoio/draco_io.h"
#include "lib/scene/scene_flatten.h"

namespace lodbake {
namespace {

constexpr uint64_t kMinBudget = uint64_t{1} << 22;
constexpr uint64_t kBudgetPerInputByte = 64;

}  // namespace

Result<TriangleMesh> parse_gltf(const uint8_t* data, size_t size, ImportReport* report,
                                const SceneResources& resources) {
  // The scene reader's own report is not passed on: its warnings (a missing
  // image, an extension it could not carry) concern parts the merged mesh
  // leaves out anyway, and the flattening notes those.
  ImportReport scene_report;
  LODBAKE_ASSIGN_OR_RETURN(const Scene scene,
                           read_gltf_scene(data, size, resources, &scene_report));
  const uint64_t budget = std::max(kMinBudget, kBudgetPerInputByte * uint64_t{size});
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, flatten_scene(scene, budget, report));
  if (report != nullptr) report->format = scene_report.format;
  return mesh;
}

}  // namespace lodbake
