// Which checked meshes a tool accepts as they are. Some problems no
// algorithm can take (non-finite coordinates, non-manifold edges,
// out-of-range indices, no triangles); the rest each tool may refuse or
// tolerate through a UsePolicy. The tools that need a 2-manifold use
// UsePolicy::two_manifold() and, by default, have lib/ingest repair what it
// refuses instead of stopping (docs/mesh-check.md).
#pragma once

#include <optional>

#include "formats/support/status.h"
#include "lib/check/mesh_check.h"

namespace lodbake {

/// Problems refused on top of the ones always refused.
struct UsePolicy {
  bool refuse_non_manifold_vertices = false;
  bool refuse_inconsistent_orientation = false;
  bool refuse_degenerate_triangles = false;
  bool refuse_duplicate_triangles = false;
  bool refuse_unreferenced_vertices = false;

  /// What the edge-collapse engine and everything built on it (simplify,
  /// hierarchy, fan, strips) need: an oriented 2-manifold without
  /// degenerate or duplicate triangles. Unreferenced vertices are tolerated
  /// (the tools drop them).
  static UsePolicy two_manifold();
};

/// The first problem of the mesh checked as `report` that `policy` refuses
/// (always-refused ones included), in kAllMeshProblems order; nothing when
/// there is none. A mesh without triangles is not a MeshProblem: check
/// report.triangles separately.
std::optional<MeshProblem> first_refused_problem(const MeshCheckReport& report,
                                                 const UsePolicy& policy);

/// True when the default repair of the tools fixes `problem` without being
/// asked: everything repair_mesh() fixes except non-finite coordinates
/// (dropping the triangles around them is --repair's decision) and
/// unreferenced vertices (which the tools drop anyway).
bool fixed_by_default_repair(MeshProblem problem);

/// Ok when the mesh checked as `report` is usable under `policy`; otherwise
/// kInvalidInput with one line naming the first blocking problem (in
/// kAllMeshProblems order, after "no triangles") and its first offending
/// elements, ending in "(use --repair to fix)" when repair_mesh() fixes it.
/// Always refused: triangles with an out-of-range index, no triangles,
/// vertices with a non-finite coordinate, edges with more than two faces.
Status check_usable(const MeshCheckReport& report, const UsePolicy& policy = UsePolicy());

}  // namespace lodbake
