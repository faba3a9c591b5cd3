// Internal to lib/dracoio: the glTF node hierarchy, checked to be a forest
// (every node at most one parent, no cycles), with each node's local
// transform, and the scene's root nodes.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/scene/node_matrix.h"
#include "formats/support/status.h"
#include "lib/dracoio/gltf_document.h"

namespace lodbake {
namespace dracoio {

// Node transforms are formats/scene/node_matrix.h's Mat4 (column-major).
bool is_identity(const Mat4& m);
// Determinant of the upper-left 3x3 part (negative: the transform mirrors).
double linear_determinant(const Mat4& m);

struct NodeForest {
  std::vector<Mat4> local;                      // per node
  std::vector<int64_t> mesh;                    // per node, -1 when none
  std::vector<std::vector<uint32_t>> children;  // per node, in file order
  std::vector<int64_t> parent;                  // per node, -1 for roots
};

// Reads `nodes`, checking indices, single parenthood and acyclicity
// (iteratively: no recursion on file-controlled depth).
Result<NodeForest> load_nodes(const Json& root, size_t mesh_count);

struct SceneChoice {
  std::vector<uint32_t> roots;
  std::vector<std::string> notes;  // how the scene was chosen, scenes left out
};

// The root nodes to import: those of the default scene (`scene`), of scene 0
// when `scene` is absent, or every parentless node when there are no scenes.
Result<SceneChoice> choose_scene(const Json& root, const NodeForest& forest);

}  // namespace dracoio
}  // namespace lodbake
