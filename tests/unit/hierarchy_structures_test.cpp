// The three structures lodbake-hierarchy writes, side by side on one balanced
// vertex hierarchy: the hierarchy's selective refiner (ActiveAncestor), the
// split DAG's fronts and the vertex trees' visible vertex list, all built
// from the hierarchy's progressive mesh (hierarchy_to_progressive_mesh).
// For the same front they must give the same triangles, orientation
// included, in one vertex numbering (the PM's: root r is vertex r, split k
// creates vertex #roots + k, a left child keeps its parent's vertex).
//
// A refiner front is the set of splits whose node is split, closed under
// the hierarchy's parents, which for this PM is also the order the vertex
// trees impose (split k's tree parent is the split of its node's parent).
// The three families of legal fronts are not nested: truly selective
// refinement lets a node split before a neighbour whose split created one of
// its faces in the PM's order (not closed under the DAG's parents; on the
// test meshes a random refiner walk is almost never closed), and the DAG lets
// a left child's split come before its parent's when their fans do not
// overlap (not closed under the hierarchy). The comparable fronts are the
// sets closed under both: a refiner walk is taken at checkpoints to the
// smallest such set containing its front (splitting more on the refiner,
// with its own dependencies), and a second walk moves all three structures
// together over fronts legal in the DAG and the trees, where the refiner
// must accept every move.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "lib/dag/dag_fronts.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/hierarchy/selective_refiner.h"
#include "lib/simplify/pm_replay.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "lib/vtrees/visible_vertex_list.h"
#include "split_front_support.h"

namespace lodbake {
namespace {

using front_test::mesh_problem;
using front_test::replay_subset;
using front_test::sorted_canonical;

class StructuresOnMesh : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    input_ = load_clean_mesh(GetParam());
    input_.normals = MeshAttribute();
    input_.texcoords = MeshAttribute();
    pm_ = front_test::balanced_pm(GetParam(), &h_, &node_of_split_);
    ASSERT_GT(pm_.splits.size(), 0u);
    ASSERT_EQ(node_of_split_.size(), pm_.splits.size());
    Result<SplitLineage> lineage = build_split_lineage(pm_);
    ASSERT_TRUE(lineage.is_ok()) << lineage.status().message();
    lineage_ = std::move(lineage).value();
    Result<VsplitDag> dag = reduce_dependencies(lineage_);
    ASSERT_TRUE(dag.is_ok()) << dag.status().message();
    dag_ = std::move(dag).value();
    Result<VertexTrees> trees = build_vertex_trees(pm_);
    ASSERT_TRUE(trees.is_ok()) << trees.status().message();
    trees_ = std::move(trees).value();
    // The PM vertex of every node, as hierarchy_to_progressive_mesh numbers.
    const auto roots = static_cast<uint32_t>(h_.root_count());
    pm_vertex_.assign(h_.node_count(), kNoVertex);
    split_of_node_.assign(h_.node_count(), kNoVertex);
    for (uint32_t r = 0; r < roots; ++r)
      pm_vertex_[r] = r;
    for (uint32_t k = 0; k < node_of_split_.size(); ++k) {
      const uint32_t s = node_of_split_[k];
      ASSERT_NE(pm_vertex_[s], kNoVertex) << "split " << k << " before its parent";
      split_of_node_[s] = k;
      pm_vertex_[h_.first_child[s]] = pm_vertex_[s];
      pm_vertex_[h_.first_child[s] + 1] = roots + k;
    }
  }

  // The refiner's triangles in PM vertex ids, canonical and sorted.
  std::vector<Triangle> refiner_triangles(const SelectiveRefiner& r) const {
    std::vector<Triangle> out;
    for (const Triangle& t : r.triangles())
      out.push_back({pm_vertex_[t[0]], pm_vertex_[t[1]], pm_vertex_[t[2]]});
    return sorted_canonical(out);
  }

  // The splits applied on the refiner's front: nodes split so far (a node is
  // split when it is not active and its parent, if any, is split; parents
  // come first in array order).
  std::vector<uint8_t> applied_splits(const SelectiveRefiner& r) const {
    std::vector<uint8_t> node_split(h_.node_count(), 0);
    std::vector<uint8_t> flags(pm_.splits.size(), 0);
    for (uint32_t s = 0; s < h_.node_count(); ++s) {
      const uint32_t p = h_.parent[s];
      node_split[s] = !r.is_active(s) && (p == kNoNode || node_split[p]);
      if (node_split[s]) flags[split_of_node_[s]] = 1;
    }
    return flags;
  }

