// An OBJ's materials as glTF 2.0 PBR materials, with the textures and images
// their maps name. Internal to lib/scene (the OBJ scene reader).
#pragma once

#include <string>
#include <vector>

#include "formats/scene/scene.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"
#include "lib/scene/scene_io.h"

namespace lodbake {

struct ObjSceneMaterials {
  SceneJson materials;  // JSON array, one per name asked for, in that order
  SceneJson textures;   // JSON array, or null when no map was named
  std::vector<SceneImage> images;
};

/// glTF materials for the 'usemtl' `names`, defined by the first of the
/// 'mtllib' `libraries` (read through `resources`) that defines each. A
/// library that cannot be read and a map whose image cannot be read are one
/// warning each in `report`; a name no library defines gets a material with
/// only that name and the defaults (a note, or a warning when every library
/// was read). Fails (kUnsupported) on a library or image that read_resource()
/// refuses rather than misses (outside the folder, a scheme), unless
/// `resources` has no folder, and when memory runs out. Mapping:
/// obj_materials.cpp.
Result<ObjSceneMaterials> obj_materials(const std::vector<std::string>& names,
                                        const std::vector<std::string>& libraries,
                                        const SceneResources& resources, ImportReport* report);

}  // namespace lodbake
