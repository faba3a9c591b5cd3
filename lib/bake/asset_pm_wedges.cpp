#include "lib/bake/asset_pm_wedges.h"

#include <utility>
#include <vector>

#include "formats/sections/wedg.h"

namespace lodbake {

Result<AssetCorners> read_asset_corners(const Scene& scene, bool repair, bool strict) {
  LoadOptions load;
  load.repair = repair;
  load.strict = strict;
  LODBAKE_ASSIGN_OR_RETURN(std::vector<MeshCornerWedges> all, scene_corner_wedges(scene, load));
  AssetCorners corners;
  for (MeshCornerWedges& c : all)
    corners.emplace(c.mesh, std::move(c));
  return corners;
}

Result<Bytes> encode_asset_pm_wedges(const ProgressiveMesh& pm, const AssetCorners& corners,
                                     uint32_t scene_mesh, const TriangleMesh& mesh) {
  // The corners read from the scene must be over the very mesh the
  // progressive mesh was built on.
  auto found = corners.find(scene_mesh);
  if (found == corners.end() || found->second.topology.positions != mesh.positions ||
      found->second.topology.triangles != mesh.triangles)
    return runtime_error("the corners read from the scene are not over the mesh built");
  LODBAKE_ASSIGN_OR_RETURN(PmWedges wedges, wedges_of_pm(pm, found->second));
  return encode_wedg(wedges);
}

}  // namespace lodbake
