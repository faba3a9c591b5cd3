// --repair: fixes what can be fixed with CGAL's Polygon Mesh Processing and
// says what it did. The only translation unit of the import path that
// includes CGAL.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

struct RepairReport {
  uint64_t removed_non_finite_triangles = 0;  // triangles touching a NaN/inf vertex
  uint64_t removed_degenerate_triangles = 0;
  uint64_t removed_duplicate_triangles = 0;
  uint64_t removed_unreferenced_vertices = 0;
  uint64_t split_non_manifold_vertices = 0;  // vertices duplicated to make fans separate
  uint64_t split_non_manifold_edges = 0;     // edges cut apart to leave at most two faces
  uint64_t flipped_triangles = 0;            // reoriented for consistent winding
  std::vector<std::string> actions() const;  // one human line per non-zero count
};

// Repairs `mesh` in place. Attributes follow their corners. Fails (kRuntime)
// only when nothing usable is left or CGAL throws.
Status repair_mesh(TriangleMesh& mesh, RepairReport* report);

}  // namespace lodbake
