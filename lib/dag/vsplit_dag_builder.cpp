// The DAG of vertex-split / edge-collapse nodes of Zheng & Chan ("Efficient
// view-dependent LOD control for large 3D unclosed mesh models", CGIV 2006,
// section 3, which refers to their earlier construction from a PM): node i
// is split i, and its parents are the splits that created what split i
// changes, so any set of splits closed under parents can be applied in any
// order that respects the edges and gives the same mesh.
//
// Choices where the paper is vague:
// - "What split i changes" is the faces it moves from vs to vt. A split adds
//   its one or two new faces without changing anything else, so on a
//   boundary (a face glued onto a boundary edge, or vs's boundary handed to
//   vt) triangle dependencies alone would let it run on a mesh whose
//   boundary is not the one it was recorded on. The boundary half-edges
//   around vs therefore count as virtual triangles (to a vertex at
//   infinity): the split depends on the creators of those it removes. This
//   makes every split an interior split of the closed-up mesh.
// - Redundant edges are removed by a transitive reduction: parents are
//   visited from the highest index down, each kept parent's ancestors with
//   index above the lowest parent are marked (the reduced graph has the same
//   reachability, and an ancestor of p has an index below p), and a marked
//   parent is dropped.
#include "lib/dag/vsplit_dag_builder.h"

#include <algorithm>
#include <new>
#include <unordered_map>

#include "lib/dag/split_simulator.h"

namespace lodbake {

Result<SplitLineage> build_split_lineage(const ProgressiveMesh& pm, bool dependencies_only) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(SplitSimulator sim, SplitSimulator::create(pm));
    SplitLineage out;
    const size_t splits = pm.splits.size();
    out.base_vertex_count = static_cast<uint32_t>(pm.base.vertex_count());
    // Triangles are counted, and stored unless only dependencies are asked.
    const bool keep = !dependencies_only;
    uint32_t triangle_count = static_cast<uint32_t>(pm.base.triangles.size());
    if (keep) {
      out.triangles = pm.base.triangles;
      out.triangles.reserve(pm.base.triangles.size() + 8 * splits);
      out.changed_by.assign(out.triangles.size(), kNoVertex);
      out.face_slot.resize(out.triangles.size());
      for (size_t t = 0; t < out.face_slot.size(); ++t)
        out.face_slot[t] = static_cast<uint32_t>(t);
    }
    std::vector<uint32_t> creator(triangle_count, kNoVertex);
    std::vector<uint32_t> slot_triangle(triangle_count);
    for (size_t t = 0; t < slot_triangle.size(); ++t)
      slot_triangle[t] = static_cast<uint32_t>(t);
    out.created_offsets.reserve(splits + 1);
    out.created_offsets.push_back(triangle_count);
    out.dependency_offsets.reserve(splits + 1);
    out.dependency_offsets.push_back(0);

    // Boundary half-edge -> the split that created it (kNoVertex: the base).
    // Looked up only, never iterated, so its order cannot leak.
    std::unordered_map<HalfEdgeKey, uint32_t> boundary_creator;
    for (uint32_t v = 0; v < out.base_vertex_count; ++v) {
      std::vector<HalfEdgeKey> edges;
      sim.boundary_half_edges(v, &edges);
      for (HalfEdgeKey e : edges)
        boundary_creator.emplace(e, kNoVertex);
    }

