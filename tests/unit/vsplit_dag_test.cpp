// The DAG of vertex splits built from progressive meshes (recorded by the
// QEM engine, and the balanced hierarchy's): edges go
// from lower to higher split index and none is transitively implied; any
// random legal order of all splits ends at the input mesh; random walks of
// splits and collapses over the two fronts keep the counters consistent and
// the cut an edge-manifold, consistently oriented mesh equal to an
// independent replay of the same splits; collapsing all returns the base.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "lib/dag/dag_fronts.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/simplify/pm_replay.h"
#include "split_front_support.h"

namespace lodbake {
namespace {

using front_test::mesh_problem;
using front_test::replay_subset;
using front_test::sorted_canonical;

std::vector<uint8_t> split_flags(const DagFronts& fronts) {
  std::vector<uint8_t> flags(fronts.node_count());
  for (uint32_t i = 0; i < flags.size(); ++i)
    flags[i] = fronts.is_split(i);
  return flags;
}

class DagOnSharedMesh : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    pm_ = front_test::test_pm(GetParam());
    ASSERT_GT(pm_.splits.size(), 0u);
    Result<SplitLineage> lineage = build_split_lineage(pm_);
    ASSERT_TRUE(lineage.is_ok()) << lineage.status().message();
    lineage_ = std::move(lineage).value();
    Result<VsplitDag> dag = reduce_dependencies(lineage_);
    ASSERT_TRUE(dag.is_ok()) << dag.status().message();
    dag_ = std::move(dag).value();
  }
  ProgressiveMesh pm_;
  SplitLineage lineage_;
  VsplitDag dag_;
};

TEST_P(DagOnSharedMesh, EdgesAreOrderedAndNotRedundantAndKeepReachability) {
  const size_t n = dag_.node_count();
  ASSERT_EQ(n, pm_.splits.size());
  // Ancestor sets of the reduced DAG (bitsets; the meshes here are small).
  std::vector<std::vector<uint64_t>> anc(n, std::vector<uint64_t>((n + 63) / 64, 0));
  for (size_t i = 0; i < n; ++i) {
    for (uint32_t k = dag_.parent_offsets[i]; k < dag_.parent_offsets[i + 1]; ++k) {
      const uint32_t p = dag_.parents[k];
      ASSERT_LT(p, i);
      if (k > dag_.parent_offsets[i]) {
        ASSERT_LT(dag_.parents[k - 1], p);
      }
      anc[i][p / 64] |= uint64_t{1} << (p % 64);
      for (size_t w = 0; w < anc[i].size(); ++w)
        anc[i][w] |= anc[p][w];
    }
  }
  auto reaches = [&](uint32_t from, uint32_t to) {  // to is an ancestor of from
    return (anc[from][to / 64] >> (to % 64)) & 1;
  };
  size_t redundant = 0;
  for (size_t i = 0; i < n; ++i) {
    for (uint32_t a = dag_.parent_offsets[i]; a < dag_.parent_offsets[i + 1]; ++a) {
      for (uint32_t b = dag_.parent_offsets[i]; b < dag_.parent_offsets[i + 1]; ++b) {
        if (a != b && reaches(dag_.parents[b], dag_.parents[a])) ++redundant;
      }
    }
    // Every raw dependency stays implied.
    for (uint32_t k = lineage_.dependency_offsets[i]; k < lineage_.dependency_offsets[i + 1]; ++k)
      EXPECT_TRUE(reaches(static_cast<uint32_t>(i), lineage_.dependencies[k])) << i;
  }
  EXPECT_EQ(redundant, 0u);
  EXPECT_LE(dag_.edge_count(), lineage_.dependencies.size());
}

TEST_P(DagOnSharedMesh, RandomLegalOrdersEndAtTheInputMesh) {
  Result<PmRefiner> refiner = PmRefiner::create(pm_);
  ASSERT_TRUE(refiner.is_ok());
  ASSERT_TRUE(refiner.value().refine_to(pm_.full_vertex_count()).is_ok());
  const std::vector<Triangle> full = sorted_canonical(refiner.value().mesh().triangles);
  TriangleMesh input = load_clean_mesh(front_test::mesh_file(GetParam()));
  std::mt19937 rng(12345);
  for (int order = 0; order < 8; ++order) {
    Result<DagFronts> created = DagFronts::create(dag_);
    ASSERT_TRUE(created.is_ok());
    DagFronts& fronts = created.value();
    while (!fronts.split_front().empty()) {
      const auto& fs = fronts.split_front();
      const uint32_t node = fs[std::uniform_int_distribution<size_t>(0, fs.size() - 1)(rng)];
      ASSERT_TRUE(fronts.split(node).is_ok());
    }
    ASSERT_EQ(fronts.split_count(), fronts.node_count()) << "a node never became legal";
    EXPECT_TRUE(fronts.check_counters().empty());
    TriangleMesh cut;
    cut.positions = refiner.value().mesh().positions;
    cut.triangles = dag_cut_triangles(lineage_, fronts);
    EXPECT_EQ(sorted_canonical(cut.triangles), full) << "order " << order;
    // In the input's numbering: the input's triangles, same orientation.
    Result<TriangleMesh> mapped = map_to_input(pm_, cut);
    ASSERT_TRUE(mapped.is_ok());
    EXPECT_TRUE(same_oriented_triangles(mapped.value(), input)) << "order " << order;
    EXPECT_EQ(mapped.value().positions, input.positions);
  }
}

