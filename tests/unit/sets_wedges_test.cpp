// The wedges of an asset's SETS levels: lodbake-strips' sections for each
// mesh of a real asset (BASE + VSPL + WEDG + SETS, strips_mesh_sections()),
// loaded as mode sets loads them. Every recovered LoD's corners have exactly
// the wedges of the progressive mesh's level (WedgeRefiner, another path
// that must agree), the full LoD is the input's corners exactly, and a WEDG
// or a VSPL that is not the structure's own is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/mesh/canonical_triangles.h"
#include "formats/sections/open_container.h"
#include "lib/bake/asset_pm_wedges.h"
#include "lib/bake/strips_step.h"
#include "lib/replay/replay_check.h"
#include "lib/replay/sets_replay.h"
#include "lib/replay/structure_loading.h"
#include "lib/simplify/wedge_replay.h"
#include "tests/unit/asset_test_support.h"

namespace lodbake {
namespace {

using test::kAssets;
using test::read_asset;

// A triangle's corners and their wedges, rotated to start at its smallest
// vertex: two meshes have the same textured triangles exactly when their
// sorted lists of these are equal.
using Corners = std::array<uint32_t, 6>;

Corners canonical_corners(const Triangle& t, const std::array<uint32_t, 3>& w) {
  int first = 0;
  for (int k = 1; k < 3; ++k)
    if (t[k] < t[first]) first = k;
  Corners out;
  for (int k = 0; k < 3; ++k) {
    out[k] = t[(first + k) % 3];
    out[3 + k] = w[(first + k) % 3];
  }
  return out;
}

std::vector<Corners> sorted_corners(const std::vector<Triangle>& triangles,
                                    const std::vector<std::array<uint32_t, 3>>& wedges) {
  std::vector<Corners> out;
  for (size_t f = 0; f < triangles.size(); ++f)
    out.push_back(canonical_corners(triangles[f], wedges[f]));
  std::sort(out.begin(), out.end());
  return out;
}

// One mesh's strips container (its group alone), as lodbake-strips writes
// the group; `replace_wedg` swaps in another WEDG payload.
Bytes strips_file(const MeshSections& built, const Bytes* replace_wedg = nullptr) {
  ContainerWriter writer;
  for (const auto& [tag, bytes] : built.sections) {
    const bool wedg = tag == kWedgTag;
    EXPECT_TRUE(
        writer.add_known_section(tag, wedg && replace_wedg != nullptr ? *replace_wedg : bytes)
            .is_ok());
  }
  Result<Bytes> file = writer.finish();
  EXPECT_TRUE(file.is_ok());
  return file.is_ok() ? std::move(file).value() : Bytes();
}

const Bytes* section(const MeshSections& built, const char* tag) {
  for (const auto& [t, bytes] : built.sections)
    if (t == tag) return &bytes;
  return nullptr;
}

class SetsWedgesTest : public testing::TestWithParam<std::string> {};

TEST_P(SetsWedgesTest, RecoveredLevelsHaveThePmLevelsWedgesAndTheFullLevelIsTheInput) {
  const Scene scene = read_asset(kAssets + GetParam());
  Result<AssetCorners> corners = read_asset_corners(scene, false, false);
  ASSERT_TRUE(corners.is_ok()) << corners.status().message();
  ASSERT_FALSE(corners.value().empty());
  for (const auto& [mesh, c] : corners.value()) {
    Result<MeshSections> built =
        strips_mesh_sections(StripsStepOptions(), corners.value(), mesh, c.topology);
    ASSERT_TRUE(built.is_ok()) << built.status().message();
    ASSERT_NE(section(built.value(), kWedgTag), nullptr);
    Result<OpenedContainer> file = open_container(strips_file(built.value()));
    ASSERT_TRUE(file.is_ok()) << file.status().message();
    Result<SetsStructure> loaded = load_sets_structure(file.value().decoded(), 0);
    ASSERT_TRUE(loaded.is_ok()) << loaded.status().message();
    const SetsStructure& s = loaded.value();
    ASSERT_TRUE(s.lookup.has_value());
    Result<SetsReplay> replay = SetsReplay::create(*s.pm, *s.graph, &*s.lookup, s.wedges.get());
    ASSERT_TRUE(replay.is_ok()) << replay.status().message();
    ASSERT_TRUE(replay.value().has_wedges());
    Result<WedgeRefiner> level = WedgeRefiner::create(*s.pm, *s.wedges);
    ASSERT_TRUE(level.is_ok()) << level.status().message();

    // Every LoD of a small graph, 40 spread ones (both ends kept) otherwise.
    const uint32_t lods = replay.value().lod_count();
    const uint32_t n = std::min<uint32_t>(lods, 40);
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t lod = n == 1 ? 0 : static_cast<uint32_t>(uint64_t{lods - 1} * i / (n - 1));
      ASSERT_TRUE(replay.value().step(lod).is_ok());
      EXPECT_TRUE(replay.value().check().empty()) << GetParam() << ", LoD " << lod;
      Result<SetsLevel> recovered = replay.value().level();
      ASSERT_TRUE(recovered.is_ok()) << recovered.status().message();
      ASSERT_EQ(recovered.value().corners.size(), recovered.value().triangles.size());
      EXPECT_TRUE(corner_wedge_problems(recovered.value().corners, *s.wedges).empty());
      ASSERT_TRUE(level.value().refine_to(s.pm->full_vertex_count() - lod).is_ok());
      EXPECT_EQ(sorted_corners(recovered.value().triangles, recovered.value().corners),
                sorted_corners(level.value().mesh().triangles, level.value().corners()))
          << GetParam() << " mesh " << mesh << ", LoD " << lod;
      if (lod != 0) continue;
      // The full LoD in the input's vertex ids: the input's triangles with
      // every corner's wedge.
      std::vector<Triangle> input;
      for (const Triangle& t : recovered.value().triangles)
        input.push_back(
            {s.pm->input_vertex[t[0]], s.pm->input_vertex[t[1]], s.pm->input_vertex[t[2]]});
      EXPECT_EQ(sorted_corners(input, recovered.value().corners),
                sorted_corners(c.topology.triangles, c.corner_wedge))
          << GetParam() << " mesh " << mesh;
    }
    EXPECT_GT(replay.value().checked_corners(), 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Assets, SetsWedgesTest,
                         testing::Values("Duck/Duck.glb", "CesiumMilkTruck/CesiumMilkTruck.gltf",
                                         "Fox/Fox.gltf", "MultiUVTest/MultiUVTest.gltf"),
                         [](const testing::TestParamInfo<std::string>& param) {
                           return param.param.substr(0, param.param.find('/'));
                         });

// The corners of a recovered LoD found against another LoD's triangles
// have no wedge, and check() says so.
TEST(SetsWedges, ATriangleTheLevelDoesNotHoldHasNoWedge) {
  const Scene scene = read_asset(kAssets + "Fox/Fox.gltf");
  Result<AssetCorners> corners = read_asset_corners(scene, false, false);
  ASSERT_TRUE(corners.is_ok());
  const auto& [mesh, c] = *corners.value().begin();
  Result<MeshSections> built =
      strips_mesh_sections(StripsStepOptions(), corners.value(), mesh, c.topology);
  ASSERT_TRUE(built.is_ok());
  Result<OpenedContainer> file = open_container(strips_file(built.value()));
  ASSERT_TRUE(file.is_ok());
  Result<SetsStructure> loaded = load_sets_structure(file.value().decoded(), 0);
  ASSERT_TRUE(loaded.is_ok());
  const SetsStructure& s = loaded.value();
  Result<SetsReplay> replay = SetsReplay::create(*s.pm, *s.graph, &*s.lookup, s.wedges.get());
  ASSERT_TRUE(replay.is_ok());
  ASSERT_TRUE(replay.value().step(0).is_ok());
  const std::vector<std::string> problems = replay.value().check(replay.value().lod_count() - 1);
  bool without = false;
  for (const std::string& p : problems)
    without = without || p.find("without a wedge") != std::string::npos;
  EXPECT_TRUE(without);
}

// The WEDG of another progressive mesh beside the strips' VSPL is refused
// when the structure loads (as mode sets and --validate load it).
TEST(SetsWedges, RefusesAWedgThatIsNotTheVsplsOwn) {
  const Scene scene = read_asset(kAssets + "Duck/Duck.glb");
  Result<AssetCorners> corners = read_asset_corners(scene, false, false);
  ASSERT_TRUE(corners.is_ok());
  const auto& [mesh, c] = *corners.value().begin();
  Result<MeshSections> built =
      strips_mesh_sections(StripsStepOptions(), corners.value(), mesh, c.topology);
  ASSERT_TRUE(built.is_ok());
  const Scene other = read_asset(kAssets + "Fox/Fox.gltf");
  Result<AssetCorners> other_corners = read_asset_corners(other, false, false);
  ASSERT_TRUE(other_corners.is_ok());
  const auto& [other_mesh, oc] = *other_corners.value().begin();
  Result<MeshSections> other_built =
      strips_mesh_sections(StripsStepOptions(), other_corners.value(), other_mesh, oc.topology);
  ASSERT_TRUE(other_built.is_ok());
  Result<OpenedContainer> swapped =
      open_container(strips_file(built.value(), section(other_built.value(), kWedgTag)));
  ASSERT_TRUE(swapped.is_ok());
  Result<SetsStructure> refused = load_sets_structure(swapped.value().decoded(), 0);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(refused.status().message().find("section WEDG"), std::string::npos);
}

// A VSPL with its own WEDG that is not the graph's own, with the same
// counts: the PM of the mesh turned inside out (the same collapses, every
// triangle reversed) has the graph's vertex and LoD counts, and its wedges
// replay with it, but the recovered triangles are not its own.
TEST(SetsWedges, RefusesAVsplThatIsNotTheGraphsOwn) {
  const Scene scene = read_asset(kAssets + "Fox/Fox.gltf");
  Result<AssetCorners> corners = read_asset_corners(scene, false, false);
  ASSERT_TRUE(corners.is_ok());
  const MeshCornerWedges& c = corners.value().begin()->second;
  Result<MeshSections> built =
      strips_mesh_sections(StripsStepOptions(), corners.value(), c.mesh, c.topology);
  ASSERT_TRUE(built.is_ok());
  Result<OpenedContainer> file = open_container(strips_file(built.value()));
  ASSERT_TRUE(file.is_ok());
  Result<SetsStructure> loaded = load_sets_structure(file.value().decoded(), 0);
  ASSERT_TRUE(loaded.is_ok());

  MeshCornerWedges flipped = c;
  for (size_t f = 0; f < flipped.topology.triangles.size(); ++f) {
    std::swap(flipped.topology.triangles[f][1], flipped.topology.triangles[f][2]);
    std::swap(flipped.corner_wedge[f][1], flipped.corner_wedge[f][2]);
  }
  Result<ProgressiveMesh> pm = record_pm(flipped.topology, nullptr);
  ASSERT_TRUE(pm.is_ok()) << pm.status().message();
  ASSERT_EQ(pm.value().splits.size(), loaded.value().pm->splits.size());
  Result<PmWedges> wedges = wedges_of_pm(pm.value(), flipped);
  ASSERT_TRUE(wedges.is_ok()) << wedges.status().message();
  Result<CornerWedges> lookup = CornerWedges::create(pm.value(), wedges.value());
  ASSERT_TRUE(lookup.is_ok()) << lookup.status().message();
  Result<SetsReplay> replay =
      SetsReplay::create(pm.value(), *loaded.value().graph, &lookup.value(), &wedges.value());
  ASSERT_FALSE(replay.is_ok());
  EXPECT_EQ(replay.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(replay.status().message().find("not the SETS graph's own"), std::string::npos)
      << replay.status().message();
  // Without wedges the replay takes it (--validate's check then fails).
  EXPECT_TRUE(SetsReplay::create(pm.value(), *loaded.value().graph).is_ok());
}

}  // namespace
}  // namespace lodbake
