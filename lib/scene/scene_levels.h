// An asset container's scene at one level of detail: every mesh whose group
// holds a progressive mesh with its wedges (BASE, VSPL, WEDG: what
// lodbake-simplify --pm writes for an asset) refined to the level, its
// primitives rebuilt with their materials and attributes, the rest of the
// scene as SCNE holds it. What lodbake-inspect --extract OUT.glb --lod does.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/scene/scene.h"
#include "formats/support/status.h"

namespace lodbake {

// How many vertices of a progressive mesh the level keeps.
using LevelChooser = std::function<size_t(const ProgressiveMesh&)>;

/// `scene` is the container's SCNE scene (scene_of_container()). Fails with
/// kMissingSection (LBK-E0xx) when a mesh's group has no VSPL or no WEDG,
/// and with the sections' own errors when they do not decode or do not fit
/// the scene.
Result<Scene> scene_at_level(const Container& container, const Scene& scene,
                             const LevelChooser& choose);

/// --validate's check of every mesh's progressive mesh with wedges against
/// the asset: refined to the full mesh, every corner is at its wedge's home
/// and each primitive has its input's triangle count; coarsened back, the
/// base corners' wedges; both levels assemble into primitives. One message
/// per mesh that fails ("mesh M (group G): ..."); empty when every level
/// extracts.
std::vector<std::string> check_scene_levels(const Container& container, const Scene& scene);

}  // namespace lodbake
