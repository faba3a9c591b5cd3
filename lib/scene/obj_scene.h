// An OBJ file with its material libraries as a Scene. Internal to lib/scene
// (read_scene_file()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "formats/scene/scene.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"
#include "lib/scene/scene_io.h"

namespace lodbake {

/// The OBJ text at `data` as one mesh named `name`: one primitive per
/// 'usemtl' material (faces before any 'usemtl' first, without a material),
/// materials as obj_materials() makes them. Vertices: one per distinct
/// (position, texture coordinate, normal) triple within a primitive (see
/// primitive_from_mesh()). A primitive holds the vertices its faces use,
/// except that a file with a single group keeps every vertex, as
/// import_mesh() does. Fails as parse_obj() fails.
Result<Scene> read_obj_scene(const uint8_t* data, size_t size, const std::string& name,
                             const SceneResources& resources, ImportReport* report);

}  // namespace lodbake
