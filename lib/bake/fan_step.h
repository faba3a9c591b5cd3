// The fan-merge hierarchy step, shared by lodbake-fan and lodbake-bake so
// that both write the same bytes: one mesh's BASE and FANH (and over an
// asset's mesh its corners' wedges, WEDG), META's counts and options.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/fanh.h"
#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/fanmerge/fan_build.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_lods.h"

namespace lodbake {

struct FanStepOptions {
  bool repair = false;
  bool strict = false;
  FanBuildOptions options;
};

// What one fan build made: the sections after META (BASE, the mesh itself,
// and FANH), META's counts and the report's figures.
struct FanBuilt {
  FanBuildResult result;
  FanhStats stats;
  double seconds = 0;
  Bytes base, fanh;
  std::map<std::string, uint64_t> counts;
};

Result<FanBuilt> build_fan(const FanBuildOptions& options, const TriangleMesh& mesh);

// META (lodbake-fan and its options; input and counts are the caller's).
MetaSection fan_meta(const FanStepOptions& request);

// One mesh's group (build_asset()): BASE and FANH, META's counts.
MeshSections fan_mesh_sections(FanBuilt&& built);

// The input's corners as a fan's WEDG stores them: `corners`' wedge table,
// each wedge homed at its point, BASE's triangles' corners, no splits
// (lib/fanmerge/fan_wedges.h gives every front its wedges from these).
PmWedges fan_input_wedges(const MeshCornerWedges& corners);

// Every mesh's corners with their wedges (scene_corner_wedges(), with the
// request's repair and strict), keyed by scene mesh.
Result<std::map<uint32_t, MeshCornerWedges>> fan_asset_corners(const FanStepOptions& request,
                                                               const Scene& scene);

// One asset mesh's group: BASE, FANH and WEDG, the fan_input_wedges() of
// the scene's corners, which must be over `mesh`, the mesh built (kRuntime
// otherwise, or when the fronts' wedges do not follow: a bug, not the
// input's fault).
Result<MeshSections> fan_asset_sections(FanBuilt&& built,
                                        const std::map<uint32_t, MeshCornerWedges>& corners,
                                        uint32_t scene_mesh, const TriangleMesh& mesh);

}  // namespace lodbake
