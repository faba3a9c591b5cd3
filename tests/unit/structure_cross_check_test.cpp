// --validate's cross-structure check (lib/replay/structure_cross_check.h):
// along random refiner walks and DAG walks on balanced hierarchies, the
// hierarchy's mesh and the DAG's cut agree on the smallest front closed
// under both orders; a mesh of another front is reported; a progressive
// mesh that is not the hierarchy's is refused.
#include "lib/replay/structure_cross_check.h"

#include <gtest/gtest.h>

#include <random>

#include "split_front_support.h"

namespace lodbake {
namespace {

struct Structures {
  VertexHierarchy h;
  ProgressiveMesh pm;
  VsplitDag dag;
};

Structures structures(const std::string& mesh) {
  Structures s;
  s.pm = front_test::balanced_pm(mesh, &s.h);
  Result<VsplitDag> dag = build_vsplit_dag(s.pm);
  EXPECT_TRUE(dag.is_ok()) << dag.status().message();
  if (dag.is_ok()) s.dag = std::move(dag).value();
  return s;
}

class CrossCheckTest : public ::testing::TestWithParam<std::string> {};

TEST_P(CrossCheckTest, RefinerAndDagWalksAgreeOnTheirCommonFronts) {
  const Structures s = structures(GetParam());
  ASSERT_GT(s.pm.splits.size(), 0u);
  Result<StructureCrossCheck> check = StructureCrossCheck::create(s.h, s.pm, s.dag);
  ASSERT_TRUE(check.is_ok()) << check.status().message();
  std::mt19937 rng(7);

  // A refiner walk of random splits (with dependencies) and collapses.
  Result<SelectiveRefiner> refiner = SelectiveRefiner::create(s.h);
  ASSERT_TRUE(refiner.is_ok());
  SelectiveRefiner& r = refiner.value();
  size_t own = 0, checks = 0;
  for (int step = 0; step < 400; ++step) {
    const std::vector<uint32_t> front = r.front();
    const uint32_t v = front[std::uniform_int_distribution<size_t>(0, front.size() - 1)(rng)];
    if (rng() % 3 != 0) {
      if (s.h.first_child[v] != kNoNode) {
        ASSERT_TRUE(r.split_with_dependencies(v).is_ok());
      }
    } else if (s.h.parent[v] != kNoNode && r.can_collapse(s.h.parent[v])) {
      ASSERT_TRUE(r.collapse(s.h.parent[v]).is_ok());
    }
    if (step % 20 != 0) continue;
    std::vector<uint8_t> flags = check.value().refiner_splits(r);
    const bool closed = check.value().close(&flags);
    own += closed;
    ++checks;
    const std::vector<std::string> problems =
        check.value().compare(flags, closed ? &r : nullptr, nullptr);
    ASSERT_TRUE(problems.empty()) << "step " << step << ": " << problems.front();
  }
  EXPECT_EQ(checks, 20u);

  // A DAG walk of random legal splits and collapses.
  Result<DagFronts> fronts = DagFronts::create(s.dag);
  ASSERT_TRUE(fronts.is_ok());
  Result<SplitLineage> lineage = build_split_lineage(s.pm);
  ASSERT_TRUE(lineage.is_ok());
  for (int step = 0; step < 2000; ++step) {
    DagFronts& f = fronts.value();
    const bool split = f.collapse_front().empty() || rng() % 4 != 0;
    const std::vector<uint32_t>& from = split ? f.split_front() : f.collapse_front();
    if (from.empty()) continue;
    const uint32_t n = from[std::uniform_int_distribution<size_t>(0, from.size() - 1)(rng)];
    ASSERT_TRUE((split ? f.split(n) : f.collapse(n)).is_ok());
    if (step % 200 != 0) continue;
    std::vector<uint8_t> flags = check.value().dag_splits(f);
    const bool closed = check.value().close(&flags);
    const std::vector<Triangle> cut = dag_cut_triangles(lineage.value(), f);
    const std::vector<std::string> problems =
        check.value().compare(flags, nullptr, closed ? &cut : nullptr);
    ASSERT_TRUE(problems.empty()) << "step " << step << ": " << problems.front();
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, CrossCheckTest,
                         ::testing::Values("cgal_fandisk.off", "cgal_mushroom.off"));

// The replay's own mesh of another front than the one compared is found.
TEST(CrossCheck, ReportsAMeshOfAnotherFront) {
  const Structures s = structures("cgal_fandisk.off");
  Result<StructureCrossCheck> check = StructureCrossCheck::create(s.h, s.pm, s.dag);
  ASSERT_TRUE(check.is_ok());
  Result<SelectiveRefiner> refiner = SelectiveRefiner::create(s.h);
  ASSERT_TRUE(refiner.is_ok());
  std::vector<uint8_t> base_front(s.pm.splits.size(), 0);
  EXPECT_TRUE(check.value().compare(base_front, &refiner.value(), nullptr).empty());
  // Split the first root: the refiner now holds another front.
  ASSERT_TRUE(refiner.value().split(0).is_ok());
  const std::vector<std::string> problems =
      check.value().compare(base_front, &refiner.value(), nullptr);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(
      problems[0].rfind("cross-check on a front of 0 splits: the replay's refined mesh has ", 0),
      0u)
      << problems[0];
  // A DAG cut of another front likewise.
  std::vector<Triangle> cut = s.pm.base.triangles;
  cut.pop_back();
  EXPECT_EQ(check.value().compare(base_front, nullptr, &cut).size(), 1u);
}

TEST(CrossCheck, RefusesAProgressiveMeshThatIsNotTheHierarchys) {
  const Structures s = structures("cgal_fandisk.off");
  const ProgressiveMesh greedy = front_test::record_half_pm("cgal_fandisk.off");
  Result<VsplitDag> dag = build_vsplit_dag(greedy);
  ASSERT_TRUE(dag.is_ok());
  Result<StructureCrossCheck> check = StructureCrossCheck::create(s.h, greedy, dag.value());
  ASSERT_FALSE(check.is_ok());
  EXPECT_EQ(check.status().kind(), ErrorKind::kInvalidInput);
}

}  // namespace
}  // namespace lodbake