TEST_P(DagOnSharedMesh, RandomWalksKeepAValidMeshEqualToReplay) {
  Result<DagFronts> created = DagFronts::create(dag_);
  ASSERT_TRUE(created.is_ok());
  DagFronts& fronts = created.value();
  const std::vector<Triangle> base = sorted_canonical(pm_.base.triangles);
  std::mt19937 rng(777);
  const int steps = 3000;
  for (int step = 0; step < steps; ++step) {
    // Biased towards refinement first, then towards coarsening.
    const double p_split = step < steps / 2 ? 0.7 : 0.35;
    const auto& fs = fronts.split_front();
    const auto& fc = fronts.collapse_front();
    const bool do_split =
        fc.empty() || (!fs.empty() && std::uniform_real_distribution<>(0, 1)(rng) < p_split);
    if (do_split) {
      const uint32_t node = fs[std::uniform_int_distribution<size_t>(0, fs.size() - 1)(rng)];
      ASSERT_TRUE(fronts.split(node).is_ok());
    } else {
      const uint32_t node = fc[std::uniform_int_distribution<size_t>(0, fc.size() - 1)(rng)];
      ASSERT_TRUE(fronts.collapse(node).is_ok());
    }
    if (step % 25 == 0 || step == steps - 1) {
      const std::vector<Triangle> cut = dag_cut_triangles(lineage_, fronts);
      ASSERT_EQ(mesh_problem(cut), "") << "step " << step;
      const std::vector<uint8_t> flags = split_flags(fronts);
      ASSERT_EQ(front_test::missing_vertex(cut, flags, lineage_.base_vertex_count), "")
          << "step " << step;
      ASSERT_EQ(sorted_canonical(cut), sorted_canonical(replay_subset(pm_, flags)))
          << "step " << step;
      ASSERT_TRUE(fronts.check_counters().empty()) << "step " << step;
    }
  }
  while (!fronts.collapse_front().empty())
    ASSERT_TRUE(fronts.collapse(fronts.collapse_front().back()).is_ok());
  EXPECT_EQ(fronts.split_count(), 0u);
  EXPECT_EQ(sorted_canonical(dag_cut_triangles(lineage_, fronts)), base);
}

