// glTF 2.0 nodes (specification sections "Nodes and Hierarchy",
// "Transformations"). Choices:
// - A node's `matrix` wins when both it and TRS are present (the
//   specification forbids both; readers differ).
// - A rotation quaternion is normalized before use; a zero or non-finite one
//   is an error.
// - The specification requires disjoint strict trees: a node with two
//   parents, a cycle or a scene root that has a parent is an error, because
//   it would instance geometry more than once or loop.
#include "lib/dracoio/gltf_nodes.h"

#include <cmath>

namespace lodbake {
namespace dracoio {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

// The node's transform is usable: numbers where numbers belong, and a
// rotation quaternion that can be normalized (unless a matrix wins).
Status check_transform(const Json& node, const std::string& where) {
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<double> matrix,
                           member_numbers(node, "matrix", 16, where));
  if (!matrix.empty()) return Status::ok();
  LODBAKE_RETURN_IF_ERROR(member_numbers(node, "translation", 3, where).status());
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<double> r, member_numbers(node, "rotation", 4, where));
  LODBAKE_RETURN_IF_ERROR(member_numbers(node, "scale", 3, where).status());
  if (!r.empty()) {
    const double norm = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    if (!(norm > 0) || !std::isfinite(norm)) {
      return invalid_input(where + ": 'rotation' is not a usable quaternion");
    }
  }
  return Status::ok();
}

}  // namespace

Result<NodeForest> load_nodes(const Json& root, size_t mesh_count) {
  NodeForest forest;
  LODBAKE_ASSIGN_OR_RETURN(const Json* nodes, member_array(root, "nodes", "glTF"));
  const size_t n = nodes == nullptr ? 0 : nodes->size();
  forest.mesh.assign(n, -1);
  forest.children.resize(n);
  forest.parent.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const std::string where = "node " + str(i);
    const Json& node = (*nodes)[i];
    if (!node.is_object()) return invalid_input(where + " is not a JSON object");
    LODBAKE_RETURN_IF_ERROR(check_transform(node, where));
    LODBAKE_ASSIGN_OR_RETURN(forest.mesh[i], member_index(node, "mesh", mesh_count, "mesh", where));
    LODBAKE_ASSIGN_OR_RETURN(const Json* children, member_array(node, "children", where));
    if (children == nullptr) continue;
    for (const Json& c : *children) {
      LODBAKE_ASSIGN_OR_RETURN(const int64_t child, as_index(c, n, "node", where + " children"));
      if (static_cast<size_t>(child) == i) return invalid_input(where + " is its own child");
      if (forest.parent[static_cast<size_t>(child)] >= 0) {
        return invalid_input("node " + str(static_cast<uint64_t>(child)) +
                             " has two parents (nodes " +
                             str(static_cast<uint64_t>(forest.parent[static_cast<size_t>(child)])) +
                             " and " + str(i) + ")");
      }
      forest.parent[static_cast<size_t>(child)] = static_cast<int64_t>(i);
      forest.children[i].push_back(static_cast<uint32_t>(child));
    }
  }
  // With at most one parent each, the nodes not reachable from a parentless
  // node are exactly those on (or below) a cycle.
  std::vector<uint8_t> reached(n, 0);
  std::vector<uint32_t> stack;
  for (size_t i = 0; i < n; ++i) {
    if (forest.parent[i] >= 0) continue;
    stack.push_back(static_cast<uint32_t>(i));
    while (!stack.empty()) {
      const uint32_t v = stack.back();
      stack.pop_back();
      reached[v] = 1;
      for (uint32_t c : forest.children[v])
        stack.push_back(c);
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (!reached[i]) return invalid_input("node " + str(i) + " is part of a cycle of children");
  }
  return forest;
}

}  // namespace dracoio
}  // namespace lodbake