  bool closed_under_dag_parents(const std::vector<uint8_t>& flags) const {
    for (uint32_t k = 0; k < flags.size(); ++k) {
      if (!flags[k]) continue;
      for (uint32_t e = dag_.parent_offsets[k]; e < dag_.parent_offsets[k + 1]; ++e) {
        if (!flags[dag_.parents[e]]) return false;
      }
    }
    return true;
  }

  // Adds to `flags` every split it needs under the DAG's and the
  // hierarchy's parents (worklist, so linear in the splits added).
  void close_under_both(std::vector<uint8_t>* flags) const {
    std::vector<uint32_t> work;
    for (uint32_t k = 0; k < flags->size(); ++k) {
      if ((*flags)[k]) work.push_back(k);
    }
    auto need = [&](uint32_t k) {
      if (!(*flags)[k]) {
        (*flags)[k] = 1;
        work.push_back(k);
      }
    };
    while (!work.empty()) {
      const uint32_t k = work.back();
      work.pop_back();
      for (uint32_t e = dag_.parent_offsets[k]; e < dag_.parent_offsets[k + 1]; ++e)
        need(dag_.parents[e]);
      const uint32_t p = h_.parent[node_of_split_[k]];
      if (p != kNoNode) need(split_of_node_[p]);
    }
  }

  // Refines `r` to the smallest front containing its own that is closed
  // under both orders: split what the closure adds (in PM order, parents
  // first), with SelStreamVSplit's dependencies, until nothing is added.
  // Returns that front's splits.
  std::vector<uint8_t> refine_to_common_front(SelectiveRefiner* r) const {
    std::vector<uint8_t> flags = applied_splits(*r);
    for (;;) {
      std::vector<uint8_t> closed = flags;
      close_under_both(&closed);
      if (closed == flags) return flags;
      for (uint32_t k = 0; k < closed.size(); ++k) {
        const uint32_t node = node_of_split_[k];
        if (closed[k] && r->is_active(node)) {
          const Status st = r->split_with_dependencies(node);
          EXPECT_TRUE(st.is_ok()) << st.message();
          if (!st.is_ok()) return flags;
        }
      }
      flags = applied_splits(*r);
    }
  }

  // Moves the DAG fronts and the visible vertex list to the splits `flags`
  // (closed under both orders): collapses from the highest index down, then
  // splits from the lowest up, so every step is legal.
  template <typename Structure>
  static void move_to(Structure* s, const std::vector<uint8_t>& now,
                      const std::vector<uint8_t>& flags) {
    for (uint32_t k = static_cast<uint32_t>(flags.size()); k-- > 0;) {
      if (now[k] && !flags[k]) {
        ASSERT_TRUE(s->collapse(k).is_ok()) << "collapse " << k;
      }
    }
    for (uint32_t k = 0; k < flags.size(); ++k) {
      if (!now[k] && flags[k]) {
        ASSERT_TRUE(s->split(k).is_ok()) << "split " << k;
      }
    }
  }

  // All three (and the independent replay) agree on the front `flags`.
  void expect_same_triangles(const SelectiveRefiner& r, const DagFronts& fronts,
                             const VisibleVertexList& list, const std::vector<uint8_t>& flags,
                             const std::string& where) const {
    const std::vector<Triangle> from_refiner = refiner_triangles(r);
    ASSERT_EQ(mesh_problem(from_refiner), "") << where;
    ASSERT_EQ(from_refiner, sorted_canonical(dag_cut_triangles(lineage_, fronts))) << where;
    ASSERT_EQ(from_refiner, sorted_canonical(list.triangles())) << where;
    ASSERT_EQ(from_refiner, sorted_canonical(replay_subset(pm_, flags))) << where;
  }

  // The PM vertex mesh of a full front, in the input's numbering.
  void expect_input_mesh(const std::vector<Triangle>& tris, const std::string& what) const {
    TriangleMesh full;
    full.positions.resize(pm_.full_vertex_count());
    full.triangles = tris;
    Result<TriangleMesh> mapped = map_to_input(pm_, full);
    ASSERT_TRUE(mapped.is_ok()) << what << ": " << mapped.status().message();
    mapped.value().positions = input_.positions;
    EXPECT_TRUE(same_oriented_triangles(mapped.value(), input_)) << what;
  }

