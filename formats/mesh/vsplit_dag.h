// The DAG of vertex splits (Zheng & Chan 2006, section 3) as lodbake stores
// it: one node per vertex split of a progressive mesh (node i is split i),
// each node's parents in compressed-sparse-row form. Plain data shared by
// formats/ (the DAGE section, formats/sections/dage.h) and lib/dag/, which
// builds it from a ProgressiveMesh and maintains the fronts over it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lodbake {

struct VsplitDag {
  uint32_t base_vertex_count = 0;  // vertices of the PM's base mesh
  // Node i's parents are parents[parent_offsets[i] .. parent_offsets[i+1]),
  // strictly increasing and each < i (split order is a topological order).
  // parent_offsets has node_count() + 1 entries, the first 0.
  std::vector<uint32_t> parent_offsets{0};
  std::vector<uint32_t> parents;

  size_t node_count() const { return parent_offsets.empty() ? 0 : parent_offsets.size() - 1; }
  size_t edge_count() const { return parents.size(); }
  bool operator==(const VsplitDag& o) const {
    return base_vertex_count == o.base_vertex_count && parent_offsets == o.parent_offsets &&
           parents == o.parents;
  }
};

}  // namespace lodbake
