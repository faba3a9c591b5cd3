// Mode dag of the replay runtime (lib/replay/dag_replay.h): MANAGE-TRAVERSAL
// (priority-oriented, budget mode) on the DAG of a greedy and of a balanced
// progressive mesh keeps a valid cut every frame, respects N and the
// triangle budget, refines when close and coarsens what leaves the view.
#include "lib/replay/dag_replay.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "split_front_support.h"

namespace lodbake {
namespace {

class DagReplayTest : public ::testing::TestWithParam<std::string> {};

struct Totals {
  size_t splits = 0, collapses_late = 0, max_triangles = 0;
};

// Replays the scan path, checking the cut and the limits after every frame.
Totals replay_scan(const ProgressiveMesh& pm, const VsplitDag& dag,
                   const DagReplayOptions& options) {
  Totals t;
  Result<DagReplay> replay = DagReplay::create(pm, dag);
  EXPECT_TRUE(replay.is_ok()) << replay.status().message();
  if (!replay.is_ok()) return t;
  std::vector<Vec3f> points = pm.base.positions;
  for (const VertexSplit& s : pm.splits)
    points.push_back(s.vt_position);
  const BoundingSphere sphere = bounding_sphere(points);
  const std::vector<CameraFrame> path = scan_path(sphere, 60);
  for (size_t i = 0; i < path.size(); ++i) {
    Result<DagFrameStats> stats = replay.value().adapt(sphere, path[i], options);
    EXPECT_TRUE(stats.is_ok()) << "frame " << i << ": " << stats.status().message();
    if (!stats.is_ok()) return t;
    const DagFrameStats& f = stats.value();
    EXPECT_LE(f.splits + f.collapses, options.max_changes) << "frame " << i;
    EXPECT_LE(f.triangles, options.triangle_budget) << "frame " << i;
    EXPECT_EQ(f.split_front, replay.value().fronts().split_front().size());
    const std::vector<std::string> problems = replay.value().check();
    EXPECT_TRUE(problems.empty()) << "frame " << i << ": " << problems.front();
    if (!problems.empty()) return t;
    t.splits += f.splits;
    if (i >= 30) t.collapses_late += f.collapses;
    t.max_triangles = std::max(t.max_triangles, f.triangles);
  }
  return t;
}

TEST_P(DagReplayTest, ScanKeepsAValidCutWithinLimits) {
  const ProgressiveMesh pm = front_test::test_pm(GetParam());
  ASSERT_GT(pm.splits.size(), 0u);
  Result<VsplitDag> dag = build_vsplit_dag(pm);
  ASSERT_TRUE(dag.is_ok()) << dag.status().message();
  DagReplayOptions options;
  options.max_changes = 300;
  options.tolerance_pixels = 0.25f;
  const Totals free_run = replay_scan(pm, dag.value(), options);
  EXPECT_GT(free_run.splits, 0u);
  EXPECT_GT(free_run.collapses_late, 0u);
  EXPECT_GT(free_run.max_triangles, pm.base.triangle_count() + 100);
  // Half the triangles the unconstrained run reached: the budget binds.
  options.triangle_budget = (pm.base.triangle_count() + free_run.max_triangles) / 2;
  const Totals budget_run = replay_scan(pm, dag.value(), options);
  EXPECT_GE(budget_run.max_triangles + 2, options.triangle_budget);
  EXPECT_LE(budget_run.max_triangles, options.triangle_budget);
}

INSTANTIATE_TEST_SUITE_P(Meshes, DagReplayTest,
                         ::testing::Values("cgal_fandisk.off", "balanced:cgal_fandisk.off"));

TEST(DagReplay, RejectsADagOfAnotherMesh) {
  const ProgressiveMesh pm = front_test::test_pm("cgal_fandisk.off");
  VsplitDag dag;
  dag.base_vertex_count = static_cast<uint32_t>(pm.base.vertex_count());
  Result<DagReplay> replay = DagReplay::create(pm, dag);
  ASSERT_FALSE(replay.is_ok());
  EXPECT_EQ(replay.status().kind(), ErrorKind::kInvalidInput);
}

}  // namespace
}  // namespace lodbake
