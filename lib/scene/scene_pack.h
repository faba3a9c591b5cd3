// `lodbake-pack ASSET.gltf -o OUT.lbk`: the container of a whole asset.
// META (its "scene" key counts the asset), SCNE and, in group g, the BASE of
// the g-th mesh with triangles (scene_container.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/scene/scene.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

struct ScenePackResult {
  Bytes file;
  uint64_t meta_bytes = 0;
  uint64_t scne_bytes = 0;
  std::vector<uint64_t> base_bytes;  // per group
  std::vector<uint64_t> base_vertices, base_triangles;
  std::vector<std::string> warnings;  // what the scene's GLB could not keep
};

// `meta` gives tool, options and input; its counts become group 0's BASE
// counts (what validation compares), and "scene" is added. Deterministic.
Result<ScenePackResult> pack_scene(const Scene& scene, MetaSection meta,
                                   const BaseEncodeOptions& encoding);

// The asset's totals META records under "scene".
nlohmann::json scene_counts(const Scene& scene);

}  // namespace lodbake
