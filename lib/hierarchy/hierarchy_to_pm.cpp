// Hierarchy -> progressive mesh. The order is the one the selective refiner
// finds: array order (breadth first, so parents first), with the partial
// order of SelStreamVSplit pulled in front where both cut vertices share an
// active ancestor. Recording what the refiner does (rather than re-deriving
// wings) makes the PM exactly the sequence of meshes the refiner passed.
#include "lib/hierarchy/hierarchy_to_pm.h"

#include <new>

#include "lib/hierarchy/selective_refiner.h"

namespace lodbake {

Result<ProgressiveMesh> hierarchy_to_progressive_mesh(const VertexHierarchy& h,
                                                      std::vector<uint32_t>* node_of_split) {
  try {
    const size_t n = h.node_count();
    const auto roots = static_cast<uint32_t>(h.root_count());
    ProgressiveMesh pm;
    pm.base = h.base;
    pm.base.normals = MeshAttribute();
    pm.base.texcoords = MeshAttribute();
    std::vector<uint32_t> pm_vertex(n, kNoVertex);
    for (uint32_t r = 0; r < roots; ++r)
      pm_vertex[r] = r;
    // First the order (the refiner decides the partial order), then a
    // replay that reads each split's wings in the state just before it.
    std::vector<uint32_t> order;
    order.reserve((n - roots) / 2);
    {
      LODBAKE_ASSIGN_OR_RETURN(SelectiveRefiner first, SelectiveRefiner::create_by_index(h));
      for (uint32_t s = 0; s < n; ++s) {
        if (h.is_leaf(s) || !first.is_active(s)) continue;
        LODBAKE_RETURN_IF_ERROR(first.split_with_dependencies(s, &order));
      }
    }
    // Created once the first refiner is gone: one refiner at a time.
    LODBAKE_ASSIGN_OR_RETURN(SelectiveRefiner replay, SelectiveRefiner::create_by_index(h));
    pm.splits.reserve(order.size());
    for (uint32_t s : order) {
      const uint32_t left = h.first_child[s];
      const uint32_t right = left + 1;
      VertexSplit split;
      split.vs = pm_vertex[s];
      if (h.cut_left[s] != kNoNode) split.vl = pm_vertex[replay.active_ancestor(h.cut_left[s])];
      if (h.cut_right[s] != kNoNode) split.vr = pm_vertex[replay.active_ancestor(h.cut_right[s])];
      split.vt_position = h.position[right];
      split.vs_position = h.position[left];
      split.error = h.error[s];
      LODBAKE_RETURN_IF_ERROR(replay.split(s));
      pm_vertex[left] = pm_vertex[s];
      pm_vertex[right] = static_cast<uint32_t>(roots + pm.splits.size());
      pm.splits.push_back(split);
    }
    pm.input_vertex.assign(pm.full_vertex_count(), kNoVertex);
    for (uint32_t i = 0; i < n; ++i) {
      if (h.is_leaf(i)) pm.input_vertex[pm_vertex[i]] = h.input_vertex[i];
    }
    if (node_of_split != nullptr) *node_of_split = std::move(order);
    return pm;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory converting the hierarchy to a progressive mesh");
  }
}

}  // namespace lodbake
