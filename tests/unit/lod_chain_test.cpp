#include "lib/simplify/lod_chain.h"

#include <gtest/gtest.h>

#include "lib/check/mesh_check.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "tests/unit/simplify_test_meshes.h"

namespace lodbake {
namespace {

ProgressiveMesh record(const TriangleMesh& mesh, double ratio) {
  SimplifyOptions options;
  options.target_ratio = ratio;
  options.record_pm = true;
  Result<SimplifyResult> result = simplify(mesh, options);
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  return *result.value().pm;
}

TEST(LodChain, EachLevelIsTheFinestWithAtMostItsTriangles) {
  TriangleMesh input = load_clean_mesh("cgal_mushroom.off");  // one boundary loop
  ProgressiveMesh pm = record(input, 0.05);
  const std::vector<uint64_t> targets = {2000, 500, 4608, 1001};
  Result<std::vector<TriangleMesh>> lods = extract_lods(pm, targets);
  ASSERT_TRUE(lods.is_ok()) << lods.status().message();
  for (size_t i = 0; i < targets.size(); ++i) {
    SCOPED_TRACE(targets[i]);
    const TriangleMesh& lod = lods.value()[i];
    EXPECT_LE(lod.triangle_count(), targets[i]);
    // One more split would pass the target (or there is none left).
    size_t vertices = lod.vertex_count();
    if (vertices < pm.full_vertex_count()) {
      Result<TriangleMesh> finer = mesh_at_lod(pm, vertices + 1);
      ASSERT_TRUE(finer.is_ok());
      EXPECT_GT(finer.value().triangle_count(), targets[i]);
    }
    EXPECT_FALSE(check_mesh(lod).has_problems());
  }
  // The full target gives the input back.
  EXPECT_EQ(lods.value()[2].triangle_count(), input.triangle_count());
}

TEST(LodChain, TheRunsOwnTargetGivesItsResult) {
  TriangleMesh input = load_clean_mesh("cgal_elephant.off");
  SimplifyOptions options;
  options.target_ratio = 0.1;
  options.record_pm = true;
  Result<SimplifyResult> result = simplify(input, options);
  ASSERT_TRUE(result.is_ok());
  Result<std::vector<TriangleMesh>> lods =
      extract_lods(*result.value().pm, {input.triangle_count() / 10});
  ASSERT_TRUE(lods.is_ok());
  EXPECT_EQ(lods.value()[0].triangle_count(), result.value().mesh.triangle_count());
}

TEST(LodRequest, ParsesVerticesTrianglesAndRatios) {
  Result<LodRequest> v = parse_lod_request("5000");
  ASSERT_TRUE(v.is_ok());
  EXPECT_EQ(v.value().kind, LodRequest::Kind::kVertices);
  EXPECT_EQ(v.value().count, 5000u);
  Result<LodRequest> t = parse_lod_request("120t");
  ASSERT_TRUE(t.is_ok());
  EXPECT_EQ(t.value().kind, LodRequest::Kind::kTriangles);
  EXPECT_EQ(t.value().count, 120u);
  Result<LodRequest> r = parse_lod_request("0.25");
  ASSERT_TRUE(r.is_ok());
  EXPECT_EQ(r.value().kind, LodRequest::Kind::kRatio);
  EXPECT_DOUBLE_EQ(r.value().ratio, 0.25);
  for (const char* bad : {"", "t", "1.5", "0.0", "-3", "12x", "1e5", "99999999999999999999"}) {
    Result<LodRequest> parsed = parse_lod_request(bad);
    ASSERT_FALSE(parsed.is_ok()) << bad;
    EXPECT_EQ(parsed.status().kind(), ErrorKind::kUsage);
  }
}

TEST(LodRequest, VertexCountsFollowTheRecords) {
  TriangleMesh input = load_clean_mesh("cgal_elephant.off");
  ProgressiveMesh pm = record(input, 0.1);
  LodRequest all{LodRequest::Kind::kRatio, 0, 1.0};
  EXPECT_EQ(lod_vertex_count(pm, all), pm.full_vertex_count());
  LodRequest few{LodRequest::Kind::kVertices, 3, 1};
  EXPECT_EQ(lod_vertex_count(pm, few), pm.base.vertex_count());  // clamped
  LodRequest many{LodRequest::Kind::kVertices, 1u << 30, 1};
  EXPECT_EQ(lod_vertex_count(pm, many), pm.full_vertex_count());
  LodRequest tris{LodRequest::Kind::kTriangles, 2000, 1};
  Result<TriangleMesh> mesh = mesh_at_lod(pm, lod_vertex_count(pm, tris));
  ASSERT_TRUE(mesh.is_ok());
  EXPECT_LE(mesh.value().triangle_count(), 2000u);
  EXPECT_GE(mesh.value().triangle_count(), 1999u);  // closed mesh: +2 per split
}

}  // namespace
}  // namespace lodbake
