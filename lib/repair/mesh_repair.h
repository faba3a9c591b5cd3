// --repair: fixes what can be fixed with CGAL's Polygon Mesh Processing and
// says what it did. CGAL appears in one translation unit of this module
// (cgal_orient.cpp); the rest is plain index work.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/check/mesh_check.h"

namespace lodbake {

struct RepairReport {
  uint64_t removed_non_finite_triangles = 0;   // triangles touching a NaN/inf vertex
  uint64_t removed_degenerate_triangles = 0;   // repeated index or exactly zero area
  uint64_t removed_duplicate_triangles = 0;    // same vertex set as an earlier one, either winding
  uint64_t removed_unreferenced_vertices = 0;  // unused at the end, whether unused in the input
                                               // or left unused by removed triangles
  uint64_t split_non_manifold_edges = 0;       // edges with more than two faces, cut apart
  uint64_t split_non_manifold_vertices = 0;    // vertices duplicated so each fan has its own
  uint64_t added_vertices = 0;                 // copies made by those splits
  uint64_t flipped_triangles = 0;              // reoriented for consistent winding

  bool changed() const;
  std::vector<std::string> actions() const;  // one human line per non-zero count
};

/// Repairs `mesh` in place, in this order: drop triangles touching a
/// non-finite vertex, drop degenerate triangles (repeated index or exactly
/// zero area, the same exact test as check_mesh), drop duplicate triangles
/// (the first copy stays), cut non-manifold edges and vertices apart and
/// orient consistently (CGAL::Polygon_mesh_processing::orient_polygon_soup),
/// drop unreferenced vertices. Afterwards check_mesh() reports none of
/// those problems. Triangles keep their input order, vertices theirs (copies
/// made by splits are appended). Per-vertex attributes follow their
/// vertices (copies get the value of their original), per-corner attributes
/// follow their corners, also through flips. Same input, same output.
///
/// Within a connected piece whose winding had to change, the orientation
/// kept is the outward one when the piece is closed (positive signed
/// volume), otherwise the one that flips fewer input triangles.
///
/// On failure `mesh` is left unchanged. Fails with kInvalidInput when an
/// index or attribute is out of range, when the mesh has 2^32 or more
/// vertices, when no triangle is left, or when a piece is not orientable;
/// with kRuntime when CGAL throws or memory runs out. `check_after`, when
/// given, receives check_mesh() of the repaired mesh, which the repair
/// computes anyway as its postcondition; the check hands its parts to
/// `run_parts` (as check_mesh()).
Status repair_mesh(TriangleMesh& mesh, RepairReport* report, MeshCheckReport* check_after = nullptr,
                   const PartRunner& run_parts = nullptr);

}  // namespace lodbake
