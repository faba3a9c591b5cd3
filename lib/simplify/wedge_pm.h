// Recording a progressive mesh with wedges from the wedge engine's log:
// the PM of the points (as simplify() records one: base points first in
// increasing order, split i creating point base + i) and the wedges its
// corners take at every level (formats/mesh/pm_wedges.h).
#pragma once

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/support/status.h"
#include "lib/simplify/wedge_collapse.h"

namespace lodbake {

struct WedgePm {
  // input_vertex maps PM vertices to the wedge mesh's points; no attribute
  // streams (the wedges carry them).
  ProgressiveMesh pm;
  // The wedge ids are the wedge mesh's, wedge_home filled; the rest of the
  // wedge table (primitive, vertex) is left for the caller, who knows what
  // the wedges are.
  PmWedges wedges;
};

/// `result` must come from collapse_wedges(mesh, options) with
/// options.record and one target (the base mesh is its one level).
/// Replays the splits once to order each split's moved wedges as the
/// replay meets them; fails (kRuntime) if the log and the replay disagree.
Result<WedgePm> record_wedge_pm(const WedgeMesh& mesh, const WedgeCollapseResult& result);

}  // namespace lodbake