  TriangleMesh input_;
  VertexHierarchy h_;
  std::vector<uint32_t> node_of_split_;
  ProgressiveMesh pm_;
  SplitLineage lineage_;
  VsplitDag dag_;
  VertexTrees trees_;
  std::vector<uint32_t> pm_vertex_;
  std::vector<uint32_t> split_of_node_;
};

std::vector<uint8_t> dag_flags(const DagFronts& fronts) {
  std::vector<uint8_t> flags(fronts.node_count());
  for (uint32_t k = 0; k < flags.size(); ++k)
    flags[k] = fronts.is_split(k);
  return flags;
}

// The walk the refiner allows (splits with SelStreamVSplit's dependencies,
// legal collapses); at checkpoints the refiner is taken to the smallest front
// around its own that the DAG and the trees can also stand on, the DAG and
// the trees are moved there, and the triangles compared.
TEST_P(StructuresOnMesh, RefinerFrontsGiveTheDagCutAndTheTreesTriangles) {
  Result<SelectiveRefiner> r_or = SelectiveRefiner::create(h_);
  ASSERT_TRUE(r_or.is_ok()) << r_or.status().message();
  SelectiveRefiner& r = r_or.value();
  Result<DagFronts> fronts_or = DagFronts::create(dag_);
  ASSERT_TRUE(fronts_or.is_ok());
  DagFronts& fronts = fronts_or.value();
  Result<VisibleVertexList> list_or = VisibleVertexList::create(trees_);
  ASSERT_TRUE(list_or.is_ok());
  VisibleVertexList& list = list_or.value();
  std::vector<uint8_t> now(pm_.splits.size(), 0);  // where fronts and list are
  std::mt19937 rng(2024);
  const int steps = 4000;
  int checkpoints = 0, already_common = 0;
  size_t added = 0;
  for (int step = 0; step < steps; ++step) {
    const std::vector<uint32_t> front = r.front();
    const uint32_t v = front[std::uniform_int_distribution<size_t>(0, front.size() - 1)(rng)];
    const double p_split = step < steps / 3 ? 0.7 : 0.4;
    if (std::uniform_real_distribution<>(0, 1)(rng) < p_split) {
      if (!h_.is_leaf(v)) {
        ASSERT_TRUE(r.split_with_dependencies(v).is_ok()) << "step " << step;
      }
    } else if (h_.parent[v] != kNoNode && r.can_collapse(h_.parent[v])) {
      ASSERT_TRUE(r.collapse(h_.parent[v]).is_ok()) << "step " << step;
    }
    if (step % 50 != 49) continue;
    ++checkpoints;
    const std::vector<uint8_t> walked = applied_splits(r);
    if (closed_under_dag_parents(walked)) ++already_common;
    const std::vector<uint8_t> flags = refine_to_common_front(&r);
    ASSERT_FALSE(HasFailure()) << "step " << step;
    std::vector<uint8_t> check = flags;
    close_under_both(&check);
    ASSERT_EQ(check, flags) << "step " << step;
    for (uint32_t k = 0; k < flags.size(); ++k)
      added += flags[k] && !walked[k];
    move_to(&fronts, now, flags);
    move_to(&list, now, flags);
    ASSERT_FALSE(HasFatalFailure());
    ASSERT_TRUE(fronts.check_counters().empty());
    now = flags;
    expect_same_triangles(r, fronts, list, flags, "step " + std::to_string(step));
    ASSERT_FALSE(HasFatalFailure());
  }
  EXPECT_EQ(checkpoints, steps / 50);
  RecordProperty("already_common", already_common);
  RecordProperty("splits_added_per_checkpoint", static_cast<int>(added / checkpoints));
}

