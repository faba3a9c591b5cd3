// The fan-hierarchy (Livny, Sokolovsky & El-Sana 2007) as plain data: what
// lib/fanmerge builds, what the FANH section stores and what the runtime
// replays. Lives in formats/ (like progressive_mesh.h) so that the section
// codec does not depend on lib/.
//
// Nodes: the input's vertices are the leaves, node ids 0 .. vertex_count-1;
// each fan-merge adds one internal node, ids vertex_count + i in the order
// the merges were made. An internal node's first child is the node that
// represented the centre vertex before the merge (it is never collapsed: the
// centre keeps its position); the others are the link vertices' nodes in the
// order of the fine path, each collapsed into the centre by one half-edge
// collapse. Triangles are the input's, by index; a collapse renames the
// collapsed vertex to the centre in its modified triangles and removes its
// removed ones.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lodbake {

struct FanHierarchy {
  uint32_t vertex_count = 0;    ///< leaves: the input mesh's vertices
  uint32_t triangle_count = 0;  ///< the input mesh's triangles
  /// internal_count() + 1 offsets into `children`.
  std::vector<uint32_t> child_start{0};
  /// Node ids; internal node i's children are
  /// children[child_start[i] .. child_start[i + 1]), the centre first.
  std::vector<uint32_t> children;
  /// Per internal node: the fan-merge error Delta(v), a sum of mean squared
  /// distances (model units squared).
  std::vector<float> error;
  /// children.size() + 1 offsets into `removed` / `modified`: the triangles
  /// removed / modified by collapsing child entry j into its parent's centre
  /// (empty for centre entries).
  std::vector<uint32_t> removed_start{0};
  std::vector<uint32_t> removed;
  std::vector<uint32_t> modified_start{0};
  std::vector<uint32_t> modified;

  size_t internal_count() const { return error.size(); }
  uint64_t node_count() const { return uint64_t{vertex_count} + internal_count(); }
};

}  // namespace lodbake
