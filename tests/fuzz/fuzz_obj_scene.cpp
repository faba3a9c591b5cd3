// Fuzz target for the OBJ and MTL scene readers: an OBJ read as a scene
// (usemtl groups as primitives, from memory: a material library is a
// warning), then written as GLB, and the same bytes read as an MTL
// library. None may crash, hang or allocate without bound.
#include <cstdint>
#include <cstdlib>

#include "lib/scene/mtl_reader.h"
#include "lib/scene/obj_scene.h"
#include "lib/scene/scene_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::ImportReport report;
  lodbake::Result<lodbake::Scene> scene =
      lodbake::read_obj_scene(data, size, "fuzz", lodbake::SceneResources{}, &report);
  if (scene.is_ok() && !scene.value().meshes.empty()) {
    lodbake::SceneWriteReport written;
    lodbake::Result<lodbake::Bytes> glb = lodbake::write_scene_glb(scene.value(), &written);
    (void)glb;  // refusing (e.g. a mesh without triangles) is fine; crashing is not
  }
  lodbake::ImportReport mtl_report;
  (void)lodbake::parse_mtl(data, size, &mtl_report);
  return 0;
}
