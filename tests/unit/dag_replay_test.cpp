// Mode dag of the replay runtime (lib/replay/dag_replay.h): MANAGE-TRAVERSAL
// with the priority-oriented, linear and constant-time traversals on the DAG
// of a greedy and of a balanced progressive mesh keeps a valid cut every
// frame, respects N and the triangle budget, refines when close and
// coarsens what leaves the view; on a still view the three traversals reach
// the one cut the fidelity constraint defines; the accuracy measure counts
// shared, same-oriented triangles.
#include "lib/replay/dag_replay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

#include "lib/dag/vsplit_dag_builder.h"
#include "split_front_support.h"

namespace lodbake {
namespace {

constexpr DagTraversal kTraversals[] = {DagTraversal::kPriority, DagTraversal::kLinear,
                                        DagTraversal::kConstantTime};

struct Totals {
  size_t splits = 0, collapses_late = 0, max_triangles = 0;
};

BoundingSphere sphere_of(const ProgressiveMesh& pm) {
  std::vector<Vec3f> points = pm.base.positions;
  for (const VertexSplit& s : pm.splits)
    points.push_back(s.vt_position);
  return bounding_sphere(points);
}

// Replays the scan path, checking the cut and the limits after every frame.
Totals replay_scan(const ProgressiveMesh& pm, const VsplitDag& dag,
                   const DagReplayOptions& options) {
  Totals t;
  Result<DagReplay> replay = DagReplay::create(pm, dag);
  EXPECT_TRUE(replay.is_ok()) << replay.status().message();
  if (!replay.is_ok()) return t;
  const BoundingSphere sphere = sphere_of(pm);
  const std::vector<CameraFrame> path = scan_path(sphere, 60);
  const size_t n = options.max_changes;
  for (size_t i = 0; i < path.size(); ++i) {
    Result<DagFrameStats> stats = replay.value().adapt(sphere, path[i], options);
    EXPECT_TRUE(stats.is_ok()) << "frame " << i << ": " << stats.status().message();
    if (!stats.is_ok()) return t;
    const DagFrameStats& f = stats.value();
    EXPECT_LE(f.splits, n) << "frame " << i;
    EXPECT_LE(f.collapses, n) << "frame " << i;
    if (options.traversal == DagTraversal::kConstantTime) {
      EXPECT_LE(f.visited, 2 * n);
    }
    EXPECT_GE(f.visited, f.splits + f.collapses);
    EXPECT_LE(f.triangles, options.triangle_budget) << "frame " << i;
    EXPECT_EQ(f.split_front, replay.value().fronts().split_front().size());
    EXPECT_EQ(f.triangles, replay.value().triangle_count());
    const std::vector<std::string> problems = replay.value().check();
    EXPECT_TRUE(problems.empty()) << "frame " << i << ": " << problems.front();
    if (!problems.empty()) return t;
    t.splits += f.splits;
    if (i >= 30) t.collapses_late += f.collapses;
    t.max_triangles = std::max(t.max_triangles, f.triangles);
  }
  return t;
}

class DagReplayTest : public ::testing::TestWithParam<std::tuple<std::string, DagTraversal>> {};

TEST_P(DagReplayTest, ScanKeepsAValidCutWithinLimits) {
  const ProgressiveMesh pm = front_test::test_pm(std::get<0>(GetParam()));
  ASSERT_GT(pm.splits.size(), 0u);
  Result<VsplitDag> dag = build_vsplit_dag(pm);
  ASSERT_TRUE(dag.is_ok()) << dag.status().message();
  DagReplayOptions options;
  options.traversal = std::get<1>(GetParam());
  options.max_changes = 300;
  options.tolerance_pixels = 0.25f;
  const Totals free_run = replay_scan(pm, dag.value(), options);
  EXPECT_GT(free_run.splits, 0u);
  EXPECT_GT(free_run.collapses_late, 0u);
  EXPECT_GT(free_run.max_triangles, pm.base.triangle_count() + 100);
  // Half the triangles the unconstrained run reached: the budget binds, and
  // the mesh gets within one split of it.
  options.triangle_budget = (pm.base.triangle_count() + free_run.max_triangles) / 2;
  const Totals budget_run = replay_scan(pm, dag.value(), options);
  EXPECT_GE(budget_run.max_triangles + 2, options.triangle_budget);
  EXPECT_LE(budget_run.max_triangles, options.triangle_budget);
}

INSTANTIATE_TEST_SUITE_P(Meshes, DagReplayTest,
                         ::testing::Combine(::testing::Values("cgal_fandisk.off",
                                                              "balanced:cgal_fandisk.off"),
                                            ::testing::ValuesIn(kTraversals)),
                         [](const ::testing::TestParamInfo<DagReplayTest::ParamType>& param) {
                           const bool balanced =
                               std::get<0>(param.param).rfind("balanced:", 0) == 0;
                           return std::string(balanced ? "balanced_" : "greedy_") +
                                  dag_traversal_name(std::get<1>(param.param));
                         });

// The cut the fidelity constraint defines for a still view: a node is split
// exactly when its error reaches the tolerance and all its parents are split
// (parents have smaller ids, so one pass in id order decides every node).
std::vector<uint8_t> fidelity_cut(const DagReplay& replay, const VsplitDag& dag, float tolerance) {
  std::vector<uint8_t> split(dag.node_count(), 0);
  for (uint32_t n = 0; n < dag.node_count(); ++n) {
    bool parents_split = true;
    for (uint32_t k = dag.parent_offsets[n]; k < dag.parent_offsets[n + 1]; ++k)
      parents_split = parents_split && split[dag.parents[k]] != 0;
    split[n] = parents_split && !(replay.priority(n) < tolerance);
  }
  return split;
}

std::vector<uint8_t> split_flags(const DagReplay& replay) {
  std::vector<uint8_t> flags(replay.fronts().node_count());
  for (uint32_t n = 0; n < flags.size(); ++n)
    flags[n] = replay.fronts().is_split(n);
  return flags;
}

// FREE mode on a still camera close to the model: the priority-oriented
// traversal with unlimited N reaches the fidelity cut in one frame; the
// linear and constant-time traversals reach the same cut with a small N over
// enough frames, because their queues carry on where they stopped.
TEST(DagReplay, TraversalsAgreeOnAStillView) {
  const ProgressiveMesh pm = front_test::test_pm("balanced:cgal_fandisk.off");
  Result<VsplitDag> dag = build_vsplit_dag(pm);
  ASSERT_TRUE(dag.is_ok()) << dag.status().message();
  const BoundingSphere sphere = sphere_of(pm);
  const CameraFrame frame = scan_path(sphere, 60)[90];
  DagReplayOptions options;
  options.budget_mode = DagBudgetMode::kFree;
  options.tolerance_pixels = 0.5f;

  Result<DagReplay> reference = DagReplay::create(pm, dag.value());
  ASSERT_TRUE(reference.is_ok());
  options.max_changes = pm.splits.size() + 1;
  ASSERT_TRUE(reference.value().adapt(sphere, frame, options).is_ok());
  const std::vector<uint8_t> expected =
      fidelity_cut(reference.value(), dag.value(), options.tolerance_pixels);
  ASSERT_EQ(split_flags(reference.value()), expected);
  const size_t expected_splits = std::count(expected.begin(), expected.end(), 1);
  ASSERT_GT(expected_splits, 50u);
  ASSERT_LT(expected_splits, pm.splits.size());

  for (DagTraversal traversal : {DagTraversal::kLinear, DagTraversal::kConstantTime}) {
    SCOPED_TRACE(dag_traversal_name(traversal));
    Result<DagReplay> replay = DagReplay::create(pm, dag.value());
    ASSERT_TRUE(replay.is_ok());
    options.traversal = traversal;
    options.max_changes = 7;
    size_t frames = 0, last_changes = 1;
    while (last_changes != 0 && frames < 100000) {
      Result<DagFrameStats> f = replay.value().adapt(sphere, frame, options);
      ASSERT_TRUE(f.is_ok()) << f.status().message();
      ASSERT_LE(f.value().splits, 7u);
      last_changes = f.value().splits + f.value().collapses;
      // Constant-time may visit only nodes that need nothing in one frame
      // and still have work left: stop only after a few idle frames.
      if (last_changes == 0 && traversal == DagTraversal::kConstantTime) {
        for (int k = 0; k < 1000 && last_changes == 0; ++k) {
          f = replay.value().adapt(sphere, frame, options);
          ASSERT_TRUE(f.is_ok());
          last_changes = f.value().splits + f.value().collapses;
        }
      }
      ++frames;
    }
    EXPECT_GT(frames, expected_splits / 7);
    EXPECT_EQ(split_flags(replay.value()), expected);
    EXPECT_TRUE(replay.value().check().empty());
    EXPECT_EQ(cut_accuracy(reference.value().cut_triangles(), replay.value().cut_triangles()), 1.0);
  }
}

// Along the scan, the linear and constant-time traversals with the paper's
// settings have part, not all, of the priority-oriented traversal's
// triangles, and the priority-oriented one has all of its own.
TEST(DagReplay, AccuracyAgainstThePriorityTraversal) {
  const ProgressiveMesh pm = front_test::test_pm("balanced:cgal_fandisk.off");
  Result<VsplitDag> dag = build_vsplit_dag(pm);
  ASSERT_TRUE(dag.is_ok());
  const BoundingSphere sphere = sphere_of(pm);
  std::vector<DagReplay> replays;
  for (int i = 0; i < 3; ++i)
    replays.push_back(std::move(DagReplay::create(pm, dag.value())).value());
  DagReplayOptions options;
  options.tolerance_pixels = 0.25f;
  options.max_changes = 30;
  double lowest = 1;
  for (const CameraFrame& frame : scan_path(sphere, 60)) {
    for (int i = 0; i < 3; ++i) {
      options.traversal = kTraversals[i];
      ASSERT_TRUE(replays[i].adapt(sphere, frame, options).is_ok());
    }
    const std::vector<Triangle> reference = replays[0].cut_triangles();
    EXPECT_EQ(cut_accuracy(reference, reference), 1.0);
    for (int i = 1; i < 3; ++i) {
      const double a = cut_accuracy(reference, replays[i].cut_triangles());
      EXPECT_GT(a, 0.0);
      EXPECT_LE(a, 1.0);
      lowest = std::min(lowest, a);
    }
  }
  EXPECT_LT(lowest, 1.0);
}

// ERROR-EVALUATE is monotone down the DAG on every frame of both paths: a
// child's sphere lies in each parent's and its error bound is no larger, so
// no node needing a split hides under one that does not.
TEST(DagReplay, PriorityNeverGrowsFromParentToChild) {
  const ProgressiveMesh pm = front_test::test_pm("balanced:cgal_fandisk.off");
  Result<VsplitDag> dag = build_vsplit_dag(pm);
  ASSERT_TRUE(dag.is_ok());
  const BoundingSphere sphere = sphere_of(pm);
  Result<DagReplay> replay = DagReplay::create(pm, dag.value());
  ASSERT_TRUE(replay.is_ok());
  const VsplitDag& d = dag.value();
  std::vector<CameraFrame> frames = scan_path(sphere, 60);
  const std::vector<CameraFrame> orbit = orbit_path(sphere, 60);
  frames.insert(frames.end(), orbit.begin(), orbit.end());
  size_t visible_children = 0;
  for (size_t i = 0; i < frames.size(); i += 7) {
    ASSERT_TRUE(replay.value().adapt(sphere, frames[i], DagReplayOptions()).is_ok());
    for (uint32_t n = 0; n < d.node_count(); ++n) {
      const float p = replay.value().priority(n);
      visible_children += p > 0;
      for (uint32_t k = d.parent_offsets[n]; k < d.parent_offsets[n + 1]; ++k) {
        ASSERT_LE(p, replay.value().priority(d.parents[k])) << "node " << n << ", frame " << i;
        ASSERT_LE(replay.value().bound_radius(n), replay.value().bound_radius(d.parents[k]));
      }
    }
  }
  EXPECT_GT(visible_children, 0u);
}

// A warm start takes every traversal to the fidelity cut of the first
// frame at once (the still-view cut of TraversalsAgreeOnAStillView), then
// holds N from the second frame.
TEST(DagReplay, WarmStartReachesTheFirstFramesCutThenHoldsN) {
  const ProgressiveMesh pm = front_test::test_pm("balanced:cgal_fandisk.off");
  Result<VsplitDag> dag = build_vsplit_dag(pm);
  ASSERT_TRUE(dag.is_ok());
  const BoundingSphere sphere = sphere_of(pm);
  const std::vector<CameraFrame> path = scan_path(sphere, 60);
  DagReplayOptions options;
  options.budget_mode = DagBudgetMode::kFree;
  options.tolerance_pixels = 0.5f;
  options.max_changes = 7;
  options.warm_start = true;
  std::vector<std::vector<uint8_t>> cuts;
  for (DagTraversal traversal : kTraversals) {
    SCOPED_TRACE(dag_traversal_name(traversal));
    Result<DagReplay> replay = DagReplay::create(pm, dag.value());
    ASSERT_TRUE(replay.is_ok());
    options.traversal = traversal;
    Result<DagFrameStats> first = replay.value().adapt(sphere, path[90], options);
    ASSERT_TRUE(first.is_ok());
    EXPECT_GT(first.value().splits, 50u);
    EXPECT_EQ(split_flags(replay.value()),
              fidelity_cut(replay.value(), dag.value(), options.tolerance_pixels));
    cuts.push_back(split_flags(replay.value()));
    Result<DagFrameStats> second = replay.value().adapt(sphere, path[10], options);
    ASSERT_TRUE(second.is_ok());
    EXPECT_LE(second.value().splits, 7u);
    EXPECT_LE(second.value().collapses, 7u);
    EXPECT_TRUE(replay.value().check().empty());
  }
  EXPECT_EQ(cuts[0], cuts[1]);
  EXPECT_EQ(cuts[0], cuts[2]);
}

TEST(DagReplay, AccuracyCountsSameOrientedTriangles) {
  const std::vector<Triangle> reference = {{0, 1, 2}, {2, 1, 3}, {3, 4, 5}, {5, 4, 6}};
  EXPECT_EQ(cut_accuracy(reference, {{1, 2, 0}, {3, 2, 1}, {4, 5, 3}, {4, 6, 5}}), 1.0);
  EXPECT_EQ(cut_accuracy(reference, {{0, 2, 1}, {2, 1, 3}}), 0.25);  // first one flipped
  EXPECT_EQ(cut_accuracy(reference, {}), 0.0);
  EXPECT_EQ(cut_accuracy({}, reference), 1.0);
}

TEST(DagReplay, BudgetModeKeepsTheMeshWithinTheBudgetFromTheStart) {
  const ProgressiveMesh pm = front_test::test_pm("cgal_fandisk.off");
  Result<VsplitDag> dag = build_vsplit_dag(pm);
  ASSERT_TRUE(dag.is_ok());
  const BoundingSphere sphere = sphere_of(pm);
  DagReplayOptions options;
  options.tolerance_pixels = 0.1f;
  options.triangle_budget = pm.base.triangle_count() + 40;
  for (DagBudgetMode mode : {DagBudgetMode::kBudget, DagBudgetMode::kAuto, DagBudgetMode::kFree}) {
    Result<DagReplay> replay = DagReplay::create(pm, dag.value());
    ASSERT_TRUE(replay.is_ok());
    options.budget_mode = mode;
    Result<DagFrameStats> f = replay.value().adapt(sphere, scan_path(sphere, 60)[60], options);
    ASSERT_TRUE(f.is_ok());
    EXPECT_EQ(f.value().budget_mode, mode != DagBudgetMode::kFree);
    if (mode == DagBudgetMode::kFree) {
      EXPECT_GT(f.value().triangles, options.triangle_budget);
    } else {
      EXPECT_LE(f.value().triangles, options.triangle_budget);
      EXPECT_GE(f.value().triangles + 2, options.triangle_budget);
    }
  }
}

// Back-facing simplification is sound and does something: on every few
// frames of both paths, a node whose priority the back-face test alone sets
// to 0 creates, with all of its descendants, only triangles whose every
// corner sees the triangle from behind (with the geometry of their
// creation; zero-area triangles face nowhere), and such nodes exist. On a still view the cut with
// the test has fewer triangles than without it.
TEST(DagReplay, BackFacingNodesCreateOnlyTrianglesFacingAway) {
  const ProgressiveMesh pm = front_test::test_pm("balanced:cgal_fandisk.off");
  Result<VsplitDag> dag = build_vsplit_dag(pm);
  ASSERT_TRUE(dag.is_ok());
  Result<SplitLineage> lineage = build_split_lineage(pm);
  ASSERT_TRUE(lineage.is_ok());
  const SplitLineage& l = lineage.value();
  const VsplitDag& d = dag.value();
  const size_t nodes = d.node_count(), base = pm.base.vertex_count();
  // Each triangle's corners when its split creates it.
  std::vector<std::array<Vec3f, 3>> corners(l.triangles.size());
  std::vector<Vec3f> at = pm.base.positions;
  at.resize(base + nodes);
  for (size_t n = 0; n < nodes; ++n) {
    at[pm.splits[n].vs] = pm.splits[n].vs_position;
    at[base + n] = pm.splits[n].vt_position;
    for (uint32_t t = l.created_offsets[n]; t < l.created_offsets[n + 1]; ++t) {
      for (int c = 0; c < 3; ++c)
        corners[t][c] = at[l.triangles[t][c]];
    }
  }
  std::vector<std::vector<uint32_t>> children(nodes);
  for (uint32_t n = 0; n < nodes; ++n) {
    for (uint32_t k = d.parent_offsets[n]; k < d.parent_offsets[n + 1]; ++k)
      children[d.parents[k]].push_back(n);
  }
  auto faces_away = [&](uint32_t node, const Vec3f& eye) {
    std::vector<uint32_t> stack{node};
    std::vector<uint8_t> seen(nodes, 0);
    seen[node] = 1;
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      for (uint32_t t = l.created_offsets[n]; t < l.created_offsets[n + 1]; ++t) {
        const std::array<Vec3f, 3>& p = corners[t];
        double e1[3], e2[3], normal[3];
        for (int i = 0; i < 3; ++i) {
          e1[i] = double{p[1][i]} - p[0][i];
          e2[i] = double{p[2][i]} - p[0][i];
        }
        normal[0] = e1[1] * e2[2] - e1[2] * e2[1];
        normal[1] = e1[2] * e2[0] - e1[0] * e2[2];
        normal[2] = e1[0] * e2[1] - e1[1] * e2[0];
        // A zero-area triangle (collinear corners) is seen from neither side.
        if (normal[0] == 0 && normal[1] == 0 && normal[2] == 0) continue;
        for (const Vec3f& q : p) {
          double along = 0;
          for (int i = 0; i < 3; ++i)
            along += normal[i] * (double{q[i]} - eye[i]);
          if (!(along > 0)) return false;
        }
      }
      for (uint32_t c : children[n]) {
        if (!seen[c]) stack.push_back(c), seen[c] = 1;
      }
    }
    return true;
  };
  const BoundingSphere sphere = sphere_of(pm);
  std::vector<CameraFrame> frames = scan_path(sphere, 60);
  const std::vector<CameraFrame> orbit = orbit_path(sphere, 60);
  frames.insert(frames.end(), orbit.begin(), orbit.end());
  Result<DagReplay> with = DagReplay::create(pm, d);
  Result<DagReplay> without = DagReplay::create(pm, d);
  ASSERT_TRUE(with.is_ok() && without.is_ok());
  DagReplayOptions on, off;
  off.back_face = false;
  size_t culled = 0;
  for (size_t i = 0; i < frames.size(); i += 11) {
    ASSERT_TRUE(with.value().adapt(sphere, frames[i], on).is_ok());
    ASSERT_TRUE(without.value().adapt(sphere, frames[i], off).is_ok());
    const Vec3f eye = frames[i].eye;
    for (uint32_t n = 0; n < nodes; ++n) {
      if (with.value().priority(n) > 0 || !(without.value().priority(n) > 0)) continue;
      ++culled;
      ASSERT_TRUE(faces_away(n, eye)) << "node " << n << ", frame " << i;
    }
  }
  EXPECT_GT(culled, 100u);

  const CameraFrame still = frames[20];
  on.budget_mode = off.budget_mode = DagBudgetMode::kFree;
  on.max_changes = off.max_changes = nodes + 1;
  Result<DagReplay> a = DagReplay::create(pm, d);
  Result<DagReplay> b = DagReplay::create(pm, d);
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  ASSERT_TRUE(a.value().adapt(sphere, still, on).is_ok());
  ASSERT_TRUE(b.value().adapt(sphere, still, off).is_ok());
  EXPECT_TRUE(a.value().check().empty());
  EXPECT_LT(a.value().triangle_count(), b.value().triangle_count());
}

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
