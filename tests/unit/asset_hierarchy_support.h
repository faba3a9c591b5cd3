// What the tests of an asset's hierarchy structures share: each mesh of
// the asset with its balanced hierarchy, refinement data, the hierarchy's
// progressive mesh and that PM's wedges, as lodbake-hierarchy builds them
// (a failure is a test failure, with an empty list back).
#pragma once

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/scene/scene_lods.h"

namespace lodbake::test {

struct AssetHierarchy {
  VertexHierarchy h;
  std::vector<NodeRefinement> data;
  ProgressiveMesh pm;
  PmWedges wedges;
};

// `Built` derives from AssetHierarchy (a test's own structures beside it).
template <typename Built = AssetHierarchy>
std::vector<Built> build_asset_hierarchies(const Scene& scene) {
  std::vector<Built> out;
  Result<std::vector<MeshCornerWedges>> corners = scene_corner_wedges(scene, LoadOptions());
  EXPECT_TRUE(corners.is_ok()) << corners.status().message();
  if (!corners.is_ok()) return out;
  for (const MeshCornerWedges& c : corners.value()) {
    Result<BalancedHierarchy> h = build_balanced_hierarchy(c.topology, BalancedBuildOptions());
    EXPECT_TRUE(h.is_ok()) << h.status().message();
    if (!h.is_ok()) return {};
    Built b;
    b.h = std::move(h).value().hierarchy;
    Result<std::vector<NodeRefinement>> data = compute_refinement_data(b.h, c.topology);
    Result<ProgressiveMesh> pm = hierarchy_to_progressive_mesh(b.h);
    EXPECT_TRUE(data.is_ok() && pm.is_ok());
    if (!data.is_ok() || !pm.is_ok()) return {};
    b.data = std::move(data).value();
    b.pm = std::move(pm).value();
    Result<PmWedges> wedges = wedges_of_pm(b.pm, c);
    EXPECT_TRUE(wedges.is_ok()) << wedges.status().message();
    if (!wedges.is_ok()) return {};
    b.wedges = std::move(wedges).value();
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace lodbake::test
