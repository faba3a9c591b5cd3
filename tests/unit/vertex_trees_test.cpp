// Vertex trees built from progressive meshes (recorded by the QEM engine,
// and the balanced hierarchy's): reconstruction down
// to the leaves gives the input mesh; on random fronts legal in the split
// DAG and in the trees, the client's triangle list equals the DAG cut and an
// independent replay of the same splits; the paper's states are 0 or 1 and
// each fan names vertices that exist at its node.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "lib/dag/dag_fronts.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/simplify/pm_replay.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "lib/vtrees/visible_vertex_list.h"
#include "split_front_support.h"

namespace lodbake {
namespace {

using front_test::mesh_problem;
using front_test::replay_subset;
using front_test::sorted_canonical;

class VertexTreesOnSharedMesh : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    pm_ = front_test::test_pm(GetParam());
    ASSERT_GT(pm_.splits.size(), 0u);
    Result<VertexTrees> trees = build_vertex_trees(pm_);
    ASSERT_TRUE(trees.is_ok()) << trees.status().message();
    trees_ = std::move(trees).value();
    Result<SplitLineage> lineage = build_split_lineage(pm_);
    ASSERT_TRUE(lineage.is_ok());
    lineage_ = std::move(lineage).value();
    Result<VsplitDag> dag = reduce_dependencies(lineage_);
    ASSERT_TRUE(dag.is_ok());
    dag_ = std::move(dag).value();
  }
  ProgressiveMesh pm_;
  VertexTrees trees_;
  SplitLineage lineage_;
  VsplitDag dag_;
};

TEST_P(VertexTreesOnSharedMesh, StructureMatchesThePm) {
  const size_t b = pm_.base.vertex_count();
  ASSERT_EQ(trees_.node_count(), b + 2 * pm_.splits.size());
  ASSERT_EQ(trees_.positions.size(), pm_.full_vertex_count());
  ASSERT_EQ(trees_.vertex_states.size(), pm_.full_vertex_count());
  size_t ones = 0;
  for (uint8_t s : trees_.vertex_states) {
    ASSERT_LE(s, 1);
    ones += s;
  }
  EXPECT_GT(ones, 0u);
  for (size_t n = 0; n < trees_.node_count(); ++n) {
    const uint32_t v = trees_.node_vertex(n);
    const size_t existing = n < b ? b : b + (n - b) / 2 + 1;
    for (uint32_t r = trees_.run_offsets[n]; r < trees_.run_offsets[n + 1]; ++r) {
      const uint32_t len = trees_.vertex_offsets[r + 1] - trees_.vertex_offsets[r];
      EXPECT_GE(len, trees_.run_closed[r] ? 3u : 2u);
      for (uint32_t k = trees_.vertex_offsets[r]; k < trees_.vertex_offsets[r + 1]; ++k) {
        EXPECT_LT(trees_.fan_vertices[k], existing) << "node " << n;
        EXPECT_NE(trees_.fan_vertices[k], v) << "node " << n;
      }
    }
  }
}

TEST_P(VertexTreesOnSharedMesh, FullReconstructionIsTheInputMesh) {
  Result<VisibleVertexList> created = VisibleVertexList::create(trees_);
  ASSERT_TRUE(created.is_ok()) << created.status().message();
  VisibleVertexList& list = created.value();
  EXPECT_EQ(sorted_canonical(list.triangles()), sorted_canonical(pm_.base.triangles));
  for (uint32_t k = 0; k < pm_.splits.size(); ++k)
    ASSERT_TRUE(list.split(k).is_ok()) << k;
  EXPECT_EQ(list.visible_count(), pm_.full_vertex_count());
  Result<PmRefiner> refiner = PmRefiner::create(pm_);
  ASSERT_TRUE(refiner.is_ok());
  ASSERT_TRUE(refiner.value().refine_to(pm_.full_vertex_count()).is_ok());
  TriangleMesh rebuilt;
  rebuilt.positions = trees_.positions;
  rebuilt.triangles = list.triangles();
  EXPECT_EQ(rebuilt.positions, refiner.value().mesh().positions);
  EXPECT_TRUE(same_oriented_triangles(rebuilt, refiner.value().mesh()));
  Result<TriangleMesh> mapped = map_to_input(pm_, rebuilt);
  ASSERT_TRUE(mapped.is_ok());
  TriangleMesh input = load_clean_mesh(front_test::mesh_file(GetParam()));
  EXPECT_EQ(mapped.value().positions, input.positions);
  EXPECT_TRUE(same_oriented_triangles(mapped.value(), input));
  for (uint32_t k = static_cast<uint32_t>(pm_.splits.size()); k-- > 0;)
    ASSERT_TRUE(list.collapse(k).is_ok()) << k;
  EXPECT_EQ(sorted_canonical(list.triangles()), sorted_canonical(pm_.base.triangles));
}

