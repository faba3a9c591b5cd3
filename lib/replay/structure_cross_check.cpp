#include "lib/replay/structure_cross_check.h"

#include <new>

#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/replay/replay_check.h"

namespace lodbake {

Result<StructureCrossCheck> StructureCrossCheck::create(const VertexHierarchy& h,
                                                        const ProgressiveMesh& pm,
                                                        const VsplitDag& dag) {
  try {
    StructureCrossCheck c(h, dag);
    LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh own,
                             hierarchy_to_progressive_mesh(h, &c.node_of_split_));
    if (own.splits.size() != pm.splits.size() ||
        own.base.vertex_count() != pm.base.vertex_count() || dag.node_count() != pm.splits.size()) {
      return invalid_input("the VSPL/DAGE sections are not the VHIE hierarchy's progressive mesh");
    }
    for (size_t k = 0; k < pm.splits.size(); ++k) {
      const VertexSplit& a = own.splits[k];
      const VertexSplit& b = pm.splits[k];
      if (a.vs != b.vs || a.vl != b.vl || a.vr != b.vr) {
        return invalid_input("split " + std::to_string(k) +
                             " of VSPL is not the VHIE hierarchy's (vs, vl, vr differ)");
      }
    }
    LODBAKE_ASSIGN_OR_RETURN(c.lineage_, build_split_lineage(pm));
    const auto roots = static_cast<uint32_t>(h.root_count());
    c.pm_vertex_.assign(h.node_count(), kNoVertex);
    c.split_of_node_.assign(h.node_count(), kNoVertex);
    for (uint32_t r = 0; r < roots; ++r)
      c.pm_vertex_[r] = r;
    // hierarchy_to_progressive_mesh numbers split k's right child
    // #roots + k; its left child keeps the parent's vertex.
    for (uint32_t k = 0; k < c.node_of_split_.size(); ++k) {
      const uint32_t s = c.node_of_split_[k];
      c.split_of_node_[s] = k;
      c.pm_vertex_[h.first_child[s]] = c.pm_vertex_[s];
      c.pm_vertex_[h.first_child[s] + 1] = roots + k;
    }
    return c;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the cross-structure check");
  }
}

std::vector<uint8_t> StructureCrossCheck::refiner_splits(const SelectiveRefiner& r) const {
  // A node is split when it is not active and its parent, if any, is split;
  // parents come first in array order.
  std::vector<uint8_t> node_split(h_->node_count(), 0);
  std::vector<uint8_t> flags(node_of_split_.size(), 0);
  for (uint32_t s = 0; s < h_->node_count(); ++s) {
    const uint32_t p = h_->parent[s];
    node_split[s] = !r.is_active(s) && (p == kNoNode || node_split[p] != 0);
    if (node_split[s] != 0 && split_of_node_[s] != kNoVertex) flags[split_of_node_[s]] = 1;
  }
  return flags;
}

std::vector<uint8_t> StructureCrossCheck::dag_splits(const DagFronts& fronts) const {
  std::vector<uint8_t> flags(fronts.node_count());
  for (uint32_t k = 0; k < flags.size(); ++k)
    flags[k] = fronts.is_split(k);
  return flags;
}

bool StructureCrossCheck::close(std::vector<uint8_t>* flags) const {
  std::vector<uint32_t> work;
  for (uint32_t k = 0; k < flags->size(); ++k) {
    if ((*flags)[k] != 0) work.push_back(k);
  }
  bool closed = true;
  auto need = [&](uint32_t k) {
    if ((*flags)[k] == 0) {
      (*flags)[k] = 1;
      work.push_back(k);
      closed = false;
    }
  };
  while (!work.empty()) {
    const uint32_t k = work.back();
    work.pop_back();
    for (uint32_t e = dag_->parent_offsets[k]; e < dag_->parent_offsets[k + 1]; ++e)
      need(dag_->parents[e]);
    const uint32_t p = h_->parent[node_of_split_[k]];
    if (p != kNoNode) need(split_of_node_[p]);
  }
  return closed;
}

std::vector<Triangle> StructureCrossCheck::in_pm_vertices(const std::vector<Triangle>& t) const {
  std::vector<Triangle> out;
  out.reserve(t.size());
  for (const Triangle& f : t)
    out.push_back({pm_vertex_[f[0]], pm_vertex_[f[1]], pm_vertex_[f[2]]});
  return out;
}

std::vector<std::string> StructureCrossCheck::compare(const std::vector<uint8_t>& flags,
                                                      const SelectiveRefiner* refiner,
                                                      const std::vector<Triangle>* cut) const {
  std::vector<std::string> problems;
  try {
    Result<DagFronts> fronts = DagFronts::create(*dag_);
    Result<SelectiveRefiner> rebuilt = SelectiveRefiner::create(*h_);
    if (!fronts.is_ok() || !rebuilt.is_ok()) {
      problems.push_back("cross-check: " +
                         (fronts.is_ok() ? rebuilt.status() : fronts.status()).message());
      return problems;
    }
    // In PM order every split of a front closed under both orders is legal
    // in both structures (parents first).
    size_t splits = 0;
    for (uint32_t k = 0; k < flags.size(); ++k) {
      if (flags[k] == 0) continue;
      ++splits;
      const Status in_dag = fronts.value().split(k);
      const Status in_hierarchy = rebuilt.value().split(node_of_split_[k]);
      if (!in_dag.is_ok() || !in_hierarchy.is_ok()) {
        problems.push_back(
            "cross-check: split " + std::to_string(k) +
            " of a front closed under "
            "both orders is refused by the " +
            (in_dag.is_ok() ? "hierarchy: " + in_hierarchy.message() : "DAG: " + in_dag.message()));
        return problems;
      }
    }
    const std::vector<Triangle> dag_mesh =
        sorted_canonical(dag_cut_triangles(lineage_, fronts.value()));
    auto differ = [&](const std::vector<Triangle>& other, const std::string& what) {
      if (other == dag_mesh) return;
      size_t only_dag = 0, only_other = 0;
      for (size_t i = 0, j = 0; i < dag_mesh.size() || j < other.size();) {
        if (j == other.size() || (i < dag_mesh.size() && dag_mesh[i] < other[j])) {
          ++only_dag, ++i;
        } else if (i == dag_mesh.size() || other[j] < dag_mesh[i]) {
          ++only_other, ++j;
        } else {
          ++i, ++j;
        }
      }
      problems.push_back("cross-check on a front of " + std::to_string(splits) +
                         " splits: " + what + " has " + std::to_string(only_other) +
                         " triangles the DAG's cut has not, the cut " + std::to_string(only_dag) +
                         " it has not");
    };
    differ(sorted_canonical(in_pm_vertices(rebuilt.value().triangles())), "the hierarchy's mesh");
    if (refiner != nullptr)
      differ(sorted_canonical(in_pm_vertices(refiner->triangles())), "the replay's refined mesh");
    if (cut != nullptr) differ(sorted_canonical(*cut), "the replay's DAG cut");
  } catch (const std::bad_alloc&) {
    problems.push_back("cross-check: out of memory");
  }
  return problems;
}

}  // namespace lodbake
