// Fuzz target: parse_gltf (glTF JSON and GLB). On success the mesh must be
// structurally valid and survive a GLB round trip (write_glb, parse_gltf)
// with identical positions and triangles: the import welds equal positions,
// so its output has none left to merge, and export keeps vertex order.
#include <cstddef>
#include <cstdint>

#include "lib/dracoio/draco_io.h"
#include "tests/fuzz/mesh_invariants.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  ImportReport report;
  auto parsed = parse_gltf(data, size, &report);
  if (!parsed.is_ok()) {
    fuzz::check_error(parsed.status());
    return 0;
  }
  const TriangleMesh& mesh = parsed.value();
  fuzz::check_mesh(mesh);
  auto glb = write_glb(mesh);
  if (!fuzz::all_finite(mesh)) {
    // glTF cannot store non-finite POSITION bounds; export refuses.
    fuzz::require(!glb.is_ok());
    return 0;
  }
  fuzz::require(glb.is_ok());
  auto again = parse_gltf(glb.value().data(), glb.value().size(), nullptr);
  fuzz::require(again.is_ok());
  fuzz::require(again.value().triangles == mesh.triangles);
  fuzz::require(again.value().positions.size() == mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    fuzz::require(fuzz::same_position(again.value().positions[i], mesh.positions[i]));
  }
  return 0;
}
