// The client side of To-Lau-Green vertex trees: the visible vertex list (one
// visible node per current vertex) moved down by splits and up by
// collapses, and the triangle list read from the visible nodes' fans.
//
// Triangle selection keeps the paper's rule (section 5.2): a triangle of
// TFan(v) is taken only when v's vertex state is the lowest of its three
// vertices', and degenerate triangles are dropped. The state used is the
// node's resolution level: the collapse step at which the node disappears
// when coarsening (split k's children: S - 1 - k with S splits; base nodes:
// S), so a lower state is a more recent node. Ties (the two children of one
// split, or two base vertices) go to the left child, then the larger vertex
// id. With that state the rule is exact: on any front that is legal in the
// split DAG and in the trees, the triangle list is the selectively refined
// mesh (docs/hierarchy-dag-vtrees.md gives the argument). The paper's own
// states (equations (1)-(3), stored in VertexTrees::vertex_states) are 0 or
// 1 and cannot order overlapping fans of more than two levels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vertex_trees.h"
#include "formats/support/status.h"

namespace lodbake {

class VisibleVertexList {
 public:
  /// The base nodes visible. Fails when the trees are malformed (a parent
  /// vertex that does not exist yet at its split, offsets that do not span
  /// the arrays, a fan vertex out of range). `trees` must outlive the list.
  static Result<VisibleVertexList> create(const VertexTrees& trees);

  size_t visible_count() const { return visible_count_; }
  /// The visible node of PM vertex v, or kNoVertex when v is not visible.
  uint32_t visible_node(uint32_t vertex) const { return visible_[vertex]; }
  /// The node split k's children hang under.
  uint32_t parent_node(uint32_t split) const { return parent_node_[split]; }
  /// Whether split k's parent node is visible (its children can replace it).
  bool can_split(uint32_t split) const;
  /// Whether both of split k's children are visible.
  bool can_collapse(uint32_t split) const;
  Status split(uint32_t split);
  Status collapse(uint32_t split);

  /// The resolution level of a node (lower: more recent, see above).
  uint32_t vertex_state(uint32_t node) const;

  /// The triangle list of the current visible vertex list, counter-clockwise.
  std::vector<Triangle> triangles() const;

 private:
  explicit VisibleVertexList(const VertexTrees& trees) : trees_(&trees) {}
  // Total order behind vertex_state(): lower wins, never equal for two nodes.
  uint64_t selection_key(uint32_t node) const;
  // The first visible vertex up the tree from `vertex`.
  uint32_t visible_ancestor(uint32_t vertex) const;

  const VertexTrees* trees_;
  std::vector<uint32_t> parent_node_;  // per split
  std::vector<uint32_t> visible_;      // per vertex
  size_t visible_count_ = 0;
};

}  // namespace lodbake
