// The wedges of the balanced hierarchy's selective fronts on real assets:
// every corner of every front has one, a face's three corners name one
// primitive, a front that is a level of the hierarchy's progressive mesh
// has that level's wedges (two paths that must agree), and the finest front
// is the input with every corner's values.
#include "lib/hierarchy/front_wedges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/scene/scene_lods.h"
#include "tests/unit/asset_test_support.h"

namespace lodbake {
namespace {

using test::kAssets;
using test::read_asset;

struct Built {
  BalancedHierarchy h;
  ProgressiveMesh pm;
  std::vector<uint32_t> order;
  PmWedges wedges;
};

std::vector<Built> build_all(const Scene& scene, std::vector<uint32_t>* meshes) {
  std::vector<Built> out;
  Result<std::vector<MeshCornerWedges>> corners = scene_corner_wedges(scene, LoadOptions());
  EXPECT_TRUE(corners.is_ok()) << corners.status().message();
  if (!corners.is_ok()) return out;
  for (const MeshCornerWedges& c : corners.value()) {
    Result<BalancedHierarchy> h = build_balanced_hierarchy(c.topology, BalancedBuildOptions());
    EXPECT_TRUE(h.is_ok()) << h.status().message();
    if (!h.is_ok()) return {};
    Built b{std::move(h).value(), {}, {}, {}};
    Result<ProgressiveMesh> pm = hierarchy_to_progressive_mesh(b.h.hierarchy, &b.order);
    EXPECT_TRUE(pm.is_ok());
    if (!pm.is_ok()) return {};
    b.pm = std::move(pm).value();
    Result<PmWedges> wedges = wedges_of_pm(b.pm, c);
    EXPECT_TRUE(wedges.is_ok()) << wedges.status().message();
    if (!wedges.is_ok()) return {};
    b.wedges = std::move(wedges).value();
    out.push_back(std::move(b));
    meshes->push_back(c.mesh);
  }
  return out;
}

// Every corner has a wedge and a face's corners one primitive.
void expect_front_textured(const FrontWedges& front, const SelectiveRefiner& refiner,
                           const PmWedges& wedges) {
  Result<std::vector<std::array<uint32_t, 3>>> corners = front.corners(refiner);
  ASSERT_TRUE(corners.is_ok()) << corners.status().message();
  for (const std::array<uint32_t, 3>& c : corners.value()) {
    ASSERT_EQ(wedges.wedge_primitive[c[0]], wedges.wedge_primitive[c[1]]);
    ASSERT_EQ(wedges.wedge_primitive[c[0]], wedges.wedge_primitive[c[2]]);
  }
}

class FrontWedgesTest : public testing::TestWithParam<std::string> {};

TEST_P(FrontWedgesTest, PmOrderFrontsHaveTheLevelsWedges) {
  const Scene scene = read_asset(kAssets + GetParam());
  std::vector<uint32_t> meshes;
  for (const Built& b : build_all(scene, &meshes)) {
    const VertexHierarchy& h = b.h.hierarchy;
    Result<FrontWedges> front = FrontWedges::create(h, b.pm, b.wedges);
    ASSERT_TRUE(front.is_ok()) << front.status().message();
    Result<SelectiveRefiner> refiner = SelectiveRefiner::create(h);
    ASSERT_TRUE(refiner.is_ok());
    Result<WedgeRefiner> level = WedgeRefiner::create(b.pm, b.wedges);
    ASSERT_TRUE(level.is_ok());
    const size_t steps = 8;
    for (size_t step = 0; step <= steps; ++step) {
      const size_t splits = b.order.size() * step / steps;
      while (level.value().refiner().applied_splits() < splits) {
        ASSERT_TRUE(
            refiner.value().split(b.order[level.value().refiner().applied_splits()]).is_ok());
        ASSERT_TRUE(level.value().split_next().is_ok());
      }
      // The same faces (by slot) with the same corners' wedges.
      Result<std::vector<std::array<uint32_t, 3>>> corners = front.value().corners(refiner.value());
      ASSERT_TRUE(corners.is_ok()) << corners.status().message();
      const std::vector<Triangle> faces = refiner.value().triangles();
      std::vector<std::array<uint32_t, 4>> ours, theirs;
      for (size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k)
          ours.push_back({front.value().pm_vertex(faces[f][k]), corners.value()[f][k], 0, 0});
      const TriangleMesh& m = level.value().mesh();
      for (size_t f = 0; f < m.triangles.size(); ++f)
        for (int k = 0; k < 3; ++k)
          theirs.push_back({m.triangles[f][k], level.value().corners()[f][k], 0, 0});
      std::sort(ours.begin(), ours.end());
      std::sort(theirs.begin(), theirs.end());
      ASSERT_EQ(ours, theirs) << GetParam() << ", " << splits << " splits";
    }
  }
}

TEST_P(FrontWedgesTest, ViewDependentFrontsAreTexturedAndTheFinestIsTheInput) {
  const Scene scene = read_asset(kAssets + GetParam());
  std::vector<uint32_t> meshes;
  std::vector<Built> all = build_all(scene, &meshes);
  for (size_t i = 0; i < all.size(); ++i) {
    const Built& b = all[i];
    const VertexHierarchy& h = b.h.hierarchy;
    Result<FrontWedges> front = FrontWedges::create(h, b.pm, b.wedges);
    ASSERT_TRUE(front.is_ok()) << front.status().message();
    Result<SelectiveRefiner> refiner = SelectiveRefiner::create(h);
    ASSERT_TRUE(refiner.is_ok());
    // Random splits (with their dependencies) and collapses: fronts no
    // level of the PM has, coarser on one side than the PM order made it.
    std::mt19937 random(5);
    for (int round = 0; round < 6; ++round) {
      for (int k = 0; k < 300; ++k) {
        const auto node = static_cast<uint32_t>(random() % h.node_count());
        if (refiner.value().is_active(node) && !h.is_leaf(node)) {
          ASSERT_TRUE(refiner.value().split_with_dependencies(node).is_ok());
        } else if (!h.is_leaf(node) && refiner.value().can_collapse(node)) {
          ASSERT_TRUE(refiner.value().collapse(node).is_ok());
        }
      }
      expect_front_textured(front.value(), refiner.value(), b.wedges);
    }
    // Every leaf: the input's triangles with every corner's values.
    for (uint32_t node = 0; node < h.node_count(); ++node) {
      if (refiner.value().is_active(node) && !h.is_leaf(node)) {
        ASSERT_TRUE(refiner.value().split_with_dependencies(node).is_ok());
      }
    }
    for (uint32_t node = 0; node < h.node_count(); ++node)
      ASSERT_TRUE(!refiner.value().is_active(node) || h.is_leaf(node));
    Result<std::vector<std::array<uint32_t, 3>>> corners = front.value().corners(refiner.value());
    ASSERT_TRUE(corners.is_ok()) << corners.status().message();
    TriangleMesh level;
    level.positions.resize(b.pm.full_vertex_count());
    for (uint32_t node = 0; node < h.node_count(); ++node)
      if (h.is_leaf(node)) level.positions[front.value().pm_vertex(node)] = h.position[node];
    for (const Triangle& t : refiner.value().triangles())
      level.triangles.push_back({front.value().pm_vertex(t[0]), front.value().pm_vertex(t[1]),
                                 front.value().pm_vertex(t[2])});
    Result<WedgeRefiner> full = WedgeRefiner::create(b.pm, b.wedges);
    ASSERT_TRUE(full.is_ok());
    ASSERT_TRUE(full.value().refine_to(b.pm.full_vertex_count()).is_ok());
    std::vector<std::array<uint32_t, 6>> ours, theirs;
    for (size_t f = 0; f < level.triangles.size(); ++f) {
      const Triangle& t = level.triangles[f];
      ours.push_back(
          {t[0], t[1], t[2], corners.value()[f][0], corners.value()[f][1], corners.value()[f][2]});
    }
    const TriangleMesh& m = full.value().mesh();
    for (size_t f = 0; f < m.triangles.size(); ++f) {
      const Triangle& t = m.triangles[f];
      const std::array<uint32_t, 3>& c = full.value().corners()[f];
      theirs.push_back({t[0], t[1], t[2], c[0], c[1], c[2]});
    }
    std::sort(ours.begin(), ours.end());
    std::sort(theirs.begin(), theirs.end());
    EXPECT_EQ(ours, theirs) << "mesh " << meshes[i];
  }
}

TEST(FrontWedges, RefusesAProgressiveMeshThatIsNotTheHierarchysOwn) {
  const Scene scene = read_asset(kAssets + "Duck/Duck.glb");
  std::vector<uint32_t> meshes;
  std::vector<Built> all = build_all(scene, &meshes);
  ASSERT_FALSE(all.empty());
  Built& b = all.front();
  ProgressiveMesh other = b.pm;
  std::swap(other.splits[3].vl, other.splits[3].vr);
  Result<FrontWedges> front = FrontWedges::create(b.h.hierarchy, other, b.wedges);
  ASSERT_FALSE(front.is_ok());
  EXPECT_EQ(front.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(front.status().message().find("not the hierarchy's"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Assets, FrontWedgesTest,
                         testing::Values("Duck/Duck.glb", "CesiumMilkTruck/CesiumMilkTruck.gltf",
                                         "CesiumMan/CesiumMan.glb", "Fox/Fox.gltf",
                                         "MultiUVTest/MultiUVTest.gltf"),
                         [](const testing::TestParamInfo<std::string>& param) {
                           return param.param.substr(0, param.param.find('/'));
                         });

}  // namespace
}  // namespace lodbake
