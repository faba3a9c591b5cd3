// Consistent orientation and manifold splitting with CGAL Polygon Mesh
// Processing (CGAL 5.5, orient_polygon_soup.h; the algorithm is Gueziec,
// Taubin, Lazarus, Horn, "Cutting and Stitching: Converting Sets of Polygons
// to Manifold Surfaces", 2001).
//
// What CGAL does, read from the 5.5 header: edges with more than two
// polygons are marked; a walk over the polygons reverses each one reached
// through a two-polygon edge it walks the same way as its neighbour, and
// marks the edge when that neighbour was already fixed; finally every point
// whose incident polygons form several umbrellas (cut at marked edges) gets
// one copy per extra umbrella, appended to the points. Polygons keep their
// position in the vector; a reversal is std::reverse. The visitor reports
// every reversal and every copy, which is all that is needed to keep
// attributes in step, so nothing has to be re-derived afterwards.
//
// Only the lightweight orienter header is included (no kernel, no
// Surface_mesh), which keeps this translation unit quick to compile.
#include "lib/repair/cgal_orient.h"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>

#include <exception>
#include <new>
#include <string>
#include <vector>

namespace lodbake {
namespace {

// CGAL copies the visitor, so it only holds pointers to the state.
struct TrackingVisitor : CGAL::Polygon_mesh_processing::Default_orientation_visitor {
  RepairSoup* soup = nullptr;
  std::vector<uint8_t>* split = nullptr;
  OrientStats* stats = nullptr;

  // Called just before CGAL reverses polygon `index`.
  void polygon_orientation_reversed(std::size_t index) {
    std::reverse(soup->sources[index].corner.begin(), soup->sources[index].corner.end());
  }
  // Called just before CGAL appends a copy of point `old_id` as `new_id`.
  void duplicated_vertex(std::size_t old_id, std::size_t /*new_id*/) {
    soup->point_origin.push_back(soup->point_origin[old_id]);
    if (!(*split)[old_id]) {
      (*split)[old_id] = 1;
      ++stats->split_vertices;
    }
    ++stats->added_points;
  }
};

}  // namespace

Status orient_soup_with_cgal(RepairSoup* soup, OrientStats* stats) {
  try {
    std::vector<uint8_t> split(soup->points.size(), 0);
    TrackingVisitor visitor;
    visitor.soup = soup;
    visitor.split = &split;
    visitor.stats = stats;
    CGAL::Polygon_mesh_processing::orient_polygon_soup(soup->points, soup->triangles,
                                                       CGAL::parameters::visitor(visitor));
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while orienting the mesh");
  } catch (const std::exception& e) {
    return runtime_error(std::string("CGAL failed to orient the mesh: ") + e.what());
  }
  if (soup->point_origin.size() != soup->points.size()) {
    return runtime_error("CGAL added points the repair could not track");
  }
  return Status::ok();
}

}  // namespace lodbake
