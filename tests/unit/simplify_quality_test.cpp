// Quality sanity of the QEM engine, measured the way the benchmark measures
// (lib/metrics: symmetric Hausdorff distance relative to the input's
// bounding-box diagonal, fixed deterministic sampling).
#include <gtest/gtest.h>

#include "lib/metrics/surface_distance.h"
#include "lib/simplify/simplify.h"
#include "tests/unit/simplify_test_meshes.h"

namespace lodbake {
namespace {

// The bound comes from tests/bench/simplify_bench.cpp (docs/benchmarks.md):
// on stanford_bun_zipper.ply at 10% of the triangles, meshoptimizer 0.18's
// meshopt_simplify reaches a symmetric Hausdorff error of 2.93e-3 of the
// diagonal with the same metric. The issue asks for no larger error than
// meshoptimizer, in half placement with the PM recorded.
constexpr double kMeshoptimizerBunny10Percent = 2.93e-3;

TEST(SimplifyQuality, BunnyAtTenPercentIsNoWorseThanMeshoptimizer) {
  TriangleMesh bunny = load_clean_mesh("stanford_bun_zipper.ply");
  ASSERT_EQ(bunny.triangle_count(), 69451u);
  SimplifyOptions options;
  options.target_ratio = 0.1;
  options.record_pm = true;
  Result<SimplifyResult> result = simplify(bunny, options);
  ASSERT_TRUE(result.is_ok()) << result.status().message();
  EXPECT_LE(result.value().mesh.triangle_count(), 6945u);
  Result<SurfaceDistance> distance = measure_surface_distance(bunny, result.value().mesh);
  ASSERT_TRUE(distance.is_ok()) << distance.status().message();
  EXPECT_LT(distance.value().hausdorff_relative, kMeshoptimizerBunny10Percent);
  EXPECT_GT(distance.value().hausdorff_relative, 0.0);
}

}  // namespace
}  // namespace lodbake
