// The balanced vertex hierarchy: its structure and ids, the choice of the
// fundamental cut vertices, truly selective refinement (random split orders
// end at the input, random walks stay valid, collapsing everything gives
// the base), the conversion to a progressive mesh, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>

#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/hierarchy/selective_refiner.h"
#include "lib/hierarchy/view_criteria.h"
#include "lib/simplify/pm_replay.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

TriangleMesh load(const char* file) {
  TriangleMesh mesh = load_clean_mesh(file);
  mesh.normals = MeshAttribute();
  mesh.texcoords = MeshAttribute();
  return mesh;
}

VertexHierarchy build(const TriangleMesh& mesh) {
  Result<BalancedHierarchy> built = build_balanced_hierarchy(mesh, BalancedBuildOptions());
  EXPECT_TRUE(built.is_ok()) << built.status().message();
  if (!built.is_ok()) return VertexHierarchy();
  return std::move(built).value().hierarchy;
}

// Edge-manifold, consistently oriented (every directed edge once), no
// repeated index, no two triangles on the same three vertices.
std::string triangulation_problem(const std::vector<Triangle>& tris) {
  std::set<std::pair<uint32_t, uint32_t>> half_edges;
  std::set<std::array<uint32_t, 3>> vertex_sets;
  for (const Triangle& t : tris) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return "repeated index";
    for (int k = 0; k < 3; ++k) {
      if (!half_edges.insert({t[k], t[(k + 1) % 3]}).second) {
        return "directed edge " + std::to_string(t[k]) + "-" + std::to_string(t[(k + 1) % 3]) +
               " twice (non-manifold or inconsistent orientation)";
      }
    }
    std::array<uint32_t, 3> s = t;
    std::sort(s.begin(), s.end());
    if (!vertex_sets.insert(s).second) return "duplicate triangle";
  }
  return "";
}

// The refiner's current mesh in input vertex ids (all leaves active).
TriangleMesh as_input_mesh(const VertexHierarchy& h, const SelectiveRefiner& r,
                           const TriangleMesh& input) {
  TriangleMesh out;
  out.positions = input.positions;
  for (const Triangle& t : r.triangles()) {
    out.triangles.push_back({h.input_vertex[t[0]], h.input_vertex[t[1]], h.input_vertex[t[2]]});
  }
  return out;
}

bool in_subtree(const VertexHierarchy& h, uint32_t node, uint32_t root) {
  for (; node != kNoNode; node = h.parent[node]) {
    if (node == root) return true;
  }
  return false;
}

class HierarchyOnMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(HierarchyOnMesh, StructureIdsAndBits) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy h = build(input);
  const std::vector<std::string> problems = validate_hierarchy(h);
  EXPECT_TRUE(problems.empty()) << problems.front();
  const HierarchyShape s = hierarchy_shape(h);
  EXPECT_EQ(s.leaves, input.positions.size());
  EXPECT_EQ(s.nodes, 2 * s.leaves - s.roots);
  EXPECT_LT(s.roots, s.leaves / 4);
  // Balanced: the deepest tree is within a few levels of a perfect one.
  const double perfect = std::log2(static_cast<double>(s.leaves) / s.roots) + 1;
  EXPECT_LE(s.depth, perfect * 2 + 2) << "depth " << s.depth << " perfect " << perfect;
  EXPECT_LE(s.id_bits, 32);
  // Heap ids: children of k are 2k and 2k+1 within the parent's tree.
  const std::vector<HierarchyNodeId> ids = hierarchy_node_ids(h);
  for (uint32_t i = 0; i < h.node_count(); ++i) {
    if (h.is_leaf(i)) continue;
    const uint32_t c = h.first_child[i];
    EXPECT_EQ(ids[c].tree, ids[i].tree);
    EXPECT_EQ(ids[c].heap, 2 * ids[i].heap);
    EXPECT_EQ(ids[c + 1].heap, 2 * ids[i].heap + 1);
    EXPECT_LT(i, c);
  }
}

