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
// The same at 1%: 1.354e-2. Without the height guard lodbake's is 1.66e-2
// there (docs/benchmarks.md); with it 1.20e-2.
constexpr double kMeshoptimizerBunny1Percent = 1.354e-2;

double bunny_hausdorff(const TriangleMesh& bunny, double ratio, bool height_guard) {
  SimplifyOptions options;
  options.target_ratio = ratio;
  options.record_pm = true;
  options.height_guard = height_guard;
  const SimplifyResult result = take(simplify(bunny, options), "simplify");
  return take(measure_surface_distance(bunny, result.mesh), "distance").hausdorff_relative;
}

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

// The height guard is lodbake's answer where the mean quadric error misses
// a face tilting away: on the bunny it lowers the Hausdorff error at 10%
// (2.61e-3 -> 1.96e-3) and brings 1% under meshoptimizer's.
TEST(SimplifyQuality, HeightGuardLowersTheBunnysHausdorffError) {
  const TriangleMesh bunny = load_clean_mesh("stanford_bun_zipper.ply");
  const double plain = bunny_hausdorff(bunny, 0.1, false);
  const double guarded = bunny_hausdorff(bunny, 0.1, true);
  EXPECT_GT(guarded, 0.0);
  EXPECT_LT(guarded, plain);
  EXPECT_LT(guarded, kMeshoptimizerBunny10Percent);
  EXPECT_LT(bunny_hausdorff(bunny, 0.01, true), kMeshoptimizerBunny1Percent);
}

// CGAL's edge_collapse with its Garland-Heckbert plane policies reaches
// 4.363e-4 on the bunny at 50 % (tests/bench/simplify_bench.cpp,
// docs/benchmarks.md); lodbake's optimal placement, ranking collapses by the
// summed quadric over unit-weight planes as CGAL does, 3.47e-4. With the
// mean over sqrt-area weights it was 5.41e-4.
constexpr double kCgalBunny50Percent = 4.363e-4;

TEST(SimplifyQuality, OptimalPlacementOnTheBunnyAtHalfIsNoWorseThanCgal) {
  const TriangleMesh bunny = load_clean_mesh("stanford_bun_zipper.ply");
  SimplifyOptions options;
  options.target_ratio = 0.5;
  options.placement = Placement::kOptimal;
  options.record_pm = true;
  const SimplifyResult result = take(simplify(bunny, options), "simplify");
  const double hausdorff =
      take(measure_surface_distance(bunny, result.mesh), "distance").hausdorff_relative;
  EXPECT_GT(hausdorff, 0.0);
  EXPECT_LT(hausdorff, kCgalBunny50Percent);
}

}  // namespace
}  // namespace lodbake