TEST_P(VertexTreesOnSharedMesh, RandomFrontsGiveTheDagCutAndTheReplay) {
  Result<VisibleVertexList> list_or = VisibleVertexList::create(trees_);
  ASSERT_TRUE(list_or.is_ok());
  VisibleVertexList& list = list_or.value();
  Result<DagFronts> fronts_or = DagFronts::create(dag_);
  ASSERT_TRUE(fronts_or.is_ok());
  DagFronts& fronts = fronts_or.value();
  std::mt19937 rng(4242);
  const int steps = 3000;
  int moves = 0;
  for (int step = 0; step < steps; ++step) {
    const double p_split = step < steps / 2 ? 0.75 : 0.3;
    const bool want_split = std::uniform_real_distribution<>(0, 1)(rng) < p_split;
    const auto& front = want_split ? fronts.split_front() : fronts.collapse_front();
    if (front.empty()) continue;
    // A node legal in the DAG may wait for its tree parent (or children):
    // try a few.
    for (int attempt = 0; attempt < 8; ++attempt) {
      const uint32_t k = front[std::uniform_int_distribution<size_t>(0, front.size() - 1)(rng)];
      if (want_split && list.can_split(k)) {
        ASSERT_TRUE(fronts.split(k).is_ok());
        ASSERT_TRUE(list.split(k).is_ok());
        ++moves;
        break;
      }
      if (!want_split && list.can_collapse(k)) {
        ASSERT_TRUE(fronts.collapse(k).is_ok());
        ASSERT_TRUE(list.collapse(k).is_ok());
        ++moves;
        break;
      }
    }
    if (step % 25 == 0 || step == steps - 1) {
      const std::vector<Triangle> tris = list.triangles();
      ASSERT_EQ(mesh_problem(tris), "") << "step " << step;
      const std::vector<Triangle> got = sorted_canonical(tris);
      ASSERT_EQ(got, sorted_canonical(dag_cut_triangles(lineage_, fronts))) << "step " << step;
      std::vector<uint8_t> flags(fronts.node_count());
      for (uint32_t i = 0; i < flags.size(); ++i)
        flags[i] = fronts.is_split(i);
      ASSERT_EQ(front_test::missing_vertex(tris, flags, trees_.base_vertex_count), "")
          << "step " << step;
      ASSERT_EQ(got, sorted_canonical(replay_subset(pm_, flags))) << "step " << step;
    }
  }
  EXPECT_GT(moves, steps / 2);
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, VertexTreesOnSharedMesh,
                         ::testing::Values("igl_decimated-knight.off", "npm_bunny.obj",
                                           "cgal_mushroom.off", "cgal_elephant.off",
                                           "cgal_elephant-with-holes.off"));
// The same on the progressive mesh of the balanced vertex hierarchy
// (hierarchy_to_progressive_mesh), which lodbake-hierarchy stores DAGE and
// VTRE for.
INSTANTIATE_TEST_SUITE_P(BalancedPm, VertexTreesOnSharedMesh,
                         ::testing::Values("balanced:igl_decimated-knight.off",
                                           "balanced:npm_bunny.obj", "balanced:cgal_mushroom.off",
                                           "balanced:cgal_elephant.off",
                                           "balanced:cgal_elephant-with-holes.off"));

TEST(VertexTrees, RefusesAPmThatMovesTheSplitVertex) {
  ProgressiveMesh pm;
  pm.base.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  pm.base.triangles = {{0, 1, 2}};
  VertexSplit s;
  s.vs = 0;
  s.vr = 1;
  s.vt_position = {0.5f, -1, 0};
  s.vs_position = {0.1f, 0, 0};
  pm.splits = {s};
  pm.input_vertex = {0, 1, 2, 3};
  Result<VertexTrees> trees = build_vertex_trees(pm);
  ASSERT_FALSE(trees.is_ok());
  EXPECT_EQ(trees.status().kind(), ErrorKind::kUnsupported);
  pm.splits[0].vs_position = {0, 0, 0};
  trees = build_vertex_trees(pm);
  ASSERT_TRUE(trees.is_ok()) << trees.status().message();
  // Equations (1)-(3): the one collapse's TRing holds both faces, all at
  // state 0, so vs (base vertex 0) and vt get state 1, the others keep 0.
  EXPECT_EQ(trees.value().vertex_states, (std::vector<uint8_t>{1, 0, 0, 1}));
  // Fans right after the split, clockwise: vt (3) sees 0, 1, 2 as an open
  // fan ending at 2; vs (0) sees only 1 and 3.
  ASSERT_EQ(trees.value().node_count(), 5u);
  const VertexTrees& t = trees.value();
  auto fan = [&](size_t node) {
    std::vector<uint32_t> out;
    for (uint32_t r = t.run_offsets[node]; r < t.run_offsets[node + 1]; ++r)
      out.insert(out.end(), t.fan_vertices.begin() + t.vertex_offsets[r],
                 t.fan_vertices.begin() + t.vertex_offsets[r + 1]);
    return out;
  };
  EXPECT_EQ(fan(3), (std::vector<uint32_t>{2, 1, 0}));  // left node: vertex 3
  EXPECT_EQ(fan(4), (std::vector<uint32_t>{3, 1}));     // right node: vertex 0
  EXPECT_EQ(fan(0), (std::vector<uint32_t>{2, 1}));     // base node 0
  Result<VisibleVertexList> list = VisibleVertexList::create(trees.value());
  ASSERT_TRUE(list.is_ok());
  ASSERT_TRUE(list.value().split(0).is_ok());
  // The walk from vr moves the base face to vt, and (vt, vs, vr) fills the
  // opened edge vs-vr.
  EXPECT_EQ(sorted_canonical(list.value().triangles()), sorted_canonical({{3, 1, 2}, {3, 0, 1}}));
}

}  // namespace
}  // namespace lodbake