// The derivation in docs/hierarchy.md: the fundamental cut vertex of a split
// is the third corner of the input face that the wing face (left, right,
// cut) becomes at full resolution, so that input face has one corner in the
// left subtree, the next (counter-clockwise) in the right subtree and the
// cut vertex last; the right wing likewise with the subtrees swapped.
TEST_P(HierarchyOnMesh, FundamentalCutVerticesAreTheWingFacesThirdCorners) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy h = build(input);
  std::vector<uint32_t> leaf_of(input.positions.size());
  for (uint32_t i = 0; i < h.node_count(); ++i) {
    if (h.is_leaf(i)) leaf_of[h.input_vertex[i]] = i;
  }
  std::map<uint32_t, std::vector<Triangle>> faces_of_leaf;
  for (const Triangle& t : input.triangles) {
    const Triangle lt{leaf_of[t[0]], leaf_of[t[1]], leaf_of[t[2]]};
    for (uint32_t v : lt)
      faces_of_leaf[v].push_back(lt);
  }
  size_t checked = 0;
  for (uint32_t s = 0; s < h.node_count(); ++s) {
    if (h.is_leaf(s)) continue;
    const uint32_t left = h.first_child[s];
    const uint32_t right = left + 1;
    for (int side = 0; side < 2; ++side) {
      const uint32_t cut = side == 0 ? h.cut_left[s] : h.cut_right[s];
      if (cut == kNoNode) continue;
      const uint32_t first = side == 0 ? left : right;
      const uint32_t second = side == 0 ? right : left;
      size_t found = 0;
      for (const Triangle& t : faces_of_leaf[cut]) {
        const int k = t[0] == cut ? 0 : (t[1] == cut ? 1 : 2);
        if (in_subtree(h, t[(k + 1) % 3], first) && in_subtree(h, t[(k + 2) % 3], second)) ++found;
      }
      EXPECT_EQ(found, 1u) << "node " << s << " side " << side;
      ++checked;
    }
  }
  EXPECT_GT(checked, h.node_count() / 2);
}

TEST_P(HierarchyOnMesh, RandomSplitOrdersEndAtTheInput) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy h = build(input);
  std::mt19937 rng(7);
  for (int run = 0; run < 4; ++run) {
    Result<SelectiveRefiner> created = SelectiveRefiner::create(h);
    ASSERT_TRUE(created.is_ok()) << created.status().message();
    SelectiveRefiner& r = created.value();
    std::vector<uint32_t> open;  // active internal nodes
    for (uint32_t i = 0; i < h.root_count(); ++i) {
      if (!h.is_leaf(i)) open.push_back(i);
    }
    size_t step = 0;
    while (!open.empty()) {
      const size_t pick = std::uniform_int_distribution<size_t>(0, open.size() - 1)(rng);
      const uint32_t node = open[pick];
      open[pick] = open.back();
      open.pop_back();
      if (!r.is_active(node)) continue;  // split earlier as a dependency
      std::vector<uint32_t> made;
      const Status st = r.split_with_dependencies(node, &made);
      ASSERT_TRUE(st.is_ok()) << st.message();
      for (uint32_t m : made) {
        const uint32_t c = h.first_child[m];
        for (uint32_t child : {c, c + 1}) {
          if (!h.is_leaf(child)) open.push_back(child);
        }
      }
      if (++step % 997 == 0) {
        const std::string problem = triangulation_problem(r.triangles());
        ASSERT_EQ(problem, "") << "run " << run << " step " << step;
      }
    }
    EXPECT_EQ(r.front_size(), input.positions.size());
    EXPECT_TRUE(same_oriented_triangles(as_input_mesh(h, r, input), input)) << "run " << run;
  }
}

TEST_P(HierarchyOnMesh, RefinerByIndexMakesTheSameSplitsAsWithIds) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy h = build(input);
  Result<SelectiveRefiner> with_ids = SelectiveRefiner::create(h);
  Result<SelectiveRefiner> by_index = SelectiveRefiner::create_by_index(h);
  ASSERT_TRUE(with_ids.is_ok() && by_index.is_ok());
  std::vector<uint32_t> made_with_ids, made_by_index;
  for (uint32_t s = 0; s < h.node_count(); ++s) {
    if (h.is_leaf(s)) continue;
    if (with_ids.value().is_active(s)) {
      ASSERT_TRUE(with_ids.value().split_with_dependencies(s, &made_with_ids).is_ok());
    }
    if (by_index.value().is_active(s)) {
      ASSERT_TRUE(by_index.value().split_with_dependencies(s, &made_by_index).is_ok());
    }
  }
  EXPECT_FALSE(made_by_index.empty());
  EXPECT_EQ(made_by_index, made_with_ids);
  EXPECT_EQ(by_index.value().triangles(), with_ids.value().triangles());
  EXPECT_EQ(by_index.value().front_size(), input.positions.size());
}

