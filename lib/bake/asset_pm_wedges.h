// The wedges of a progressive mesh that a builder makes over one mesh of an
// asset from its topology alone (the balanced hierarchy's, the strips'
// QEM progressive mesh): each mesh's corners read once from the scene, and
// the WEDG written beside the builder's VSPL, so that every level of that
// PM (and every structure over it) is textured and full refinement gives
// back every input corner. Shared by the hierarchy and strips steps.
#pragma once

#include <cstdint>
#include <map>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/scene/scene.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/scene/scene_lods.h"

namespace lodbake {

// Every mesh's corners with their wedges, keyed by scene mesh.
using AssetCorners = std::map<uint32_t, MeshCornerWedges>;

// scene_corner_wedges() with the builder's --repair and --strict: the same
// welded, repaired topology build_asset() hands the builder.
Result<AssetCorners> read_asset_corners(const Scene& scene, bool repair, bool strict);

// The WEDG payload of `pm`, a progressive mesh built over `mesh`, the
// topology build_asset() gave for `scene_mesh` (wedges_of_pm()). kRuntime
// when `corners` holds no corners over that very mesh.
Result<Bytes> encode_asset_pm_wedges(const ProgressiveMesh& pm, const AssetCorners& corners,
                                     uint32_t scene_mesh, const TriangleMesh& mesh);

}  // namespace lodbake
