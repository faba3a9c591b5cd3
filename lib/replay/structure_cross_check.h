// --validate's cross-structure check (issue 8): lodbake-hierarchy writes the
// balanced vertex hierarchy (VHIE) and, from the same hierarchy, its
// progressive mesh (VSPL) and split DAG (DAGE). Both describe the same
// meshes for the same set of splits, so after every frame of a vhier or dag
// replay the mesh it holds is compared with the other structure's mesh for
// that front.
//
// The two families of legal fronts are not nested (docs/replay.md, "The
// cross-structure check"): truly selective refinement splits a node before
// a neighbour whose split created one of its faces in the PM's order, and
// the DAG splits a left child's split before its parent's when their fans do
// not overlap. A front is comparable when it is closed under both the DAG's
// parents and the hierarchy's; otherwise the check moves to the smallest such
// front containing it and compares the two structures there, each rebuilt
// from the base by splitting in PM order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/mesh/vsplit_dag.h"
#include "formats/support/status.h"
#include "lib/dag/dag_fronts.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/hierarchy/selective_refiner.h"

namespace lodbake {

class StructureCrossCheck {
 public:
  /// Fails (kInvalidInput) when `pm` is not the hierarchy's progressive mesh
  /// (hierarchy_to_progressive_mesh: same splits, same wings) or `dag` is not
  /// the PM's. All three must outlive the check.
  static Result<StructureCrossCheck> create(const VertexHierarchy& h, const ProgressiveMesh& pm,
                                            const VsplitDag& dag);

  /// The PM splits applied on the refiner's front (flags in split order).
  std::vector<uint8_t> refiner_splits(const SelectiveRefiner& refiner) const;
  /// The PM splits the DAG's fronts have split.
  std::vector<uint8_t> dag_splits(const DagFronts& fronts) const;
  /// Adds to `flags` every split it needs under the DAG's parents and the
  /// hierarchy's; true when nothing had to be added.
  bool close(std::vector<uint8_t>* flags) const;

  /// Problems, empty when the hierarchy's mesh and the DAG's cut for the
  /// front `flags` (closed, see close()) are the same oriented triangles:
  /// both are rebuilt from the base by splitting in PM order, and `refiner`
  /// (node ids) and `cut` (PM vertex ids), when given, are a replay's own
  /// meshes for exactly that front and must be the same too.
  std::vector<std::string> compare(const std::vector<uint8_t>& flags,
                                   const SelectiveRefiner* refiner,
                                   const std::vector<Triangle>* cut) const;

 private:
  StructureCrossCheck(const VertexHierarchy& h, const VsplitDag& dag) : h_(&h), dag_(&dag) {}
  std::vector<Triangle> in_pm_vertices(const std::vector<Triangle>& node_triangles) const;

  const VertexHierarchy* h_;
  const VsplitDag* dag_;
  SplitLineage lineage_;
  std::vector<uint32_t> node_of_split_;
  std::vector<uint32_t> split_of_node_;  // kNoVertex for leaves
  std::vector<uint32_t> pm_vertex_;      // per node
};

}  // namespace lodbake
