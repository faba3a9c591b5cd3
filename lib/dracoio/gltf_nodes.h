// Internal to lib/dracoio: the glTF node hierarchy, checked to be a forest
// (every node at most one parent, no cycles), each node's transform checked
// to be usable.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/support/status.h"
#include "lib/dracoio/gltf_document.h"

namespace lodbake {
namespace dracoio {

struct NodeForest {
  std::vector<int64_t> mesh;                    // per node, -1 when none
  std::vector<std::vector<uint32_t>> children;  // per node, in file order
  std::vector<int64_t> parent;                  // per node, -1 for roots
};

// Reads `nodes`, checking indices, single parenthood and acyclicity
// (iteratively: no recursion on file-controlled depth).
Result<NodeForest> load_nodes(const Json& root, size_t mesh_count);

}  // namespace dracoio
}  // namespace lodbake
