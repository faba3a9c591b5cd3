// The wedges of a fan front: which attribute set (a wedge of the asset's
// mesh, WEDG beside BASE and FANH) each corner of FanRuntime's current mesh
// uses. WEDG gives the input's corners (no splits: BASE's triangles are the
// finest mesh). A front's triangle is an input triangle whose corners have
// moved up the forest, one half-edge collapse at a time; each corner's
// wedge follows the rule that gives the balanced hierarchy's progressive
// mesh its wedges (lib/simplify/pm_wedge_assignment.h): a corner moved from
// the collapsed vertex u to the centre v takes the wedge v has across the
// collapsed edge in the same chart (u's and v's wedges in the step's removed
// triangles, in list order), or keeps its wedge when u's wedge has no
// partner there (a seam that meets u away from the edge; the wedge's values
// are then used at v's position). A corner moves only along its own chain
// of centres and the lists fix which triangles each step renames, so the
// wedge is a function of (triangle, corner, vertex) computed once by
// replaying the construction: any front, whatever order reached it, has the
// same wedges, the input's corners at the finest front.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "formats/mesh/fan_hierarchy.h"
#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/fanmerge/fan_runtime.h"

namespace lodbake {

class FanWedges {
 public:
  /// `input` and `h` are the fan's BASE and FANH, `wedges` the WEDG beside
  /// them: no splits, one corner triple per input triangle, each corner's
  /// wedge homed at the corner's own vertex, a face's three wedges of one
  /// primitive; and `h`'s steps must replay over `input`. kInvalidInput
  /// naming the first problem otherwise (all three may come from a file);
  /// kRuntime on out of memory.
  static Result<FanWedges> create(const TriangleMesh& input, const FanHierarchy& h,
                                  const PmWedges& wedges);

  /// The wedge corner k of input triangle t has while it sits at `vertex`;
  /// kNoVertex when that corner never sits there (or t, k are out of range).
  uint32_t wedge(uint32_t t, int k, uint32_t vertex) const;

  /// Every corner's wedge of `runtime`'s current mesh, alive triangles in
  /// input order as mesh() lists them. kInvalidInput naming the first
  /// corner without one (a runtime over another hierarchy).
  Result<std::vector<std::array<uint32_t, 3>>> corners(const FanRuntime& runtime) const;

  /// Moves recorded: corners a construction step renamed.
  size_t move_count() const { return chain_.size() - 3 * triangle_count_; }

 private:
  FanWedges() = default;
  uint32_t triangle_count_ = 0;
  // Per corner 3t + k, its (vertex, wedge) positions in construction order,
  // the input's first: chain_[start_[c] .. start_[c + 1]).
  std::vector<uint32_t> start_;
  std::vector<std::array<uint32_t, 2>> chain_;
};

}  // namespace lodbake