// All three structures moved together over fronts legal in the DAG (Fs, Fc)
// and in the trees: the refiner must accept every such move, and every
// checkpoint has the same triangles in all three. Then every remaining split
// in random DAG order ends at exactly the input mesh in all three, and
// random collapses back end at exactly the base mesh.
TEST_P(StructuresOnMesh, JointWalkAgreesAndEndsAtTheInputAndTheBase) {
  std::mt19937 rng(99);
  for (int run = 0; run < 3; ++run) {
    Result<SelectiveRefiner> r_or = SelectiveRefiner::create(h_);
    ASSERT_TRUE(r_or.is_ok());
    SelectiveRefiner& r = r_or.value();
    Result<DagFronts> fronts_or = DagFronts::create(dag_);
    ASSERT_TRUE(fronts_or.is_ok());
    DagFronts& fronts = fronts_or.value();
    Result<VisibleVertexList> list_or = VisibleVertexList::create(trees_);
    ASSERT_TRUE(list_or.is_ok());
    VisibleVertexList& list = list_or.value();
    auto apply = [&](bool split, uint32_t k) {
      const uint32_t node = node_of_split_[k];
      std::string why;
      if (split) {
        ASSERT_TRUE(r.can_split(node, &why)) << "split " << k << " legal in the DAG: " << why;
        ASSERT_TRUE(fronts.split(k).is_ok());
        ASSERT_TRUE(list.split(k).is_ok());
        ASSERT_TRUE(r.split(node).is_ok());
      } else {
        ASSERT_TRUE(r.can_collapse(node, &why)) << "collapse " << k << " legal in the DAG: " << why;
        ASSERT_TRUE(fronts.collapse(k).is_ok());
        ASSERT_TRUE(list.collapse(k).is_ok());
        ASSERT_TRUE(r.collapse(node).is_ok());
      }
    };
    auto pick = [&](const std::vector<uint32_t>& set) {
      return set[std::uniform_int_distribution<size_t>(0, set.size() - 1)(rng)];
    };
    // A move legal in the DAG may wait for the tree order: try a few.
    auto tree_legal = [&](bool split, uint32_t k) {
      return split ? list.can_split(k) : list.can_collapse(k);
    };
    const int steps = 2000;
    int moves = 0;
    for (int step = 0; step < steps; ++step) {
      const bool want_split = std::uniform_real_distribution<>(0, 1)(rng) < 0.6;
      const std::vector<uint32_t>& set =
          want_split ? fronts.split_front() : fronts.collapse_front();
      for (int attempt = 0; attempt < 8 && !set.empty(); ++attempt) {
        const uint32_t k = pick(set);
        if (!tree_legal(want_split, k)) continue;
        apply(want_split, k);
        ++moves;
        break;
      }
      ASSERT_FALSE(HasFatalFailure()) << "run " << run << " step " << step;
      if (step % 100 == 99) {
        expect_same_triangles(r, fronts, list, dag_flags(fronts),
                              "run " + std::to_string(run) + " step " + std::to_string(step));
        ASSERT_FALSE(HasFatalFailure());
        ASSERT_EQ(applied_splits(r), dag_flags(fronts));
      }
    }
    EXPECT_GT(moves, steps / 2);
    // Every remaining split, in a random order legal in the DAG and the trees.
    for (;;) {
      std::vector<uint32_t> legal;
      for (uint32_t k : fronts.split_front()) {
        if (list.can_split(k)) legal.push_back(k);
      }
      if (legal.empty()) break;
      apply(true, pick(legal));
      ASSERT_FALSE(HasFatalFailure()) << "run " << run;
    }
    ASSERT_EQ(fronts.split_count(), fronts.node_count()) << "a split never became legal";
    EXPECT_EQ(r.front_size(), input_.positions.size());
    const std::string where = "run " + std::to_string(run) + ", all splits";
    expect_same_triangles(r, fronts, list, dag_flags(fronts), where);
    ASSERT_FALSE(HasFatalFailure());
    expect_input_mesh(refiner_triangles(r), where + " (refiner)");
    expect_input_mesh(dag_cut_triangles(lineage_, fronts), where + " (DAG)");
    expect_input_mesh(list.triangles(), where + " (vertex trees)");
    for (;;) {
      std::vector<uint32_t> legal;
      for (uint32_t k : fronts.collapse_front()) {
        if (list.can_collapse(k)) legal.push_back(k);
      }
      if (legal.empty()) break;
      apply(false, pick(legal));
      ASSERT_FALSE(HasFatalFailure()) << "run " << run;
    }
    ASSERT_EQ(fronts.split_count(), 0u);
    const std::vector<Triangle> base = sorted_canonical(pm_.base.triangles);
    EXPECT_EQ(refiner_triangles(r), base);
    EXPECT_EQ(sorted_canonical(dag_cut_triangles(lineage_, fronts)), base);
    EXPECT_EQ(sorted_canonical(list.triangles()), base);
  }
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, StructuresOnMesh,
                         ::testing::Values("npm_bunny.obj",        // closed, genus 0
                                           "cgal_mushroom.off",    // boundary
                                           "cgal_elephant.off",    // genus 3
                                           "igl_fertility.off"));  // genus 4

}  // namespace
}  // namespace lodbake
