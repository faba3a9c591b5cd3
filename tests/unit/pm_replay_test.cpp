// The recorded progressive mesh replays back to the input exactly, every
// sampled LoD is a clean manifold mesh with the triangle count the records
// imply, the refiner undoes splits, and malformed records give a Status.
#include "lib/simplify/pm_replay.h"

#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "lib/check/mesh_check.h"
#include "lib/simplify/simplify.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

ProgressiveMesh record(const TriangleMesh& mesh, Placement placement, bool height_guard = false) {
  SimplifyOptions options;
  options.record_pm = true;
  options.placement = placement;
  options.height_guard = height_guard;
  return take(simplify(mesh, options), "simplify").pm.value_or(ProgressiveMesh());
}

void expect_clean(const TriangleMesh& mesh, const std::string& what) {
  const MeshCheckReport r = check_mesh(mesh);
  EXPECT_EQ(r.non_manifold_edges, 0u) << what;
  EXPECT_EQ(r.non_manifold_vertices, 0u) << what;
  EXPECT_EQ(r.inconsistent_orientation_edges, 0u) << what;
  EXPECT_EQ(r.degenerate_triangles, 0u) << what;
  EXPECT_EQ(r.duplicate_triangles, 0u) << what;
}

// Each mesh without and with the height guard.
class PmReplayOnSharedMesh : public ::testing::TestWithParam<std::tuple<const char*, bool>> {};

TEST_P(PmReplayOnSharedMesh, FullRefinementIsTheInputAndEveryPrefixIsClean) {
  const char* name = std::get<0>(GetParam());
  TriangleMesh input = load_clean_mesh(name);
  ASSERT_GT(input.triangles.size(), 0u);
  // Per-corner attributes (spot's) cannot go into a PM; this test is about
  // connectivity and positions.
  input.normals = MeshAttribute();
  input.texcoords = MeshAttribute();
  const ProgressiveMesh pm = record(input, Placement::kHalf, std::get<1>(GetParam()));
  ASSERT_EQ(pm.full_vertex_count(), input.positions.size());
  // Simplified as far as legal: the base is small.
  EXPECT_LT(pm.base.triangles.size(), input.triangles.size() / 4 + 8);
  expect_clean(pm.base, "base");

  Result<PmRefiner> refiner = PmRefiner::create(pm);
  ASSERT_TRUE(refiner.is_ok()) << refiner.status().message();
  PmRefiner& r = refiner.value();
  const size_t splits = pm.splits.size();
  const size_t samples = 9;
  size_t next_sample = 1;
  size_t expected_triangles = pm.base.triangles.size();
  for (size_t i = 0; i < splits; ++i) {
    const Status status = r.split_next();
    ASSERT_TRUE(status.is_ok()) << status.message();
    const VertexSplit& s = pm.splits[i];
    expected_triangles += (s.vl != kNoVertex) + (s.vr != kNoVertex);
    ASSERT_EQ(r.mesh().triangles.size(), expected_triangles);
    if (i + 1 == next_sample * splits / samples) {
      ++next_sample;
      expect_clean(r.mesh(), std::string(name) + " after " + std::to_string(i + 1));
    }
  }
  ASSERT_TRUE(r.fully_refined());
  Result<TriangleMesh> mapped = map_to_input(pm, r.mesh());
  ASSERT_TRUE(mapped.is_ok()) << mapped.status().message();
  EXPECT_EQ(mapped.value().positions, input.positions);
  EXPECT_TRUE(same_oriented_triangles(mapped.value(), input));
}

INSTANTIATE_TEST_SUITE_P(
    SharedMeshes, PmReplayOnSharedMesh,
    ::testing::Combine(::testing::Values("cgal_tetrahedron.off", "cgal_cube_quad.off",
                                         "igl_decimated-knight.off", "npm_bunny.obj",
                                         "cgal_mushroom.off", "cgal_elephant.off", "c3d_spot.obj",
                                         "cgal_knot2.off", "cgal_fandisk.off", "igl_camelhead.off",
                                         "stanford_bun_zipper.ply", "cgal_elephant-with-holes.off",
                                         "cgal_blobby_3cc.off", "cgal_mpi.off", "igl_fertility.off",
                                         "cgal_cheese.off", "cgal_camel.off",
                                         "cgal_ChineseDragon-10kv.off", "c3d_rocker-arm.obj"),
                       ::testing::Bool()));