    SplitSimulator::Effect effect;
    std::vector<HalfEdgeKey> before;
    std::vector<HalfEdgeKey> after;
    std::vector<uint32_t> deps;
    for (size_t i = 0; i < splits; ++i) {
      const uint32_t split = static_cast<uint32_t>(i);
      const uint32_t vs = pm.splits[i].vs;
      const uint32_t vt = static_cast<uint32_t>(sim.vertex_count());
      before.clear();
      if (vs < sim.vertex_count()) sim.boundary_half_edges(vs, &before);
      LODBAKE_RETURN_IF_ERROR(sim.split_next(&effect));
      after.clear();
      sim.boundary_half_edges(vs, &after);
      sim.boundary_half_edges(vt, &after);
      std::sort(before.begin(), before.end());
      std::sort(after.begin(), after.end());

      deps.clear();
      for (uint32_t slot : effect.moved) {
        const uint32_t old = slot_triangle[slot];
        if (creator[old] != kNoVertex) deps.push_back(creator[old]);
        slot_triangle[slot] = triangle_count++;
        creator.push_back(split);
        if (!keep) continue;
        out.changed_by[old] = split;
        out.triangles.push_back(sim.faces()[slot]);
        out.face_slot.push_back(slot);
        out.changed_by.push_back(kNoVertex);
      }
      for (uint32_t slot : effect.added) {
        slot_triangle.push_back(triangle_count++);
        creator.push_back(split);
        if (!keep) continue;
        out.triangles.push_back(sim.faces()[slot]);
        out.face_slot.push_back(slot);
        out.changed_by.push_back(kNoVertex);
      }
      for (HalfEdgeKey e : before) {
        if (std::binary_search(after.begin(), after.end(), e)) continue;
        auto it = boundary_creator.find(e);
        if (it == boundary_creator.end()) continue;
        if (it->second != kNoVertex) deps.push_back(it->second);
        boundary_creator.erase(it);
      }
      for (HalfEdgeKey e : after) {
        if (!std::binary_search(before.begin(), before.end(), e)) boundary_creator[e] = split;
      }
      std::sort(deps.begin(), deps.end());
      deps.erase(std::unique(deps.begin(), deps.end()), deps.end());
      out.dependencies.insert(out.dependencies.end(), deps.begin(), deps.end());
      out.dependency_offsets.push_back(static_cast<uint32_t>(out.dependencies.size()));
      out.created_offsets.push_back(triangle_count);
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while building the split lineage");
  }
}

Result<VsplitDag> reduce_dependencies(const SplitLineage& lineage) {
  try {
    VsplitDag dag;
    dag.base_vertex_count = lineage.base_vertex_count;
    const size_t n = lineage.split_count();
    dag.parent_offsets.reserve(n + 1);
    dag.parents.reserve(lineage.dependencies.size());
    std::vector<uint32_t> mark(n, kNoVertex);  // mark[v] == i: ancestor of a kept parent of i
    std::vector<uint32_t> stack;
    std::vector<uint32_t> kept;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t node = static_cast<uint32_t>(i);
      const uint32_t* first = lineage.dependencies.data() + lineage.dependency_offsets[i];
      const uint32_t* last = lineage.dependencies.data() + lineage.dependency_offsets[i + 1];
      kept.clear();
      if (first != last) {
        const uint32_t lowest = *first;
        for (const uint32_t* q = last; q != first;) {
          --q;
          if (mark[*q] == node) continue;  // implied by a higher parent
          kept.push_back(*q);
          stack.assign(1, *q);
          while (!stack.empty()) {
            const uint32_t v = stack.back();
            stack.pop_back();
            for (uint32_t k = dag.parent_offsets[v]; k < dag.parent_offsets[v + 1]; ++k) {
              const uint32_t p = dag.parents[k];
              if (p < lowest || mark[p] == node) continue;
              mark[p] = node;
              stack.push_back(p);
            }
          }
        }
      }
      std::sort(kept.begin(), kept.end());
      dag.parents.insert(dag.parents.end(), kept.begin(), kept.end());
      dag.parent_offsets.push_back(static_cast<uint32_t>(dag.parents.size()));
    }
    return dag;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reducing the split DAG");
  }
}

Result<VsplitDag> build_vsplit_dag(const ProgressiveMesh& pm) {
  LODBAKE_ASSIGN_OR_RETURN(SplitLineage lineage,
                           build_split_lineage(pm, /*dependencies_only=*/true));
  return reduce_dependencies(lineage);
}

}  // namespace lodbake
