// The two fronts of a DAG of vertex splits, maintained with one counter per
// node exactly as Zheng & Chan 2006 (section 3, Figure 1) describe: a split
// node's counter is its number of split children, a collapsed node's its
// number of collapsed parents; Fs (the collapsed nodes legal to split) and
// Fc (the split nodes legal to collapse) are the nodes whose counter is 0.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vsplit_dag.h"
#include "formats/support/status.h"
#include "lib/dag/vsplit_dag_builder.h"

namespace lodbake {

class DagFronts {
 public:
  /// Every node collapsed (the base mesh): Fs holds the nodes without
  /// parents, Fc is empty. Fails when the DAG is not well formed (offsets
  /// not increasing from 0, a parent not below its node, parents not
  /// strictly increasing). `dag` must outlive the fronts.
  static Result<DagFronts> create(const VsplitDag& dag);

  size_t node_count() const { return split_.size(); }
  size_t split_count() const { return applied_; }
  bool is_split(uint32_t node) const { return split_[node] != 0; }
  uint32_t counter(uint32_t node) const { return counter_[node]; }
  bool can_split(uint32_t node) const { return !is_split(node) && counter_[node] == 0; }
  bool can_collapse(uint32_t node) const { return is_split(node) && counter_[node] == 0; }

  /// Fs and Fc in no particular order (a node's slot changes as others
  /// enter and leave; the content is what the counters say).
  const std::vector<uint32_t>& split_front() const { return fs_.nodes; }
  const std::vector<uint32_t>& collapse_front() const { return fc_.nodes; }

  /// The children of `node` (the nodes that list it as a parent), ascending.
  const uint32_t* children_begin(uint32_t node) const;
  const uint32_t* children_end(uint32_t node) const;

  /// Splits a node of Fs; fails (no change) when the node is out of range
  /// or not in Fs.
  Status split(uint32_t node);
  /// Collapses a node of Fc; fails (no change) otherwise.
  Status collapse(uint32_t node);

  /// Recomputes every counter and both fronts from the split flags and
  /// compares; one line per kind of mismatch, empty when consistent.
  std::vector<std::string> check_counters() const;

 private:
  explicit DagFronts(const VsplitDag& dag) : dag_(&dag) {}
  // A set of nodes with O(1) insert and erase (swap with the last).
  struct NodeSet {
    std::vector<uint32_t> nodes;
    std::vector<uint32_t> slot;  // position in nodes, or kNoVertex
    void insert(uint32_t v);
    void erase(uint32_t v);
    bool contains(uint32_t v) const { return slot[v] != kNoVertex; }
  };

  const VsplitDag* dag_;
  std::vector<uint32_t> child_offsets_;
  std::vector<uint32_t> children_;
  std::vector<uint8_t> split_;
  std::vector<uint32_t> counter_;
  NodeSet fs_;
  NodeSet fc_;
  size_t applied_ = 0;
};

/// The triangles of the mesh a front stands for: those created by the base
/// or by a split node and not changed by a split node, in lineage order.
/// \pre lineage and fronts come from the same PM (same split count).
std::vector<Triangle> dag_cut_triangles(const SplitLineage& lineage, const DagFronts& fronts);

/// The same cut as lineage indices (into lineage.triangles, face_slot).
std::vector<uint32_t> dag_cut(const SplitLineage& lineage, const DagFronts& fronts);

}  // namespace lodbake
