// Fuzz target: parse_draco (.drc). On success the mesh must be structurally
// valid and its corners must keep their positions through a GLB round trip
// (write_glb, parse_gltf); vertex counts may drop there, because glTF import
// welds positions that Draco kept as separate vertices.
#include <cstddef>
#include <cstdint>

#include "lib/dracoio/draco_io.h"
#include "tests/fuzz/mesh_invariants.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  auto parsed = parse_draco(data, size, nullptr);
  if (!parsed.is_ok()) {
    fuzz::check_error(parsed.status());
    return 0;
  }
  const TriangleMesh& mesh = parsed.value();
  fuzz::check_mesh(mesh);
  if (!fuzz::all_finite(mesh)) return 0;
  auto glb = write_glb(mesh);
  fuzz::require(glb.is_ok());
  auto again = parse_gltf(glb.value().data(), glb.value().size(), nullptr);
  fuzz::require(again.is_ok());
  const TriangleMesh& back = again.value();
  fuzz::require(back.triangles.size() == mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      fuzz::require(fuzz::same_position(back.positions[back.triangles[t][k]],
                                        mesh.positions[mesh.triangles[t][k]]));
    }
  }
  return 0;
}