TEST_P(HierarchyOnMesh, RandomWalksStayValidAndCollapseToTheBase) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy h = build(input);
  std::mt19937 rng(11);
  Result<SelectiveRefiner> created = SelectiveRefiner::create(h);
  ASSERT_TRUE(created.is_ok()) << created.status().message();
  SelectiveRefiner& r = created.value();
  // Refine to about a third first so the walk has room both ways.
  size_t splits = 0, collapses = 0, refused = 0;
  for (int step = 0; step < 6000; ++step) {
    const std::vector<uint32_t> front = r.front();
    const uint32_t v = front[std::uniform_int_distribution<size_t>(0, front.size() - 1)(rng)];
    const bool refine = step < 1500 || std::uniform_int_distribution<int>(0, 1)(rng) == 0;
    if (refine) {
      if (h.is_leaf(v)) continue;
      if (r.can_split(v)) {
        ASSERT_TRUE(r.split(v).is_ok());
        ++splits;
      } else {
        ++refused;
        ASSERT_TRUE(r.split_with_dependencies(v).is_ok());
        ++splits;
      }
    } else {
      const uint32_t p = h.parent[v];
      if (p == kNoNode) continue;
      if (!r.can_collapse(p)) {
        ++refused;
        continue;
      }
      ASSERT_TRUE(r.collapse(p).is_ok());
      ++collapses;
    }
    if (step % 20 == 0 || input.positions.size() < 4000) {
      const std::string problem = triangulation_problem(r.triangles());
      ASSERT_EQ(problem, "") << "step " << step;
    }
  }
  EXPECT_GT(splits, 1000u);
  EXPECT_GT(collapses, 500u);
  // Collapse everything.
  const Status down = r.collapse_to_base();
  ASSERT_TRUE(down.is_ok()) << down.message();
  EXPECT_EQ(r.front_size(), h.root_count());
  TriangleMesh now = r.current_mesh();
  EXPECT_TRUE(same_oriented_triangles(now, h.base));
}

TEST_P(HierarchyOnMesh, ActiveAncestorByRightShiftMatchesTheParentWalk) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy h = build(input);
  Result<SelectiveRefiner> created = SelectiveRefiner::create(h);
  ASSERT_TRUE(created.is_ok());
  SelectiveRefiner& r = created.value();
  std::mt19937 rng(3);
  for (int i = 0; i < 3000; ++i) {
    const std::vector<uint32_t> front = r.front();
    const uint32_t v = front[std::uniform_int_distribution<size_t>(0, front.size() - 1)(rng)];
    if (!h.is_leaf(v)) (void)r.split_with_dependencies(v);
  }
  for (uint32_t leaf = 0; leaf < h.node_count(); ++leaf) {
    if (!h.is_leaf(leaf)) continue;
    const uint32_t a = r.active_ancestor(leaf);
    EXPECT_EQ(r.active_ancestor_id(r.id_of(leaf)), r.id_of(a));
    EXPECT_EQ(r.node_of(r.id_of(a)), a);
  }
}

TEST_P(HierarchyOnMesh, ProgressiveMeshReplaysToTheInput) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy h = build(input);
  Result<ProgressiveMesh> pm = hierarchy_to_progressive_mesh(h);
  ASSERT_TRUE(pm.is_ok()) << pm.status().message();
  EXPECT_EQ(pm.value().full_vertex_count(), input.positions.size());
  Result<TriangleMesh> full = mesh_at_lod(pm.value(), pm.value().full_vertex_count());
  ASSERT_TRUE(full.is_ok()) << full.status().message();
  Result<TriangleMesh> mapped = map_to_input(pm.value(), full.value());
  ASSERT_TRUE(mapped.is_ok()) << mapped.status().message();
  EXPECT_TRUE(same_oriented_triangles(mapped.value(), input));
  EXPECT_EQ(mapped.value().positions, input.positions);
}

TEST_P(HierarchyOnMesh, DeterministicAndSectionsRoundTrip) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy a = build(input);
  const VertexHierarchy b = build(input);
  Result<Bytes> ea = encode_vhie(a);
  Result<Bytes> eb = encode_vhie(b);
  ASSERT_TRUE(ea.is_ok()) << ea.status().message();
  ASSERT_TRUE(eb.is_ok());
  EXPECT_EQ(ea.value(), eb.value());
  Result<VertexHierarchy> back = decode_vhie(ea.value().data(), ea.value().size(), a.base);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  const VertexHierarchy& d = back.value();
  EXPECT_EQ(d.parent, a.parent);
  EXPECT_EQ(d.first_child, a.first_child);
  EXPECT_EQ(d.position, a.position);
  EXPECT_EQ(d.cut_left, a.cut_left);
  EXPECT_EQ(d.cut_right, a.cut_right);
  EXPECT_EQ(d.input_vertex, a.input_vertex);
  EXPECT_EQ(d.error, a.error);

  Result<std::vector<NodeRefinement>> rf = compute_refinement_data(a, input);
  ASSERT_TRUE(rf.is_ok()) << rf.status().message();
  Result<Bytes> er = encode_rfin(a, rf.value());
  ASSERT_TRUE(er.is_ok()) << er.status().message();
  Result<std::vector<NodeRefinement>> rb = decode_rfin(er.value().data(), er.value().size(), a);
  ASSERT_TRUE(rb.is_ok()) << rb.status().message();
  for (uint32_t i = 0; i < a.node_count(); ++i) {
    if (a.is_leaf(i)) continue;
    const NodeRefinement& x = rf.value()[i];
    const NodeRefinement& y = rb.value()[i];
    EXPECT_EQ(x.radius, y.radius);
    EXPECT_EQ(x.mu2, y.mu2);
    EXPECT_EQ(x.delta2, y.delta2);
    // The stored cone contains the computed one.
    const Vec3f& p = x.cone_axis;
    const Vec3f& q = y.cone_axis;
    const double cx = double{p[1]} * q[2] - double{p[2]} * q[1];
    const double cy = double{p[2]} * q[0] - double{p[0]} * q[2];
    const double cz = double{p[0]} * q[1] - double{p[1]} * q[0];
    const double dd = double{p[0]} * q[0] + double{p[1]} * q[1] + double{p[2]} * q[2];
    const double between = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dd);
    EXPECT_GE(y.cone_half_angle + 1e-6, std::min(3.14159265, between + x.cone_half_angle));
  }
}

