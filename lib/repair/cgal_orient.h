// The CGAL step of the repair: orient_polygon_soup() cuts non-manifold edges
// and vertices apart and orients every piece consistently. Internal to
// lib/repair; cgal_orient.cpp is the only translation unit of the import
// path that includes CGAL.
#pragma once

#include <cstdint>

#include "formats/support/status.h"
#include "lib/repair/repair_soup.h"

namespace lodbake {

struct OrientStats {
  uint64_t split_vertices = 0;  // distinct points CGAL duplicated
  uint64_t added_points = 0;    // copies it appended
};

/// Runs CGAL::Polygon_mesh_processing::orient_polygon_soup on `soup`,
/// keeping point origins and corner sources in step through its visitor.
/// \pre the soup has no repeated-index and no duplicate triangles (CGAL's
///      orienter asserts it).
/// Returns kRuntime when CGAL throws or memory runs out.
Status orient_soup_with_cgal(RepairSoup* soup, OrientStats* stats);

}  // namespace lodbake
