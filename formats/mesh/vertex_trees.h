// Vertex trees (To, Lau & Green, "An adaptive multiresolution method for
// progressive model transmission", sections 3-5) as lodbake stores them:
// one tree per base vertex; each vertex split k of a progressive mesh gives
// the node of its split vertex vs two children, the left one the vertex the
// split creates (PM vertex B + k) and the right one a copy of vs, each with
// its vertex fan right after the split. Plain data shared by formats/ (the
// VTRE section, formats/sections/vtre.h) and lib/vtrees/.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

enum class VertexTreeNodeKind : uint8_t { kBase = 0, kLeft = 1, kRight = 2 };

struct VertexTrees {
  uint32_t base_vertex_count = 0;  // B: base nodes 0 .. B-1, node v is base vertex v
  // Per split k: vs, the parent vertex (the paper's PID of the left node).
  // Node B + 2k is split k's left child (vertex B + k), node B + 2k + 1 its
  // right child (a copy of vs).
  std::vector<uint32_t> parent_vertex;
  // Per vertex (B base vertices, then one per split): the coordinate the
  // base or left node carries; a right node has its parent's.
  std::vector<Vec3f> positions;
  // The paper's vertex state (equation (2), 0 or 1) of each base vertex and
  // of each split's left node (per split; the right sibling shares it):
  // base vertices first, then one per split.
  std::vector<uint8_t> vertex_states;
  // Fans: node n has runs [run_offsets[n], run_offsets[n + 1]); run r has the
  // clockwise neighbour vertex ids fan_vertices[vertex_offsets[r] ..
  // vertex_offsets[r + 1]) and is closed when run_closed[r] != 0. A manifold
  // vertex has one run (none when it has no face).
  std::vector<uint32_t> run_offsets{0};
  std::vector<uint8_t> run_closed;
  std::vector<uint32_t> vertex_offsets{0};
  std::vector<uint32_t> fan_vertices;

  size_t split_count() const { return parent_vertex.size(); }
  size_t node_count() const { return base_vertex_count + 2 * split_count(); }
  size_t run_count() const { return run_closed.size(); }
  VertexTreeNodeKind kind(size_t node) const {
    return node < base_vertex_count
               ? VertexTreeNodeKind::kBase
               : ((node - base_vertex_count) % 2 == 0 ? VertexTreeNodeKind::kLeft
                                                      : VertexTreeNodeKind::kRight);
  }
  /// The PM vertex a node stands for. \pre node < node_count().
  uint32_t node_vertex(size_t node) const {
    if (node < base_vertex_count) return static_cast<uint32_t>(node);
    const size_t k = (node - base_vertex_count) / 2;
    return (node - base_vertex_count) % 2 == 0 ? static_cast<uint32_t>(base_vertex_count + k)
                                               : parent_vertex[k];
  }
  bool operator==(const VertexTrees& o) const {
    return base_vertex_count == o.base_vertex_count && parent_vertex == o.parent_vertex &&
           positions == o.positions && vertex_states == o.vertex_states &&
           run_offsets == o.run_offsets && run_closed == o.run_closed &&
           vertex_offsets == o.vertex_offsets && fan_vertices == o.fan_vertices;
  }
};

}  // namespace lodbake