// The client loop of section 5.3 on RFIN data: a near view refines more
// than a far one, the mesh stays valid, and backing away coarsens again.
TEST_P(HierarchyOnMesh, AdaptsToTheView) {
  const TriangleMesh input = load(GetParam());
  const VertexHierarchy h = build(input);
  Result<std::vector<NodeRefinement>> data = compute_refinement_data(h, input);
  ASSERT_TRUE(data.is_ok()) << data.status().message();
  Vec3f lo = input.positions[0], hi = input.positions[0];
  for (const Vec3f& p : input.positions) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  const float diag =
      std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const Vec3f center{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  Result<SelectiveRefiner> created = SelectiveRefiner::create(h);
  ASSERT_TRUE(created.is_ok());
  SelectiveRefiner& r = created.value();
  ViewParameters view;
  view.kappa = 0.002f;
  view.eye = {center[0], center[1], center[2] + 1.5f * diag};
  Result<AdaptStats> near = adapt_to_view(&r, h, data.value(), view);
  ASSERT_TRUE(near.is_ok()) << near.status().message();
  const size_t near_front = r.front_size();
  EXPECT_GT(near_front, h.root_count());
  EXPECT_EQ(triangulation_problem(r.triangles()), "");
  view.eye = {center[0], center[1], center[2] + 200.0f * diag};
  Result<AdaptStats> far = adapt_to_view(&r, h, data.value(), view);
  ASSERT_TRUE(far.is_ok()) << far.status().message();
  EXPECT_GT(far.value().collapses, 0u);
  EXPECT_LT(r.front_size(), near_front);
  EXPECT_EQ(triangulation_problem(r.triangles()), "");
}

TEST(Qrefine, FrustumBackFacingAndScreenSpaceError) {
  NodeRefinement d;
  d.radius = 1;
  d.cone_axis = {0, 0, 1};
  d.cone_half_angle = 0.2f;
  d.mu2 = 0.01f;  // mu = 0.1
  d.delta2 = 0;
  ViewParameters view;
  view.kappa = 0.01f;
  view.eye = {0, 0, 5};                      // facing the node's normal
  EXPECT_TRUE(qrefine(d, {0, 0, 0}, view));  // 0.1 / 5 = 0.02 > kappa
  view.eye = {0, 0, 50};
  EXPECT_FALSE(qrefine(d, {0, 0, 0}, view));  // 0.1 / 50 = 0.002 < kappa
  view.eye = {0, 0, -5};
  EXPECT_FALSE(qrefine(d, {0, 0, 0}, view));  // the cone faces away
  d.cone_half_angle = 2.0f;
  EXPECT_TRUE(qrefine(d, {0, 0, 0}, view));  // a wide cone never faces away
  view.eye = {0, 0, 5};
  view.frustum = {{1, 0, 0, -3}};  // x >= 3: the sphere (x in [-1, 1]) is outside
  EXPECT_FALSE(qrefine(d, {0, 0, 0}, view));
  view.frustum = {{1, 0, 0, 0.5f}};
  EXPECT_TRUE(qrefine(d, {0, 0, 0}, view));
  // delta only counts where the surface is seen edge-on.
  d.mu2 = 0;
  d.delta2 = 0.01f;
  view.frustum.clear();
  EXPECT_FALSE(qrefine(d, {0, 0, 0}, view));  // face-on: no projected deviation
  view.eye = {5, 0, 0.1f};
  EXPECT_TRUE(qrefine(d, {0, 0, 0}, view));  // edge-on
  NodeRefinement leaf;
  EXPECT_FALSE(qrefine(leaf, {0, 0, 0}, view));
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, HierarchyOnMesh,
                         ::testing::Values("npm_bunny.obj",        // closed, genus 0
                                           "cgal_mushroom.off",    // boundary
                                           "cgal_elephant.off",    // genus 3
                                           "igl_fertility.off"));  // genus 4

}  // namespace
}  // namespace lodbake
