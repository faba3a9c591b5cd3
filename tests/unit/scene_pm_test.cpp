// Progressive meshes with wedges on real assets: full refinement gives back
// every primitive's triangles with every attribute of every corner, every
// level is a valid textured mesh, and the level with a simplified level's
// vertex count is that level (two paths that must agree).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "formats/container/section_registry.h"
#include "formats/scene/accessor_values.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/sections/open_container.h"
#include "formats/sections/vspl.h"
#include "formats/sections/wedg.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_levels.h"
#include "lib/scene/scene_lods.h"
#include "lib/simplify/wedge_replay.h"
#include "tests/unit/asset_test_support.h"

namespace lodbake {
namespace {

using test::kAssets;
using test::read_asset;

// Every stream's bytes of one vertex (positions included).
std::string vertex_bytes(const ScenePrimitive& prim, uint32_t v) {
  std::string bytes;
  for (const SceneAttribute& a : prim.attributes) {
    const size_t size = a.data.element_size();
    bytes.append(a.semantic);
    bytes.append(reinterpret_cast<const char*>(a.data.bytes.data()) + size_t{v} * size, size);
  }
  for (const std::vector<SceneAttribute>& target : prim.targets)
    for (const SceneAttribute& a : target) {
      const size_t size = a.data.element_size();
      bytes.append(reinterpret_cast<const char*>(a.data.bytes.data()) + size_t{v} * size, size);
    }
  return bytes;
}

// A mesh's triangles as (material, corner values) triples, each rotated to
// start at its smallest corner, sorted: equal for two meshes exactly when
// they draw the same triangles with the same values, whatever the vertex
// numbering and triangle order.
std::vector<std::string> canonical(const std::vector<ScenePrimitive>& primitives) {
  std::vector<std::string> out;
  for (const ScenePrimitive& prim : primitives) {
    for (const std::array<uint32_t, 3>& t : primitive_triangles(prim)) {
      std::string c[3] = {vertex_bytes(prim, t[0]), vertex_bytes(prim, t[1]),
                          vertex_bytes(prim, t[2])};
      int first = 0;
      for (int k = 1; k < 3; ++k)
        if (c[k] < c[first]) first = k;
      out.push_back(std::to_string(prim.material) + "|" + c[first] + "|" + c[(first + 1) % 3] +
                    "|" + c[(first + 2) % 3]);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

class ScenePm : public testing::TestWithParam<std::string> {};

// Every tenth of the way a level with the input's materials; fully refined,
// the input's triangles with every corner's values; back down, the base's
// wedges.
void expect_textured_levels(const SceneMesh& mesh, uint32_t m, const ProgressiveMesh& pm,
                            const PmWedges& wedges) {
  Result<WedgeRefiner> refiner = WedgeRefiner::create(pm, wedges);
  ASSERT_TRUE(refiner.is_ok()) << refiner.status().message();
  const size_t splits = pm.splits.size();
  for (int step = 0; step <= 10; ++step) {
    ASSERT_TRUE(refiner.value().refine_to(pm.base.vertex_count() + splits * step / 10).is_ok());
    Result<std::vector<ScenePrimitive>> level =
        primitives_at_level(mesh, refiner.value().mesh(), refiner.value().corners(), wedges);
    ASSERT_TRUE(level.is_ok()) << level.status().message();
    for (const ScenePrimitive& prim : level.value()) {
      ASSERT_TRUE(prim.indices.has_value());
      for (uint32_t i : *prim.indices)
        ASSERT_LT(i, prim.vertex_count());
    }
    if (step < 10) continue;
    EXPECT_EQ(canonical(level.value()), canonical(mesh.primitives)) << "mesh " << m;
  }
  ASSERT_TRUE(refiner.value().refine_to(pm.base.vertex_count()).is_ok());
  EXPECT_EQ(refiner.value().corners(), wedges.base);
}

TEST_P(ScenePm, FullRefinementGivesEveryCornerBackAndEveryLevelIsTextured) {
  const Scene scene = read_asset(kAssets + GetParam());
  SceneLodOptions options;
  Result<std::vector<MeshPm>> pms = scene_progressive_meshes(scene, options);
  ASSERT_TRUE(pms.is_ok()) << pms.status().message();
  ASSERT_FALSE(pms.value().empty());
  for (const MeshPm& m : pms.value())
    expect_textured_levels(scene.meshes[m.mesh], m.mesh, m.pm, m.wedges);
}

// The balanced hierarchy's progressive mesh knows nothing of attributes;
// its wedges are assigned afterwards (lib/simplify/pm_wedge_assignment.h).
TEST_P(ScenePm, TheHierarchysProgressiveMeshGetsWedgesThatGiveEveryCornerBack) {
  const Scene scene = read_asset(kAssets + GetParam());
  Result<std::vector<MeshCornerWedges>> corners = scene_corner_wedges(scene, LoadOptions());
  ASSERT_TRUE(corners.is_ok()) << corners.status().message();
  ASSERT_FALSE(corners.value().empty());
  for (const MeshCornerWedges& c : corners.value()) {
    Result<BalancedHierarchy> h = build_balanced_hierarchy(c.topology, BalancedBuildOptions());
    ASSERT_TRUE(h.is_ok()) << h.status().message();
    Result<ProgressiveMesh> pm = hierarchy_to_progressive_mesh(h.value().hierarchy);
    ASSERT_TRUE(pm.is_ok()) << pm.status().message();
    Result<PmWedges> wedges = wedges_of_pm(pm.value(), c);
    ASSERT_TRUE(wedges.is_ok()) << wedges.status().message();
    expect_textured_levels(scene.meshes[c.mesh], c.mesh, pm.value(), wedges.value());
  }
}

void expect_assigned_wedges_are_recorded(const Scene& scene, const SceneLodOptions& options) {
  Result<std::vector<MeshPm>> pms = scene_progressive_meshes(scene, options);
  ASSERT_TRUE(pms.is_ok()) << pms.status().message();
  Result<std::vector<MeshCornerWedges>> corners = scene_corner_wedges(scene, options.load);
  ASSERT_TRUE(corners.is_ok()) << corners.status().message();
  ASSERT_EQ(pms.value().size(), corners.value().size());
  for (size_t i = 0; i < pms.value().size(); ++i) {
    const MeshPm& m = pms.value()[i];
    Result<PmWedges> assigned = wedges_of_pm(m.pm, corners.value()[i]);
    ASSERT_TRUE(assigned.is_ok()) << assigned.status().message();
    EXPECT_EQ(assigned.value().base, m.wedges.base) << "mesh " << m.mesh;
    EXPECT_EQ(assigned.value().added, m.wedges.added) << "mesh " << m.mesh;
    EXPECT_EQ(assigned.value().moved, m.wedges.moved) << "mesh " << m.mesh;
    EXPECT_EQ(assigned.value().wedge_home, m.wedges.wedge_home) << "mesh " << m.mesh;
  }
}

// Two paths that must agree: the wedge engine records its wedges as it
// collapses; assigning them afterwards to the PM it recorded, by the rule
// of pm_wedge_assignment.h, gives the same records, with seams locked and
// with --permissive.
TEST_P(ScenePm, AssignedWedgesAreTheEnginesOwn) {
  const Scene scene = read_asset(kAssets + GetParam());
  for (bool permissive : {false, true}) {
    SCOPED_TRACE(permissive ? "permissive" : "seams locked");
    SceneLodOptions options;
    options.simplify.permissive = permissive;
    expect_assigned_wedges_are_recorded(scene, options);
  }
}

TEST_P(ScenePm, EveryLevelsCornersAreFoundByFaceAndVertex) {
  const Scene scene = read_asset(kAssets + GetParam());
  const SceneLodOptions options;
  Result<std::vector<MeshPm>> pms = scene_progressive_meshes(scene, options);
  ASSERT_TRUE(pms.is_ok());
  for (const MeshPm& m : pms.value()) {
    Result<CornerWedges> lookup = CornerWedges::create(m.pm, m.wedges);
    ASSERT_TRUE(lookup.is_ok()) << lookup.status().message();
    Result<WedgeRefiner> refiner = WedgeRefiner::create(m.pm, m.wedges);
    ASSERT_TRUE(refiner.is_ok());
    const size_t splits = m.pm.splits.size();
    for (int step = 0; step <= 4; ++step) {
      ASSERT_TRUE(refiner.value().refine_to(m.pm.base.vertex_count() + splits * step / 4).is_ok());
      const TriangleMesh& level = refiner.value().mesh();
      for (size_t f = 0; f < level.triangles.size(); ++f)
        for (int k = 0; k < 3; ++k)
          ASSERT_EQ(lookup.value().wedge(static_cast<uint32_t>(f), level.triangles[f][k]),
                    refiner.value().corners()[f][k])
              << "mesh " << m.mesh << ", step " << step << ", face " << f;
    }
    EXPECT_EQ(
        lookup.value().wedge(static_cast<uint32_t>(m.pm.base.triangles.size() + 2 * splits), 0),
        kNoVertex);
  }
}

TEST_P(ScenePm, TheLevelAtALevelsCountIsThatLevel) {
  const Scene scene = read_asset(kAssets + GetParam());
  SceneLodOptions options;
  options.ratios = {0.5};
  Result<SceneLods> lods = simplify_scene(scene, options);
  ASSERT_TRUE(lods.is_ok()) << lods.status().message();
  options.ratios = {0.0};  // record to the end
  Result<std::vector<MeshPm>> pms = scene_progressive_meshes(scene, options);
  ASSERT_TRUE(pms.is_ok()) << pms.status().message();
  for (const MeshPm& m : pms.value()) {
    Result<WedgeRefiner> refiner = WedgeRefiner::create(m.pm, m.wedges);
    ASSERT_TRUE(refiner.is_ok());
    // Split until the triangle count is the level's.
    const std::vector<ScenePrimitive>& expected = lods.value().levels[0].meshes[m.mesh].primitives;
    size_t triangles = canonical(expected).size();
    while (refiner.value().mesh().triangle_count() < triangles)
      ASSERT_TRUE(refiner.value().split_next().is_ok());
    Result<std::vector<ScenePrimitive>> level = primitives_at_level(
        scene.meshes[m.mesh], refiner.value().mesh(), refiner.value().corners(), m.wedges);
    ASSERT_TRUE(level.is_ok());
    EXPECT_EQ(canonical(level.value()), canonical(expected)) << "mesh " << m.mesh;
  }
}

INSTANTIATE_TEST_SUITE_P(Assets, ScenePm,
                         testing::Values("Duck/Duck.glb", "CesiumMilkTruck/CesiumMilkTruck.gltf",
                                         "CesiumMan/CesiumMan.glb", "Fox/Fox.gltf",
                                         "Lantern/Lantern.gltf", "MultiUVTest/MultiUVTest.gltf",
                                         "BoxDraco/Box_Draco.glb"),
                         [](const testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param.substr(0, param.param.find('/'));
                           return name;
                         });

TEST(WedgeRefiner, RefusesWedgesThatDoNotFit) {
  const Scene scene = read_asset(kAssets + "Duck/Duck.glb");
  const SceneLodOptions defaults;
  Result<std::vector<MeshPm>> pms = scene_progressive_meshes(scene, defaults);
  ASSERT_TRUE(pms.is_ok());
  const MeshPm& m = pms.value().at(0);
  PmWedges wrong = m.wedges;
  wrong.base[0][1] = static_cast<uint32_t>(wrong.wedge_count());
  EXPECT_FALSE(WedgeRefiner::create(m.pm, wrong).is_ok());
  wrong = m.wedges;
  wrong.moved_offset.back() += 1;
  EXPECT_FALSE(WedgeRefiner::create(m.pm, wrong).is_ok());
  wrong = m.wedges;
  wrong.added.pop_back();
  EXPECT_FALSE(WedgeRefiner::create(m.pm, wrong).is_ok());
  // A split whose moved wedges name one face too few fails when applied.
  wrong = m.wedges;
  size_t split = 0;
  while (wrong.moved_offset[split + 1] == wrong.moved_offset[split])
    ++split;
  wrong.moved.erase(wrong.moved.begin() + wrong.moved_offset[split]);
  for (size_t i = split + 1; i < wrong.moved_offset.size(); ++i)
    --wrong.moved_offset[i];
  Result<WedgeRefiner> refiner = WedgeRefiner::create(m.pm, wrong);
  ASSERT_TRUE(refiner.is_ok());
  Status status = refiner.value().refine_to(m.pm.full_vertex_count());
  EXPECT_FALSE(status.is_ok());
  // A wedge table entry that is no vertex of the mesh.
  wrong = m.wedges;
  wrong.wedge_vertex[0] = 1u << 30;
  Result<WedgeRefiner> r2 = WedgeRefiner::create(m.pm, wrong);
  ASSERT_TRUE(r2.is_ok());
  Result<std::vector<ScenePrimitive>> level =
      primitives_at_level(scene.meshes[0], r2.value().mesh(), r2.value().corners(), wrong);
  // Wedge 0 may not be at the base; refine fully so every wedge is used.
  ASSERT_TRUE(r2.value().refine_to(m.pm.full_vertex_count()).is_ok());
  level = primitives_at_level(scene.meshes[0], r2.value().mesh(), r2.value().corners(), wrong);
  EXPECT_FALSE(level.is_ok());
}

}  // namespace
}  // namespace lodbake

namespace lodbake {
namespace {

// An asset container as lodbake-simplify --pm writes it, from `pms` (whose
// wedges a test may have changed).
Bytes pm_container(const Scene& scene, const std::vector<MeshPm>& pms) {
  Result<AssetBuild> built = build_asset(
      scene, make_meta("test"), LoadOptions{},
      [&](uint32_t mesh, const TriangleMesh&) -> Result<MeshSections> {
        for (const MeshPm& m : pms) {
          if (m.mesh != mesh) continue;
          MeshSections out;
          LODBAKE_ASSIGN_OR_RETURN(Bytes base, encode_base(m.pm.base, BaseEncodeOptions{}));
          LODBAKE_ASSIGN_OR_RETURN(Bytes vspl, encode_vspl(m.pm, VsplEncodeOptions{}));
          LODBAKE_ASSIGN_OR_RETURN(Bytes wedg, encode_wedg(m.wedges));
          out.sections.emplace_back(kBaseTag, std::move(base));
          out.sections.emplace_back(kVsplTag, std::move(vspl));
          out.sections.emplace_back(kWedgTag, std::move(wedg));
          return out;
        }
        return runtime_error("no progressive mesh");
      });
  EXPECT_TRUE(built.is_ok()) << built.status().message();
  return built.is_ok() ? built.value().file : Bytes();
}

TEST(SceneLevels, ValidationReplaysEveryMeshsWedges) {
  const Scene truck = read_asset(kAssets + "CesiumMilkTruck/CesiumMilkTruck.gltf");
  const SceneLodOptions options;
  Result<std::vector<MeshPm>> pms = scene_progressive_meshes(truck, options);
  ASSERT_TRUE(pms.is_ok());
  Result<OpenedContainer> good = open_container(pm_container(truck, pms.value()));
  ASSERT_TRUE(good.is_ok()) << good.status().message();
  EXPECT_TRUE(check_scene_levels(good.value().decoded(), truck).empty());
  // A level extracts with the asset's materials.
  Result<Scene> half = scene_at_level(good.value().decoded(), truck, [](const ProgressiveMesh& pm) {
    return (pm.base.vertex_count() + pm.full_vertex_count()) / 2;
  });
  ASSERT_TRUE(half.is_ok()) << half.status().message();
  EXPECT_EQ(half.value().materials, truck.materials);

  // A moved corner given another vertex's wedge: every section decodes and
  // agrees in counts, but the replay finds it.
  std::vector<MeshPm> damaged = pms.value();
  PmWedges& w = damaged[0].wedges;
  // The last moved corner: no later split moves it again.
  ASSERT_FALSE(w.moved.empty());
  const size_t last = w.moved.size() - 1;
  const uint32_t wrong = w.moved[last] == 0 ? 1 : 0;
  ASSERT_NE(w.wedge_home[wrong], w.wedge_home[w.moved[last]]);
  w.moved[last] = wrong;
  Result<OpenedContainer> bad = open_container(pm_container(truck, damaged));
  ASSERT_TRUE(bad.is_ok());
  const std::vector<std::string> findings = check_scene_levels(bad.value().decoded(), truck);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_NE(findings[0].find("mesh 0 (group"), std::string::npos) << findings[0];
}

}  // namespace
}  // namespace lodbake
