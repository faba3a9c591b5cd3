// Front maintenance of Zheng & Chan 2006, section 3: splitting node n
// increments the counter of each of its (split) parents, which leave Fc
// when theirs was 0, and decrements the counter of each (collapsed) child,
// which enters Fs when it reaches 0; collapsing does the reverse. Both
// fronts are kept as swap-with-last sets so a traversal can pick any member
// in O(1).
#include "lib/dag/dag_fronts.h"

#include <new>
#include <string>

namespace lodbake {

void DagFronts::NodeSet::insert(uint32_t v) {
  slot[v] = static_cast<uint32_t>(nodes.size());
  nodes.push_back(v);
}

void DagFronts::NodeSet::erase(uint32_t v) {
  const uint32_t at = slot[v];
  const uint32_t last = nodes.back();
  nodes[at] = last;
  slot[last] = at;
  nodes.pop_back();
  slot[v] = kNoVertex;
}

Result<DagFronts> DagFronts::create(const VsplitDag& dag) {
  try {
    const size_t n = dag.node_count();
    if (dag.parent_offsets.empty() || dag.parent_offsets[0] != 0 ||
        dag.parent_offsets.back() != dag.parents.size()) {
      return invalid_input("split DAG offsets do not span its parent list");
    }
    for (size_t i = 0; i < n; ++i) {
      const uint32_t b = dag.parent_offsets[i];
      const uint32_t e = dag.parent_offsets[i + 1];
      if (e < b) return invalid_input("split DAG offsets decrease at node " + std::to_string(i));
      for (uint32_t k = b; k < e; ++k) {
        if (dag.parents[k] >= i || (k > b && dag.parents[k] <= dag.parents[k - 1])) {
          return invalid_input("split DAG node " + std::to_string(i) +
                               ": parents must be strictly increasing and below the node");
        }
      }
    }
    DagFronts f(dag);
    f.child_offsets_.assign(n + 1, 0);
    for (uint32_t p : dag.parents)
      ++f.child_offsets_[p + 1];
    for (size_t i = 0; i < n; ++i)
      f.child_offsets_[i + 1] += f.child_offsets_[i];
    f.children_.resize(dag.parents.size());
    std::vector<uint32_t> fill(f.child_offsets_.begin(), f.child_offsets_.end() - 1);
    for (size_t i = 0; i < n; ++i) {
      for (uint32_t k = dag.parent_offsets[i]; k < dag.parent_offsets[i + 1]; ++k)
        f.children_[fill[dag.parents[k]]++] = static_cast<uint32_t>(i);
    }
    f.split_.assign(n, 0);
    f.counter_.resize(n);
    f.fs_.slot.assign(n, kNoVertex);
    f.fc_.slot.assign(n, kNoVertex);
    for (size_t i = 0; i < n; ++i) {
      f.counter_[i] = dag.parent_offsets[i + 1] - dag.parent_offsets[i];
      if (f.counter_[i] == 0) f.fs_.insert(static_cast<uint32_t>(i));
    }
    return f;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while setting up the DAG fronts");
  }
}

const uint32_t* DagFronts::children_begin(uint32_t node) const {
  return children_.data() + child_offsets_[node];
}

const uint32_t* DagFronts::children_end(uint32_t node) const {
  return children_.data() + child_offsets_[node + 1];
}

Status DagFronts::split(uint32_t node) {
  if (node >= node_count() || !can_split(node)) {
    return invalid_input("node " + std::to_string(node) + " is not in the split front Fs");
  }
  const VsplitDag& dag = *dag_;
  for (uint32_t k = dag.parent_offsets[node]; k < dag.parent_offsets[node + 1]; ++k) {
    const uint32_t p = dag.parents[k];
    if (counter_[p]++ == 0) fc_.erase(p);
  }
  for (const uint32_t* c = children_begin(node); c != children_end(node); ++c) {
    if (--counter_[*c] == 0) fs_.insert(*c);
  }
  fs_.erase(node);
  split_[node] = 1;
  counter_[node] = 0;  // no child of a collapsed node is split
  fc_.insert(node);
  ++applied_;
  return Status::ok();
}

Status DagFronts::collapse(uint32_t node) {
  if (node >= node_count() || !can_collapse(node)) {
    return invalid_input("node " + std::to_string(node) + " is not in the collapse front Fc");
  }
  const VsplitDag& dag = *dag_;
  for (uint32_t k = dag.parent_offsets[node]; k < dag.parent_offsets[node + 1]; ++k) {
    const uint32_t p = dag.parents[k];
    if (--counter_[p] == 0) fc_.insert(p);
  }
  for (const uint32_t* c = children_begin(node); c != children_end(node); ++c) {
    if (counter_[*c]++ == 0) fs_.erase(*c);
  }
  fc_.erase(node);
  split_[node] = 0;
  counter_[node] = 0;  // every parent of a split node is split
  fs_.insert(node);
  --applied_;
  return Status::ok();
}

std::vector<std::string> DagFronts::check_counters() const {
  std::vector<std::string> findings;
  const VsplitDag& dag = *dag_;
  size_t wrong_counter = 0;
  size_t wrong_front = 0;
  size_t broken_order = 0;
  for (uint32_t i = 0; i < node_count(); ++i) {
    uint32_t expected = 0;
    if (is_split(i)) {
      for (const uint32_t* c = children_begin(i); c != children_end(i); ++c)
        expected += split_[*c];
    } else {
      for (uint32_t k = dag.parent_offsets[i]; k < dag.parent_offsets[i + 1]; ++k)
        expected += split_[dag.parents[k]] == 0;
      for (const uint32_t* c = children_begin(i); c != children_end(i); ++c)
        broken_order += split_[*c];
    }
    if (expected != counter_[i]) ++wrong_counter;
    const bool in_fs = fs_.contains(i);
    const bool in_fc = fc_.contains(i);
    if (in_fs != (!is_split(i) && expected == 0) || in_fc != (is_split(i) && expected == 0)) {
      ++wrong_front;
    }
  }
  if (wrong_counter) findings.push_back(std::to_string(wrong_counter) + " counters are wrong");
  if (wrong_front)
    findings.push_back(std::to_string(wrong_front) + " nodes are in the wrong front");
  if (broken_order) {
    findings.push_back(std::to_string(broken_order) + " split nodes below a collapsed node");
  }
  return findings;
}

std::vector<uint32_t> dag_cut(const SplitLineage& lineage, const DagFronts& fronts) {
  std::vector<uint32_t> out;
  const size_t splits = lineage.split_count();
  auto alive = [&](size_t t) {
    const uint32_t by = lineage.changed_by[t];
    return by == kNoVertex || !fronts.is_split(by);
  };
  for (uint32_t t = 0; t < lineage.created_offsets[0]; ++t) {
    if (alive(t)) out.push_back(t);
  }
  for (size_t i = 0; i < splits; ++i) {
    if (!fronts.is_split(static_cast<uint32_t>(i))) continue;
    for (uint32_t t = lineage.created_offsets[i]; t < lineage.created_offsets[i + 1]; ++t) {
      if (alive(t)) out.push_back(t);
    }
  }
  return out;
}

std::vector<Triangle> dag_cut_triangles(const SplitLineage& lineage, const DagFronts& fronts) {
  std::vector<Triangle> out;
  for (uint32_t t : dag_cut(lineage, fronts))
    out.push_back(lineage.triangles[t]);
  return out;
}

}  // namespace lodbake
