// Building the DAG of vertex splits (Zheng & Chan 2006, section 3) from a
// progressive mesh, and the triangle lineage its cuts are read from.
// Definitions and choices: docs/hierarchy-dag-vtrees.md.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vsplit_dag.h"
#include "formats/support/status.h"

namespace lodbake {

/// Every triangle that ever exists while a PM is refined in split order, with
/// the split that creates it and the split that changes it. A split changes
/// the faces it moves from vs to vt (they become new triangles with vt) and
/// adds one or two; it never touches a triangle otherwise.
struct SplitLineage {
  uint32_t base_vertex_count = 0;
  /// Base triangles first (in BASE order), then each split's, in split order:
  /// the moved faces' new versions, then (vs, vt, vl), then (vt, vs, vr).
  std::vector<Triangle> triangles;
  /// Split i creates triangles [created_offsets[i], created_offsets[i + 1]);
  /// created_offsets[0] is the base triangle count. splits + 1 entries.
  std::vector<uint32_t> created_offsets;
  /// The split that changes each triangle, or kNoVertex when none does (it
  /// is in the fully refined mesh).
  std::vector<uint32_t> changed_by;
  /// The progressive mesh's face slot of each triangle (PmRefiner's: base
  /// triangles, then each split's added faces): a moved face's new version
  /// keeps its slot, so corners find their wedges (CornerWedges).
  std::vector<uint32_t> face_slot;
  /// Split i's dependencies before transitive reduction, CSR like
  /// VsplitDag: the creators of the triangles it changes and of the
  /// boundary half-edges it changes (see build_split_lineage()).
  std::vector<uint32_t> dependency_offsets;
  std::vector<uint32_t> dependencies;

  size_t split_count() const { return created_offsets.empty() ? 0 : created_offsets.size() - 1; }
};

/// Replays `pm` in split order and records the lineage. A boundary
/// half-edge (a directed edge without a face whose twin has one) counts as a
/// triangle to a virtual vertex at infinity, so a split that changes it (glues
/// a face on it, or moves it from vs to vt) depends on the split that created
/// it; with that, every split, including one on the boundary, replaces a set
/// of (real or virtual) triangles by another set with the same outline.
/// \return kInvalidInput when a record does not fit the mesh (the errors of
///         PmRefiner::split_next()), kRuntime when memory runs out.
/// With `dependencies_only`, triangles, changed_by and face_slot stay empty
/// (what reduce_dependencies() reads is the same).
Result<SplitLineage> build_split_lineage(const ProgressiveMesh& pm, bool dependencies_only = false);

/// The transitive reduction of the lineage's dependencies: node i keeps
/// parent p unless p is an ancestor of another of i's parents.
Result<VsplitDag> reduce_dependencies(const SplitLineage& lineage);

/// build_split_lineage() then reduce_dependencies().
Result<VsplitDag> build_vsplit_dag(const ProgressiveMesh& pm);

}  // namespace lodbake
