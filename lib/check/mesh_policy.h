// Which checked meshes a tool accepts without --repair. Some problems no
// algorithm can take (non-finite coordinates, non-manifold edges,
// out-of-range indices, no triangles); the rest each tool may refuse or
// tolerate through a UsePolicy.
#pragma once

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
};

/// Ok when the mesh checked as `report` is usable under `policy`; otherwise
/// kInvalidInput with one line naming the first blocking problem (in
/// kAllMeshProblems order, after "no triangles") and its first offending
/// elements, ending in "(use --repair to fix)" when repair_mesh() fixes it.
/// Always refused: triangles with an out-of-range index, no triangles,
/// vertices with a non-finite coordinate, edges with more than two faces.
Status check_usable(const MeshCheckReport& report, const UsePolicy& policy = UsePolicy());

}  // namespace lodbake
