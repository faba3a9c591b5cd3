// What `lodbake-inspect ASSET` reports about a scene: per mesh and
// primitive, triangles, attributes, material, instancing, skin and seams.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/scene/scene.h"

namespace lodbake {

struct PrimitiveSummary {
  std::string mode;  // "TRIANGLES", "LINES", ...
  uint64_t vertices = 0;
  uint64_t triangles = 0;
  bool indexed = false;
  std::vector<std::string>
      attributes;        // "TEXCOORD_0 VEC2 float", "COLOR_0 VEC4 unsigned byte normalized"
  uint64_t targets = 0;  // morph targets
  int32_t material = -1;
  std::string material_name;
  // Points of this primitive that sit on a seam (SceneSummary comment).
  uint64_t seam_points = 0;
};

struct MeshSummary {
  std::string name;
  std::vector<uint32_t> nodes;  // the nodes that use it (instancing when more than one)
  bool skinned = false;         // a node using it has a skin
  uint64_t points = 0;          // distinct positions over all its primitives
  uint64_t triangles = 0;
  // A seam point is a point whose vertices (over all the mesh's primitives)
  // do not all carry the same attribute values, e.g. a UV seam, a hard
  // edge, or a border between two materials; a border point is one used by
  // more than one primitive.
  uint64_t seam_points = 0;
  uint64_t border_points = 0;
  std::vector<PrimitiveSummary> primitives;
};

struct SceneSummary {
  uint64_t nodes = 0, scenes = 0, materials = 0, textures = 0, images = 0, missing_images = 0,
           skins = 0, animations = 0, cameras = 0;
  uint64_t primitives = 0;
  uint64_t triangles = 0;            // each mesh once
  uint64_t instanced_triangles = 0;  // each mesh once per node that uses it
  std::vector<std::string> extensions_used;
  std::vector<MeshSummary> meshes;
};

// Needs every mesh's point_of_vertex filled (weld_mesh_points()).
SceneSummary summarize_scene(const Scene& scene);

nlohmann::json to_json(const SceneSummary& summary);

// "TEXCOORD_0 VEC2 float", "JOINTS_0 VEC4 unsigned short".
std::string describe_stream(const SceneAttribute& attribute);

}  // namespace lodbake