TEST(PmReplay, OptimalPlacementReplaysExactly) {
  const TriangleMesh input = load_clean_mesh("cgal_mushroom.off");
  const ProgressiveMesh pm = record(input, Placement::kOptimal);
  Result<TriangleMesh> full = mesh_at_lod(pm, pm.full_vertex_count());
  ASSERT_TRUE(full.is_ok()) << full.status().message();
  Result<TriangleMesh> mapped = map_to_input(pm, full.value());
  ASSERT_TRUE(mapped.is_ok());
  EXPECT_EQ(mapped.value().positions, input.positions);
  EXPECT_TRUE(same_oriented_triangles(mapped.value(), input));
  // Optimal placement moved the base vertices off the input positions.
  size_t moved = 0;
  for (size_t v = 0; v < pm.base.positions.size(); ++v) {
    moved += pm.base.positions[v] != input.positions[pm.input_vertex[v]];
  }
  EXPECT_GT(moved, 0u);
}

TEST(PmReplay, CollapseUndoesSplits) {
  const TriangleMesh input = load_clean_mesh("igl_decimated-knight.off");
  const ProgressiveMesh pm = record(input, Placement::kOptimal);
  Result<PmRefiner> refiner = PmRefiner::create(pm);
  ASSERT_TRUE(refiner.is_ok());
  PmRefiner& r = refiner.value();
  const size_t mid = pm.base.positions.size() + pm.splits.size() / 2;
  ASSERT_TRUE(r.refine_to(mid).is_ok());
  const TriangleMesh at_mid = r.mesh();
  ASSERT_TRUE(r.refine_to(pm.full_vertex_count()).is_ok());
  ASSERT_TRUE(r.refine_to(pm.base.positions.size()).is_ok());
  EXPECT_EQ(r.mesh(), pm.base);
  ASSERT_TRUE(r.refine_to(mid).is_ok());
  EXPECT_EQ(r.mesh(), at_mid);
  Result<TriangleMesh> direct = mesh_at_lod(pm, mid);
  ASSERT_TRUE(direct.is_ok());
  EXPECT_EQ(direct.value(), at_mid);
  EXPECT_FALSE(mesh_at_lod(pm, pm.full_vertex_count() + 1).is_ok());
  EXPECT_FALSE(mesh_at_lod(pm, pm.base.positions.size() - 1).is_ok());
}

TEST(PmReplay, MalformedRecordsAreRefused) {
  const TriangleMesh input = load_clean_mesh("igl_decimated-knight.off");
  const ProgressiveMesh good = record(input, Placement::kHalf);
  ASSERT_GT(good.splits.size(), 10u);
  const size_t full = good.full_vertex_count();
  const uint32_t n0 = static_cast<uint32_t>(good.base.positions.size());
  auto fails = [&](ProgressiveMesh pm) { return !mesh_at_lod(pm, full).is_ok(); };
  {
    ProgressiveMesh pm = good;
    pm.splits[0].vs = n0;  // the vertex does not exist yet
    EXPECT_TRUE(fails(pm));
  }
  {
    ProgressiveMesh pm = good;
    pm.splits[3].vl = pm.splits[3].vr = kNoVertex;
    EXPECT_TRUE(fails(pm));
  }
  {
    ProgressiveMesh pm = good;
    pm.splits[5].vl = pm.splits[5].vs;
    EXPECT_TRUE(fails(pm));
  }
  {
    ProgressiveMesh pm = good;
    pm.splits[7].vr = static_cast<uint32_t>(n0 + 7 + 1);  // created by a later split
    EXPECT_TRUE(fails(pm));
  }
  {
    ProgressiveMesh pm = good;
    pm.input_vertex.pop_back();
    EXPECT_TRUE(fails(pm));
  }
  {
    ProgressiveMesh pm = good;
    pm.base.triangles[0][1] = n0;
    EXPECT_TRUE(fails(pm));
  }
  {
    ProgressiveMesh pm = good;
    pm.input_vertex[1] = pm.input_vertex[0];
    Result<TriangleMesh> refined = mesh_at_lod(pm, full);
    ASSERT_TRUE(refined.is_ok());
    EXPECT_FALSE(map_to_input(pm, refined.value()).is_ok());
  }
  // Arbitrary corruption never crashes (ASan checks the accesses): the
  // refiner either refuses a record or produces some mesh.
  uint64_t state = 12345;
  auto next = [&]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<uint32_t>(state >> 33);
  };
  size_t refused = 0;
  for (int round = 0; round < 200; ++round) {
    ProgressiveMesh pm = good;
    for (int k = 0; k < 3; ++k) {
      VertexSplit& s = pm.splits[next() % pm.splits.size()];
      const uint32_t value = next() % 3 == 0 ? kNoVertex : next() % static_cast<uint32_t>(full);
      switch (next() % 3) {
        case 0:
          s.vs = value;
          break;
        case 1:
          s.vl = value;
          break;
        default:
          s.vr = value;
          break;
      }
    }
    refused += fails(pm);
  }
  EXPECT_GT(refused, 0u);
}

}  // namespace
}  // namespace lodbake
