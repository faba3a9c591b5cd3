// glTF 2.0 nodes and scenes (specification sections "Nodes and Hierarchy",
// "Transformations", "Scenes"). Choices:
// - A node's `matrix` wins when both it and TRS are present (the
//   specification forbids both; readers differ).
// - A rotation quaternion is normalized before use; a zero or non-finite one
//   is an error.
// - The specification requires disjoint strict trees: a node with two
//   parents, a cycle or a scene root that has a parent is an error, because
//   it would instance geometry more than once or loop.
// - Without `scene`, scene 0 is used (most viewers do); without scenes,
//   every parentless node is a root, in index order.
#include "lib/dracoio/gltf_nodes.h"

#include <cmath>

namespace lodbake {
namespace dracoio {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

// Column-major index of row r, column c.
constexpr size_t at(int r, int c) {
  return static_cast<size_t>(c) * 4 + static_cast<size_t>(r);
}

Result<Mat4> node_transform(const Json& node, const std::string& where) {
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<double> matrix,
                           member_numbers(node, "matrix", 16, where));
  if (!matrix.empty()) {
    Mat4 m;
    for (size_t i = 0; i < 16; ++i)
      m[i] = matrix[i];
    return m;
  }
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<double> t,
                           member_numbers(node, "translation", 3, where));
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<double> r, member_numbers(node, "rotation", 4, where));
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<double> s, member_numbers(node, "scale", 3, where));
  if (!r.empty()) {
    const double norm = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    if (!(norm > 0) || !std::isfinite(norm)) {
      return invalid_input(where + ": 'rotation' is not a usable quaternion");
    }
  }
  return trs_matrix(t.empty() ? nullptr : t.data(), r.empty() ? nullptr : r.data(),
                    s.empty() ? nullptr : s.data());
}

}  // namespace

bool is_identity(const Mat4& m) {
  return m == identity_matrix();
}

double linear_determinant(const Mat4& m) {
  return m[at(0, 0)] * (m[at(1, 1)] * m[at(2, 2)] - m[at(1, 2)] * m[at(2, 1)]) -
         m[at(0, 1)] * (m[at(1, 0)] * m[at(2, 2)] - m[at(1, 2)] * m[at(2, 0)]) +
         m[at(0, 2)] * (m[at(1, 0)] * m[at(2, 1)] - m[at(1, 1)] * m[at(2, 0)]);
}

Result<NodeForest> load_nodes(const Json& root, size_t mesh_count) {
  NodeForest forest;
  LODBAKE_ASSIGN_OR_RETURN(const Json* nodes, member_array(root, "nodes", "glTF"));
  const size_t n = nodes == nullptr ? 0 : nodes->size();
  forest.local.resize(n);
  forest.mesh.assign(n, -1);
  forest.children.resize(n);
  forest.parent.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const std::string where = "node " + str(i);
    const Json& node = (*nodes)[i];
    if (!node.is_object()) return invalid_input(where + " is not a JSON object");
    LODBAKE_ASSIGN_OR_RETURN(forest.local[i], node_transform(node, where));
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

Result<SceneChoice> choose_scene(const Json& root, const NodeForest& forest) {
  SceneChoice choice;
  LODBAKE_ASSIGN_OR_RETURN(const Json* scenes, member_array(root, "scenes", "glTF"));
  const size_t scene_count = scenes == nullptr ? 0 : scenes->size();
  LODBAKE_ASSIGN_OR_RETURN(int64_t scene,
                           member_index(root, "scene", scene_count, "scene", "glTF"));
  if (scene_count == 0) {
    for (size_t i = 0; i < forest.parent.size(); ++i) {
      if (forest.parent[i] < 0) choice.roots.push_back(static_cast<uint32_t>(i));
    }
    if (!forest.parent.empty()) choice.notes.push_back("no scenes: used every root node");
    return choice;
  }
  if (scene < 0) {
    scene = 0;
    if (scene_count > 0) choice.notes.push_back("no default scene given: used scene 0");
  }
  for (size_t s = 0; s < scene_count; ++s) {
    if (static_cast<int64_t>(s) != scene) {
      choice.notes.push_back("ignored scene " + str(s) + " (not the default scene)");
    }
  }
  const std::string where = "scene " + str(static_cast<uint64_t>(scene));
  const Json& chosen = (*scenes)[static_cast<size_t>(scene)];
  if (!chosen.is_object()) return invalid_input(where + " is not a JSON object");
  LODBAKE_ASSIGN_OR_RETURN(const Json* nodes, member_array(chosen, "nodes", where));
  if (nodes == nullptr) return choice;
  std::vector<uint8_t> listed(forest.parent.size(), 0);
  for (const Json& value : *nodes) {
    LODBAKE_ASSIGN_OR_RETURN(const int64_t node,
                             as_index(value, forest.parent.size(), "node", where));
    const size_t i = static_cast<size_t>(node);
    if (forest.parent[i] >= 0) {
      return invalid_input(where + " lists node " + str(i) + ", which is a child of node " +
                           str(static_cast<uint64_t>(forest.parent[i])));
    }
    if (listed[i]) return invalid_input(where + " lists node " + str(i) + " twice");
    listed[i] = 1;
    choice.roots.push_back(static_cast<uint32_t>(i));
  }
  return choice;
}

}  // namespace dracoio
}  // namespace lodbake
