// repair_mesh(): the --repair pipeline. Index-level removals first (they
// change which edges and fans exist), then CGAL's orientation with manifold
// splitting, then the orientation choice per piece, then unreferenced
// vertices, and finally check_mesh() as a postcondition, so that a repaired
// mesh is never handed on with a problem the repair claims to fix.
//
// Zero-area triangles are deleted rather than removed by edge collapses and
// flips (PMP::remove_degenerate_faces): deletion keeps every other triangle
// and vertex as it is and keeps attributes trivially exact, at the price of
// a zero-width crack where a sliver sat between two neighbours; the crack
// shows up as boundary edges in the check that follows.
#include "lib/repair/mesh_repair.h"

#include <exception>
#include <new>
#include <string>
#include <utility>

#include "lib/check/mesh_check.h"
#include "lib/repair/cgal_orient.h"
#include "lib/repair/repair_soup.h"

namespace lodbake {
namespace {

std::string count_text(uint64_t count, const char* singular, const char* plural_form) {
  return std::to_string(count) + " " + (count == 1 ? singular : plural_form);
}

Status repair(TriangleMesh& mesh, RepairReport* report, MeshCheckReport* check_after,
              const PartRunner& run_parts) {
  RepairReport r;
  SoupRemovals removals;
  LODBAKE_ASSIGN_OR_RETURN(RepairSoup soup, build_clean_soup(mesh, &removals));
  r.removed_non_finite_triangles = removals.non_finite;
  r.removed_degenerate_triangles = removals.degenerate;
  r.removed_duplicate_triangles = removals.duplicate;
  if (soup.triangles.empty()) {
    std::string removed;
    auto add = [&removed](uint64_t count, const char* singular, const char* plural_form) {
      if (count == 0) return;
      removed += (removed.empty() ? "" : ", ") + count_text(count, singular, plural_form);
    };
    add(removals.non_finite, "triangle touching a non-finite vertex",
        "triangles touching a non-finite vertex");
    add(removals.degenerate, "degenerate triangle", "degenerate triangles");
    add(removals.duplicate, "duplicate triangle", "duplicate triangles");
    if (removed.empty()) return invalid_input("the mesh has no triangles");
    return invalid_input("no triangle is left after repair: removed " + removed);
  }

  // Most inputs only need the removals: when the cleaned soup is already a
  // consistently oriented 2-manifold, CGAL's orientation would reverse no
  // triangle and copy no point, and choose_piece_orientation() would flip
  // nothing, so the mesh written straight from the soup is the result, and
  // its check (needed anyway as the postcondition) says so. Skipping CGAL
  // here takes the dragon's import from seconds to a fraction of one.
  TriangleMesh repaired;
  LODBAKE_ASSIGN_OR_RETURN(r.removed_unreferenced_vertices, soup_to_mesh(&soup, mesh, &repaired));
  MeshCheckReport after = check_mesh(repaired, run_parts);
  if (after.non_manifold_edges != 0 || after.non_manifold_vertices != 0 ||
      after.inconsistent_orientation_edges != 0) {
    r.split_non_manifold_edges = count_non_manifold_edges(soup);
    OrientStats orient_stats;
    LODBAKE_RETURN_IF_ERROR(orient_soup_with_cgal(&soup, &orient_stats));
    r.split_non_manifold_vertices = orient_stats.split_vertices;
    r.added_vertices = orient_stats.added_points;
    choose_piece_orientation(&soup);
    for (size_t t = 0; t < soup.triangles.size(); ++t) {
      if (soup.reversed(t)) ++r.flipped_triangles;
    }
    LODBAKE_ASSIGN_OR_RETURN(r.removed_unreferenced_vertices, soup_to_mesh(&soup, mesh, &repaired));
    after = check_mesh(repaired, run_parts);
  }
  if (after.inconsistent_orientation_edges != 0 && after.non_manifold_edges == 0 &&
      after.non_manifold_vertices == 0) {
    // CGAL cuts an orientation conflict only where the cut separates fans;
    // inside a non-orientable piece (a Moebius band with interior vertices)
    // the conflict stays.
    return invalid_input("the mesh is not orientable: " +
                         count_text(after.inconsistent_orientation_edges, "edge", "edges") +
                         " keep inconsistent orientation after repair");
  }
  if (after.has_problems()) {
    return runtime_error("repair left a problem: " + after.problems().front());
  }
  mesh = std::move(repaired);
  if (report != nullptr) *report = r;
  if (check_after != nullptr) *check_after = std::move(after);
  return Status::ok();
}

}  // namespace

bool RepairReport::changed() const {
  return removed_non_finite_triangles != 0 || removed_degenerate_triangles != 0 ||
         removed_duplicate_triangles != 0 || removed_unreferenced_vertices != 0 ||
         split_non_manifold_edges != 0 || split_non_manifold_vertices != 0 || added_vertices != 0 ||
         flipped_triangles != 0;
}

std::vector<std::string> RepairReport::actions() const {
  std::vector<std::string> lines;
  if (removed_non_finite_triangles != 0) {
    lines.push_back("removed " + count_text(removed_non_finite_triangles, "triangle", "triangles") +
                    " touching a vertex with a non-finite coordinate");
  }
  if (removed_degenerate_triangles != 0) {
    lines.push_back(
        "removed " +
        count_text(removed_degenerate_triangles, "degenerate triangle", "degenerate triangles") +
        " (repeated vertex or zero area)");
  }
  if (removed_duplicate_triangles != 0) {
    lines.push_back("removed " + count_text(removed_duplicate_triangles, "duplicate triangle",
                                            "duplicate triangles"));
  }
  if (split_non_manifold_edges != 0) {
    lines.push_back(
        "cut apart " +
        count_text(split_non_manifold_edges, "non-manifold edge", "non-manifold edges") +
        " (more than two faces)");
  }
  if (split_non_manifold_vertices != 0) {
    lines.push_back("split " + count_text(split_non_manifold_vertices, "vertex", "vertices") +
                    " whose faces form separate fans, adding " +
                    count_text(added_vertices, "vertex", "vertices"));
  }
  if (flipped_triangles != 0) {
    lines.push_back("flipped " + count_text(flipped_triangles, "triangle", "triangles") +
                    " for consistent orientation");
  }
  if (removed_unreferenced_vertices != 0) {
    lines.push_back("removed " + count_text(removed_unreferenced_vertices, "unreferenced vertex",
                                            "unreferenced vertices"));
  }
  return lines;
}

Status repair_mesh(TriangleMesh& mesh, RepairReport* report, MeshCheckReport* check_after,
                   const PartRunner& run_parts) {
  try {
    return repair(mesh, report, check_after, run_parts);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while repairing the mesh");
  } catch (const std::exception& e) {
    return runtime_error(std::string("mesh repair failed: ") + e.what());
  }
}

}  // namespace lodbake
