// Mode vhier of the replay runtime (lib/replay/vhier_replay.h): both built-in
// paths on a torus's balanced hierarchy keep a valid mesh every frame, refine
// when close, coarsen what leaves the view, and a coarser tolerance gives
// fewer triangles.
#include "lib/replay/vhier_replay.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/refinement_data.h"
#include "tests/unit/test_meshes.h"

namespace lodbake {
namespace {

struct Built {
  TriangleMesh input;
  VertexHierarchy h;
  std::vector<NodeRefinement> data;
};

Built build_torus() {
  Built b;
  b.input = test_meshes::torus(48, 32);
  Result<BalancedHierarchy> built = build_balanced_hierarchy(b.input, BalancedBuildOptions());
  EXPECT_TRUE(built.is_ok()) << built.status().message();
  b.h = std::move(built).value().hierarchy;
  Result<std::vector<NodeRefinement>> data = compute_refinement_data(b.h, b.input);
  EXPECT_TRUE(data.is_ok()) << data.status().message();
  b.data = std::move(data).value();
  return b;
}

struct Totals {
  size_t splits = 0, collapses = 0, max_triangles = 0, collapses_after_approach = 0;
};

Totals replay(const Built& b, const std::vector<CameraFrame>& path, float tolerance) {
  Result<SelectiveRefiner> refiner = SelectiveRefiner::create(b.h);
  EXPECT_TRUE(refiner.is_ok());
  const BoundingSphere sphere = bounding_sphere(b.h.position);
  VhierReplayOptions options;
  options.tolerance_pixels = tolerance;
  Totals t;
  for (size_t i = 0; i < path.size(); ++i) {
    Result<VhierFrameStats> stats =
        adapt_vhier_frame(&refiner.value(), b.h, b.data, sphere, path[i], options);
    EXPECT_TRUE(stats.is_ok()) << "frame " << i << ": " << stats.status().message();
    if (!stats.is_ok()) return t;
    const std::vector<std::string> problems = check_vhier_mesh(refiner.value());
    EXPECT_TRUE(problems.empty()) << "frame " << i << ": " << problems.front();
    EXPECT_EQ(stats.value().triangles, refiner.value().triangle_count());
    t.splits += stats.value().splits;
    t.collapses += stats.value().collapses;
    if (i >= 30) t.collapses_after_approach += stats.value().collapses;
    t.max_triangles = std::max(t.max_triangles, stats.value().triangles);
  }
  return t;
}

TEST(VhierReplay, ScanAndOrbitKeepAValidMeshAndAdapt) {
  const Built b = build_torus();
  const BoundingSphere sphere = bounding_sphere(b.h.position);
  for (const std::vector<CameraFrame>& path : {scan_path(sphere, 60), orbit_path(sphere, 60)}) {
    const Totals t = replay(b, path, 1.0f);
    EXPECT_GT(t.splits, 0u);
    EXPECT_GT(t.max_triangles, b.h.base.triangle_count());
    EXPECT_LE(t.max_triangles, b.input.triangle_count());
    // The view moves over the model: regions that leave it are coarsened.
    EXPECT_GT(t.collapses_after_approach, 0u);
  }
}

TEST(VhierReplay, CoarserToleranceGivesFewerTriangles) {
  const Built b = build_torus();
  const std::vector<CameraFrame> path = scan_path(bounding_sphere(b.h.position), 60);
  const Totals fine = replay(b, path, 0.5f);
  const Totals coarse = replay(b, path, 8.0f);
  EXPECT_LT(coarse.max_triangles, fine.max_triangles);
}

TEST(VhierReplay, RejectsMismatchedRefinementData) {
  const Built b = build_torus();
  Result<SelectiveRefiner> refiner = SelectiveRefiner::create(b.h);
  ASSERT_TRUE(refiner.is_ok());
  std::vector<NodeRefinement> short_data(b.data.begin(), b.data.end() - 1);
  Result<VhierFrameStats> stats =
      adapt_vhier_frame(&refiner.value(), b.h, short_data, bounding_sphere(b.h.position),
                        scan_path(bounding_sphere(b.h.position), 60)[0], VhierReplayOptions());
  ASSERT_FALSE(stats.is_ok());
  EXPECT_EQ(stats.status().kind(), ErrorKind::kInvalidInput);
}

TEST(VhierReplay, BaseMeshIsValidBeforeAnyFrame) {
  const Built b = build_torus();
  Result<SelectiveRefiner> refiner = SelectiveRefiner::create(b.h);
  ASSERT_TRUE(refiner.is_ok());
  EXPECT_TRUE(check_vhier_mesh(refiner.value()).empty());
}

}  // namespace
}  // namespace lodbake
