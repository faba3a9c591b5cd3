// Hoppe 1997 ("View-dependent refinement of progressive meshes") criteria as
// Kim, Lee and Kobbelt's qrefine() uses them. Choices:
// - frustum: the node's sphere against each plane (outside one plane:
//   invisible);
// - back-facing: Hoppe's test with the sphere centre at the node's
//   position: the cone faces away when (v - e).n > 0 and
//   ((v - e).n)^2 > |v - e|^2 sin^2(alpha); a cone of half-angle >= pi/2
//   never faces away;
// - screen-space error: Hoppe's formula on the squared terms, all in double.
// adapt_to_view() visits nodes in array (breadth-first) order, so a pass
// sees children after parents, as the windowed active tags of section 6.1.
#include "lib/hierarchy/view_criteria.h"

#include <cmath>

namespace lodbake {

bool qrefine(const NodeRefinement& data, const Vec3f& position, const ViewParameters& view) {
  for (const std::array<float, 4>& p : view.frustum) {
    const double s =
        double{p[0]} * position[0] + double{p[1]} * position[1] + double{p[2]} * position[2] + p[3];
    const double len = std::sqrt(double{p[0]} * p[0] + double{p[1]} * p[1] + double{p[2]} * p[2]);
    if (len > 0 && s < -double{data.radius} * len) return false;
  }
  const double vx = double{position[0]} - view.eye[0];
  const double vy = double{position[1]} - view.eye[1];
  const double vz = double{position[2]} - view.eye[2];
  const double dist2 = vx * vx + vy * vy + vz * vz;
  const double along = vx * data.cone_axis[0] + vy * data.cone_axis[1] + vz * data.cone_axis[2];
  const double sin_alpha = std::sin(std::min(double{data.cone_half_angle}, 3.14159265358979 / 2));
  if (data.cone_half_angle < 3.14159265358979 / 2 && along > 0 &&
      along * along > dist2 * sin_alpha * sin_alpha) {
    return false;
  }
  const double k2 = double{view.kappa} * view.kappa;
  if (double{data.mu2} >= k2 * dist2 && data.mu2 > 0) return true;
  return double{data.delta2} * (dist2 - along * along) >= k2 * dist2 * dist2 && data.delta2 > 0;
}

Result<AdaptStats> adapt_to_view(SelectiveRefiner* refiner, const VertexHierarchy& h,
                                 const std::vector<NodeRefinement>& data,
                                 const ViewParameters& view, size_t max_passes) {
  if (data.size() != h.node_count()) {
    return invalid_input("refinement data has " + std::to_string(data.size()) + " entries for " +
                         std::to_string(h.node_count()) + " nodes");
  }
  AdaptStats stats;
  for (bool changed = true; changed && stats.passes < max_passes;) {
    changed = false;
    ++stats.passes;
    for (uint32_t v = 0; v < h.node_count(); ++v) {
      if (!refiner->is_active(v)) continue;
      if (!h.is_leaf(v) && qrefine(data[v], h.position[v], view)) {
        std::vector<uint32_t> made;
        LODBAKE_RETURN_IF_ERROR(refiner->split_with_dependencies(v, &made));
        stats.splits += made.size();
        changed = true;
        continue;
      }
      const uint32_t p = h.parent[v];
      if (p == kNoNode || v != h.first_child[p]) continue;  // each pair once, from its left child
      if (!refiner->is_active(v + 1) || qrefine(data[p], h.position[p], view)) continue;
      if (refiner->can_collapse(p)) {
        LODBAKE_RETURN_IF_ERROR(refiner->collapse(p));
        ++stats.collapses;
        changed = true;
      }
    }
  }
  return stats;
}

}  // namespace lodbake
