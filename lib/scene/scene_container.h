// A whole asset in a lodbake container: the SCNE section (the scene as GLB
// and the group of each mesh) and, in each mesh's group, the BASE that is
// that mesh's welded topology, which every structure builder then refines.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/scene/scene.h"
#include "formats/sections/scne.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"
#include "lib/scene/scene_topology.h"

namespace lodbake {

struct SceneContainerContents {
  SceneSection section;                  // the map and the GLB
  std::vector<MeshTopology> topologies;  // per group, in group order
  std::vector<std::string> warnings;     // the GLB writer's
};

// Groups 0, 1, ... go to the meshes with triangles, in mesh order. Needs
// every mesh's point_of_vertex filled.
Result<SceneContainerContents> scene_container_contents(const Scene& scene);

// True when the container holds a SCNE section (in group 0).
bool has_scene(const Container& container);

// The scene the container's SCNE holds, every mesh's points welded, and
// its map. Fails with SCNE's decoding error or the GLB's.
Result<Scene> scene_of_container(const Container& container, SceneSection* map = nullptr,
                                 ImportReport* report = nullptr);

}  // namespace lodbake