TEST_P(DagOnSharedMesh, PrefixCutsArePmRefinerMeshes) {
  Result<PmRefiner> refiner = PmRefiner::create(pm_);
  ASSERT_TRUE(refiner.is_ok());
  Result<DagFronts> created = DagFronts::create(dag_);
  ASSERT_TRUE(created.is_ok());
  const size_t n = pm_.splits.size();
  for (size_t i = 0; i < n; ++i) {
    ASSERT_TRUE(created.value().split(static_cast<uint32_t>(i)).is_ok()) << i;
    ASSERT_TRUE(refiner.value().split_next().is_ok());
    if ((i + 1) % (n / 7 + 1) == 0) {
      EXPECT_EQ(sorted_canonical(dag_cut_triangles(lineage_, created.value())),
                sorted_canonical(refiner.value().mesh().triangles))
          << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, DagOnSharedMesh,
                         ::testing::Values("igl_decimated-knight.off", "npm_bunny.obj",
                                           "cgal_mushroom.off", "cgal_elephant.off",
                                           "cgal_elephant-with-holes.off"));
// The same on the progressive mesh of the balanced vertex hierarchy
// (hierarchy_to_progressive_mesh), which lodbake-hierarchy stores DAGE and
// VTRE for.
INSTANTIATE_TEST_SUITE_P(BalancedPm, DagOnSharedMesh,
                         ::testing::Values("balanced:igl_decimated-knight.off",
                                           "balanced:npm_bunny.obj", "balanced:cgal_mushroom.off",
                                           "balanced:cgal_elephant.off",
                                           "balanced:cgal_elephant-with-holes.off"));

// The DAG is topological: a PM recorded with optimal placement (vs moves)
// gives the same guarantees for the triangle sets.
TEST(VsplitDag, OptimalPlacementPmRandomWalk) {
  TriangleMesh input = load_clean_mesh("cgal_mushroom.off");
  SimplifyOptions options;
  options.record_pm = true;
  options.placement = Placement::kOptimal;
  Result<SimplifyResult> simplified = simplify(input, options);
  ASSERT_TRUE(simplified.is_ok());
  const ProgressiveMesh& pm = *simplified.value().pm;
  Result<SplitLineage> lineage = build_split_lineage(pm);
  ASSERT_TRUE(lineage.is_ok());
  Result<VsplitDag> dag = reduce_dependencies(lineage.value());
  ASSERT_TRUE(dag.is_ok());
  Result<DagFronts> created = DagFronts::create(dag.value());
  ASSERT_TRUE(created.is_ok());
  DagFronts& fronts = created.value();
  std::mt19937 rng(99);
  for (int step = 0; step < 2000; ++step) {
    const auto& fs = fronts.split_front();
    const auto& fc = fronts.collapse_front();
    const bool do_split =
        fc.empty() || (!fs.empty() && std::uniform_real_distribution<>(0, 1)(rng) < 0.6);
    const auto& front = do_split ? fs : fc;
    const uint32_t node = front[std::uniform_int_distribution<size_t>(0, front.size() - 1)(rng)];
    ASSERT_TRUE((do_split ? fronts.split(node) : fronts.collapse(node)).is_ok());
    if (step % 50 == 0) {
      const std::vector<Triangle> cut = dag_cut_triangles(lineage.value(), fronts);
      ASSERT_EQ(mesh_problem(cut), "") << step;
      ASSERT_EQ(sorted_canonical(cut), sorted_canonical(replay_subset(pm, split_flags(fronts))))
          << step;
    }
  }
}

TEST(DagFronts, CountersFollowFigureOne) {
  // A diamond 0 -> {1, 2} -> 3, plus 4 under 2.
  VsplitDag dag;
  dag.base_vertex_count = 3;
  dag.parent_offsets = {0, 0, 1, 2, 4, 5};
  dag.parents = {0, 0, 1, 2, 2};
  Result<DagFronts> created = DagFronts::create(dag);
  ASSERT_TRUE(created.is_ok());
  DagFronts& f = created.value();
  EXPECT_EQ(f.split_front(), std::vector<uint32_t>{0});
  EXPECT_TRUE(f.collapse_front().empty());
  EXPECT_EQ(f.counter(3), 2u);
  EXPECT_FALSE(f.split(3).is_ok());
  ASSERT_TRUE(f.split(0).is_ok());
  EXPECT_EQ(f.counter(1), 0u);
  EXPECT_TRUE(f.can_split(1) && f.can_split(2) && f.can_collapse(0));
  ASSERT_TRUE(f.split(2).is_ok());
  EXPECT_EQ(f.counter(0), 1u);  // one split child
  EXPECT_FALSE(f.can_collapse(0));
  EXPECT_EQ(f.counter(3), 1u);  // one collapsed parent left
  EXPECT_TRUE(f.can_split(4));
  ASSERT_TRUE(f.split(1).is_ok());
  EXPECT_EQ(f.counter(0), 2u);  // two split children
  EXPECT_TRUE(f.can_split(3));
  EXPECT_FALSE(f.collapse(0).is_ok());
  ASSERT_TRUE(f.split(3).is_ok());
  EXPECT_EQ(f.counter(2), 1u);
  EXPECT_TRUE(f.check_counters().empty());
  ASSERT_TRUE(f.collapse(3).is_ok());
  ASSERT_TRUE(f.collapse(2).is_ok());
  ASSERT_TRUE(f.collapse(1).is_ok());
  ASSERT_TRUE(f.collapse(0).is_ok());
  EXPECT_EQ(f.split_count(), 0u);
  EXPECT_TRUE(f.check_counters().empty());
}

TEST(DagFronts, RejectsMalformedDags) {
  VsplitDag dag;
  dag.parent_offsets = {0, 1};
  dag.parents = {0};  // its own parent
  EXPECT_FALSE(DagFronts::create(dag).is_ok());
  dag.parent_offsets = {0, 0, 2};
  dag.parents = {0, 0};  // repeated
  EXPECT_FALSE(DagFronts::create(dag).is_ok());
  dag.parent_offsets = {0, 0, 3};
  EXPECT_FALSE(DagFronts::create(dag).is_ok());
}

}  // namespace
}  // namespace lodbake
