// The wedges of a progressive mesh that was not recorded with them: any
// PM whose full mesh is a mesh with per-corner wedges (the balanced
// hierarchy's, lib/hierarchy/hierarchy_to_pm.h, whose collapses know
// nothing of attributes) gets the PmWedges that make every level a
// textured mesh and give back every input corner at full refinement.
//
// The rule, from the full mesh down, collapse by collapse: a face's corner
// keeps its wedge while its vertex stays; a corner that a collapse moves
// from vt to vs takes the wedge vs has in the same chart, read across the
// collapsed edge (the wedges of vt and vs in the wing face (vs, vt, vl),
// then in (vt, vs, vr)); a wedge of vt with no partner across the edge (a
// seam that meets vt away from the edge) keeps its values at vs's
// position, as a permissive collapse of the wedge engine leaves it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

/// `triangles` (over the points that pm.input_vertex names) with
/// `corner_wedge` per corner is the mesh `pm` refines to; `wedge_point`
/// gives each wedge's point. Returns the wedges' PM homes, base corners,
/// added and moved records; wedge_primitive and wedge_vertex are left for
/// the caller. Fails (kRuntime) when the full mesh is not those triangles,
/// each once, or a record does not replay.
Result<PmWedges> assign_pm_wedges(const ProgressiveMesh& pm, const std::vector<Triangle>& triangles,
                                  const std::vector<std::array<uint32_t, 3>>& corner_wedge,
                                  const std::vector<uint32_t>& wedge_point);

}  // namespace lodbake
