// A balanced vertex hierarchy (Kim, Lee and Kobbelt, "View-dependent mesh
// streaming with minimal latency", sections 4, 5.2, 6.1, 6.2) as lodbake
// stores it: a forest of binary trees over half-edge collapses, packed
// breadth-first into one array, with the fundamental cut vertices of every
// vertex split. Built by lib/hierarchy, stored as BASE + VHIE (+ RFIN,
// formats/sections/vhie.h, rfin.h), refined by lib/hierarchy's
// SelectiveRefiner. Plain data shared by formats/ and lib/.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

inline constexpr uint32_t kNoNode = std::numeric_limits<uint32_t>::max();

/// Node i of the array; nodes 0 .. root_count-1 are the roots (tree i, heap
/// id 1, base vertex i). Breadth-first over all trees: parent[i] < i, and the
/// two children of a node are adjacent: left = first_child, right =
/// first_child + 1. Left child = the vertex that survives the half-edge
/// collapse (it keeps the parent's position), right child = the removed one.
struct VertexHierarchy {
  TriangleMesh base;                  ///< base mesh over the roots (vertex i = node i)
  std::vector<uint32_t> parent;       ///< kNoNode for roots
  std::vector<uint32_t> first_child;  ///< kNoNode for leaves
  std::vector<Vec3f> position;        ///< every node's position (= its leftmost leaf's)
  /// Fundamental cut vertices of an internal node's split: node indices of
  /// leaves, kNoNode for a missing wing (boundary) and for leaves. The new
  /// faces of the split are (left, right, AA(cut_left)) and
  /// (right, left, AA(cut_right)), counter-clockwise.
  std::vector<uint32_t> cut_left;
  std::vector<uint32_t> cut_right;
  /// Input vertex of a leaf (a permutation of the input's vertices over the
  /// leaves), kNoVertex for internal nodes.
  std::vector<uint32_t> input_vertex;
  /// The collapse's error (sqrt of the quadric's weighted mean squared
  /// distance, model units) for internal nodes, 0 for leaves.
  std::vector<float> error;

  size_t node_count() const { return parent.size(); }
  size_t root_count() const { return base.positions.size(); }
  bool is_leaf(uint32_t node) const { return first_child[node] == kNoNode; }
};

/// <tree-id, node-id> of one node: tree = root index, heap = heap id within
/// the tree (root 1, children of k are 2k and 2k+1).
struct HierarchyNodeId {
  uint32_t tree = 0;
  uint64_t heap = 0;
  bool operator==(const HierarchyNodeId& o) const { return tree == o.tree && heap == o.heap; }
  bool operator<(const HierarchyNodeId& o) const {
    return tree < o.tree || (tree == o.tree && heap < o.heap);
  }
};

/// Per-internal-node refinement data for Hoppe's view-dependent criteria
/// (RFIN): bounding sphere around the node's position, cone of normals, and
/// the squared deviation-space terms.
struct NodeRefinement {
  float radius = 0;           ///< sphere at the node's position holding its region
  Vec3f cone_axis{};          ///< unit axis of the cone of normals
  float cone_half_angle = 0;  ///< radians, in [0, pi]
  float mu2 = 0;              ///< squared uniform deviation
  float delta2 = 0;           ///< squared deviation along the node's normal
};

}  // namespace lodbake
