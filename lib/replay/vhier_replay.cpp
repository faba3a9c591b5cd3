// Mode vhier of the replay runtime. The refinement itself is
// lib/hierarchy's (adapt_to_view); this file only turns a camera into view
// parameters, times the adaptation and checks the result with
// lib/check's exact index-structure counts. Non-manifold vertices (two fans
// meeting at a vertex) are not a violation: the hierarchy's input may have
// them and the refiner keeps them.
#include "lib/replay/vhier_replay.h"

#include <chrono>
#include <new>

#include "lib/hierarchy/view_criteria.h"
#include "lib/replay/replay_check.h"

namespace lodbake {

Result<VhierFrameStats> adapt_vhier_frame(SelectiveRefiner* refiner, const VertexHierarchy& h,
                                          const std::vector<NodeRefinement>& data,
                                          const BoundingSphere& sphere, const CameraFrame& frame,
                                          const VhierReplayOptions& options) {
  if (data.size() != h.node_count()) {
    return invalid_input("refinement data has " + std::to_string(data.size()) +
                         " entries, the hierarchy " + std::to_string(h.node_count()) + " nodes");
  }
  try {
    const ViewParameters view =
        view_parameters(frame, options.viewport, options.viewport.near_fraction * sphere.radius,
                        options.tolerance_pixels);
    const auto start = std::chrono::steady_clock::now();
    LODBAKE_ASSIGN_OR_RETURN(AdaptStats adapt,
                             adapt_to_view(refiner, h, data, view, options.max_passes));
    const auto stop = std::chrono::steady_clock::now();
    VhierFrameStats stats;
    stats.splits = adapt.splits;
    stats.collapses = adapt.collapses;
    stats.passes = adapt.passes;
    stats.front_size = refiner->front_size();
    stats.triangles = refiner->triangle_count();
    stats.adapt_ms = std::chrono::duration<double, std::milli>(stop - start).count();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory adapting the vertex hierarchy");
  }
}

std::vector<std::string> check_vhier_mesh(const SelectiveRefiner& refiner) {
  const TriangleMesh mesh = refiner.current_mesh();
  std::vector<std::string> problems = triangulation_problems(mesh);
  if (mesh.vertex_count() != refiner.front_size()) {
    problems.push_back("front size " + std::to_string(refiner.front_size()) + " but the mesh has " +
                       std::to_string(mesh.vertex_count()) + " vertices");
  }
  if (mesh.triangle_count() != refiner.triangle_count()) {
    problems.push_back("triangle count " + std::to_string(refiner.triangle_count()) +
                       " but the mesh has " + std::to_string(mesh.triangle_count()) + " triangles");
  }
  return problems;
}

std::vector<std::string> check_vhier_wedges(const SelectiveRefiner& refiner,
                                            const FrontWedges& front, const PmWedges& wedges) {
  Result<std::vector<std::array<uint32_t, 3>>> corners = front.corners(refiner);
  if (!corners.is_ok()) return {corners.status().message()};
  size_t mixed = 0, first = 0;
  for (size_t f = 0; f < corners.value().size(); ++f) {
    const std::array<uint32_t, 3>& c = corners.value()[f];
    const uint32_t p = wedges.wedge_primitive[c[0]];
    if (p == wedges.wedge_primitive[c[1]] && p == wedges.wedge_primitive[c[2]]) continue;
    if (mixed++ == 0) first = f;
  }
  if (mixed == 0) return {};
  return {std::to_string(mixed) + " faces have corners of two primitives, first face " +
          std::to_string(first)};
}

}  // namespace lodbake
