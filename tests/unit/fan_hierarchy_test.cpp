// The fan-merge hierarchy (lib/fanmerge) and its FANH section: construction,
// the dual paths at run time, the active-nodes list, the codec.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/fanh.h"
#include "formats/sections/section_validation.h"
#include "lib/fanmerge/fan_build.h"
#include "lib/fanmerge/fan_mesh_state.h"
#include "lib/fanmerge/fan_runtime.h"
#include "lib/simplify/face_quadrics.h"
#include "lib/simplify/mesh_topology.h"
#include "tests/unit/simplify_test_meshes.h"
#include "tests/unit/test_meshes.h"

namespace lodbake {
namespace {

FanBuildResult build(const TriangleMesh& mesh, const FanBuildOptions& options = {}) {
  Result<FanBuildResult> r = build_fan_hierarchy(mesh, options);
  EXPECT_TRUE(r.is_ok()) << r.status().message();
  return r.is_ok() ? std::move(r).value() : FanBuildResult{};
}

FanRuntime runtime(const TriangleMesh& mesh, const FanHierarchy& h) {
  Result<FanRuntime> r = FanRuntime::create(mesh, h);
  EXPECT_TRUE(r.is_ok()) << r.status().message();
  return std::move(r).value();
}

// A valid triangulation: oriented edge-manifold with single fans
// (lib/simplify's check), and no two triangles on the same three vertices.
::testing::AssertionResult valid_triangulation(const TriangleMesh& mesh) {
  simplify_internal::MeshTopology topology;
  Status s = simplify_internal::build_topology(mesh, &topology);
  if (!s.is_ok()) return ::testing::AssertionFailure() << s.message();
  std::set<std::array<uint32_t, 3>> seen;
  for (const Triangle& t : mesh.triangles) {
    std::array<uint32_t, 3> key = t;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) return ::testing::AssertionFailure() << "duplicate triangle";
  }
  return ::testing::AssertionSuccess();
}

// Every active node stands for a present vertex and every present vertex
// has exactly one active node.
void expect_active_list_matches(const FanRuntime& rt) {
  const std::vector<uint32_t> nodes = rt.active().nodes();
  ASSERT_EQ(nodes.size(), rt.vertex_count());
  std::set<uint32_t> vertices;
  for (uint32_t node : nodes) {
    EXPECT_FALSE(rt.held(node)) << node;
    vertices.insert(rt.vertex(node));
  }
  EXPECT_EQ(vertices.size(), nodes.size());
  std::vector<uint8_t> used(rt.leaf_count(), 0);
  for (const Triangle& t : rt.mesh().triangles)
    for (uint32_t v : t)
      used[v] = 1;
  for (uint32_t v : vertices)
    EXPECT_TRUE(used[v]) << "active vertex " << v << " has no triangle";
}

struct Case {
  const char* name;
  TriangleMesh mesh;
};

std::vector<Case> small_cases() {
  std::vector<Case> cases;
  cases.push_back({"torus", test_meshes::torus(24, 16)});
  cases.push_back({"elephant", load_clean_mesh("cgal_elephant.off")});
  cases.push_back({"camelhead (boundary)", load_clean_mesh("igl_camelhead.off")});
  cases.push_back({"fandisk", load_clean_mesh("cgal_fandisk.off")});
  return cases;
}

TEST(FanBuild, ForestShapeAndCounts) {
  for (const Case& c : small_cases()) {
    SCOPED_TRACE(c.name);
    FanBuildResult r = build(c.mesh);
    const FanHierarchy& h = r.hierarchy;
    EXPECT_TRUE(validate_fanh_structure(h).empty());
    EXPECT_TRUE(validate_fanh(h, c.mesh).empty());
    const FanhStats s = fanh_stats(h);
    EXPECT_EQ(s.leaves, c.mesh.vertex_count());
    EXPECT_GT(s.internal_nodes, 0u);
    EXPECT_EQ(s.roots, r.stats.output_vertices);
    // Each merge removes its collapsed children: leaves - roots of them in all.
    EXPECT_EQ(h.children.size() - h.internal_count(), c.mesh.vertex_count() - s.roots);
    EXPECT_GT(s.average_children, 2.0);
    EXPECT_GE(s.depth, 2u);
    EXPECT_TRUE(valid_triangulation(r.coarsest));
    EXPECT_LT(r.coarsest.triangle_count(), c.mesh.triangle_count() / 4);
    for (float e : h.error)
      EXPECT_GE(e, 0.f);
  }
}

// Replays the construction's quadrics independently (sqrt-area plane
// quadrics of the input faces, a centre's quadric growing by each child it
// merges, in fine-path order): at every node, the children after the centre
// are in non-decreasing delta(u) = Q_u(v) / w_u (the fine path is the
// collapse-error order), and the node's error is their sum, Delta(v). On the
// closed meshes, where no boundary planes enter.
TEST(FanBuild, FinePathIsInDeltaOrderAndErrorIsTheirSum) {
  for (const Case& c : small_cases()) {
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (const Triangle& t : c.mesh.triangles)
      for (int k = 0; k < 3; ++k)
        edges.insert({t[k], t[(k + 1) % 3]});
    bool closed = true;
    for (const auto& [a, b] : edges)
      closed = closed && edges.count({b, a}) != 0;
    if (!closed) continue;
    SCOPED_TRACE(c.name);
    const FanHierarchy h = build(c.mesh).hierarchy;
    std::vector<Quadric> q(c.mesh.vertex_count());
    auto at = [&](uint32_t v) { return to_d(c.mesh.positions[v]); };
    for (const Triangle& t : c.mesh.triangles) {
      const Quadric f = sqrt_area_triangle_quadric(at(t[0]), at(t[1]), at(t[2]));
      for (uint32_t v : t)
        q[v] += f;
    }
    std::vector<uint32_t> vertex_of(h.node_count());
    for (uint32_t v = 0; v < h.vertex_count; ++v)
      vertex_of[v] = v;
    size_t checked = 0;
    for (uint32_t i = 0; i < h.internal_count(); ++i) {
      const uint32_t begin = h.child_start[i], end = h.child_start[i + 1];
      const uint32_t v = vertex_of[h.children[begin]];
      vertex_of[h.vertex_count + i] = v;
      double sum = 0, last = -1;
      for (uint32_t k = begin + 1; k < end; ++k) {
        const uint32_t u = vertex_of[h.children[k]];
        const double d = q[u].weight > 0 ? q[u].evaluate(at(v)) / q[u].weight : 0.0;
        ASSERT_GE(d, last) << "node " << i << ", child " << k - begin;
        last = d;
        sum += d;
      }
      ASSERT_NEAR(h.error[i], sum, 1e-5 * sum + 1e-30) << "node " << i;
      for (uint32_t k = begin + 1; k < end; ++k)
        q[v] += q[vertex_of[h.children[k]]];
      ++checked;
    }
    EXPECT_GT(checked, 20u);
  }
}

TEST(FanBuild, StopCriteria) {
  const TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  FanBuildOptions by_count;
  by_count.target_vertices = 800;
  FanBuildResult r = build(mesh, by_count);
  EXPECT_LE(r.stats.output_vertices, 800u);
  EXPECT_GT(r.stats.output_vertices, 700u);  // stops at the first merge reaching it
  FanBuildOptions by_ratio;
  by_ratio.target_ratio = 0.5;
  r = build(mesh, by_ratio);
  EXPECT_LE(r.stats.output_vertices, (mesh.vertex_count() + 1) / 2);
  FanBuildOptions by_error;
  by_error.max_error = 0.002;
  r = build(mesh, by_error);
  EXPECT_GT(r.stats.skipped_error, 0u);
  // Errors are squared lengths; the limit is relative to the diagonal.
  Vec3f lo = mesh.positions[0], hi = mesh.positions[0];
  for (const Vec3f& p : mesh.positions)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
    d2 += double(hi[k] - lo[k]) * (hi[k] - lo[k]);
  for (float e : r.hierarchy.error)
    EXPECT_LE(e, 0.002 * 0.002 * d2 * 1.0001);
  FanBuildResult full = build(mesh);
  EXPECT_GT(r.stats.output_vertices, full.stats.output_vertices);
}

TEST(FanBuild, DegreeWeightingMergesLowDegreeFansFirst) {
  const TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  FanBuildOptions weighted;
  weighted.degree_weight = 2;
  FanBuildResult plain = build(mesh), deg = build(mesh, weighted);
  EXPECT_TRUE(validate_fanh(deg.hierarchy, mesh).empty());
  EXPECT_LT(fanh_stats(deg.hierarchy).average_children,
            fanh_stats(plain.hierarchy).average_children);
}

TEST(FanBuild, RefusesNonManifoldInput) {
  Result<FanBuildResult> r = build_fan_hierarchy(test_meshes::three_on_an_edge(), {});
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
}

TEST(FanBuild, Deterministic) {
  const TriangleMesh mesh = load_clean_mesh("npm_bunny.obj");
  Result<Bytes> a = encode_fanh(build(mesh).hierarchy);
  Result<Bytes> b = encode_fanh(build(mesh).hierarchy);
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  EXPECT_EQ(a.value(), b.value());
}

TEST(FanRuntime, FullFanSplitFromTheCoarsestMeshGivesTheInput) {
  std::vector<Case> cases = small_cases();
  cases.push_back({"bunny", load_clean_mesh("npm_bunny.obj")});
  cases.push_back({"armadillo", load_clean_mesh("cgal_armadillo.off")});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    FanBuildResult r = build(c.mesh);
    FanRuntime rt = runtime(c.mesh, r.hierarchy);
    ASSERT_TRUE(rt.merge_all());
    EXPECT_EQ(rt.mesh().triangles, r.coarsest.triangles);
    EXPECT_EQ(rt.vertex_count(), r.stats.output_vertices);
    expect_active_list_matches(rt);
    ASSERT_TRUE(rt.split_all());
    const TriangleMesh back = rt.mesh();
    EXPECT_EQ(back.positions, c.mesh.positions);
    EXPECT_EQ(back.triangles, c.mesh.triangles);
    expect_active_list_matches(rt);
  }
}

// For every node, from the state its merge was built in: the direct
// fan-merge and its children's collapses one by one give the same mesh
// (same triangles, same order, same orientation), and so do the two splits.
TEST(FanRuntime, DirectFanMergeEqualsTheFinePath) {
  for (const Case& c : small_cases()) {
    SCOPED_TRACE(c.name);
    FanBuildResult r = build(c.mesh);
    FanRuntime rt = runtime(c.mesh, r.hierarchy);
    for (size_t i = 0; i < rt.internal_count(); ++i) {
      const uint32_t node = static_cast<uint32_t>(rt.leaf_count() + i);
      const std::vector<Triangle> before = rt.mesh().triangles;
      ASSERT_TRUE(rt.fan_merge(node)) << node;
      const std::vector<Triangle> direct = rt.mesh().triangles;
      ASSERT_TRUE(rt.fan_split(node)) << node;
      ASSERT_EQ(rt.mesh().triangles, before) << node;
      const uint32_t d = rt.collapsible_children(node);
      for (uint32_t k = 0; k < d; ++k) {
        ASSERT_EQ(rt.merge_pointer(node), k);
        ASSERT_TRUE(rt.advance(node)) << node << " step " << k + 1;
      }
      ASSERT_EQ(rt.mesh().triangles, direct) << node;
      for (uint32_t k = d; k > 0; --k)
        ASSERT_TRUE(rt.retreat(node)) << node << " step " << k;
      ASSERT_EQ(rt.mesh().triangles, before) << node;
      ASSERT_TRUE(rt.fan_merge(node));
    }
    EXPECT_EQ(rt.mesh().triangles, r.coarsest.triangles);
  }
}

// Random advances, retreats, fan-merges and fan-splits over many nodes:
// every state reached is a valid triangulation, the active list follows,
// and enough operations are legal for the mix to be real.
TEST(FanRuntime, AnyMixOfPartialFinePathsIsAValidTriangulation) {
  std::vector<Case> cases = small_cases();
  cases.push_back({"bunny", load_clean_mesh("npm_bunny.obj")});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    FanBuildResult r = build(c.mesh);
    std::mt19937 rng(12345);
    // From the input, then from the coarsest mesh.
    for (int start = 0; start < 2; ++start) {
      FanRuntime rt = runtime(c.mesh, r.hierarchy);
      if (start == 1) {
        ASSERT_TRUE(rt.merge_all());
      }
      uint64_t tried = 0, accepted = 0, partial_seen = 0;
      for (int round = 0; round < 20; ++round) {
        for (int op = 0; op < 500; ++op) {
          // Coarsen at an active node's parent or refine an active node,
          // as a traversal of the active list would.
          const std::vector<uint32_t> active = rt.active().nodes();
          const uint32_t picked = active[rng() % active.size()];
          const uint32_t parent = rt.parent(picked);
          bool ok = false;
          switch (rng() % 4) {
            case 0:
              ok = parent != kNoNode && rt.advance(parent);
              break;
            case 1:
              ok = rt.retreat(picked);
              break;
            case 2:
              ok = parent != kNoNode && rt.fan_merge(parent);
              break;
            default:
              ok = rt.fan_split(picked);
              break;
          }
          ++tried;
          accepted += ok;
        }
        for (size_t i = 0; i < rt.internal_count(); ++i) {
          const uint32_t node = static_cast<uint32_t>(rt.leaf_count() + i);
          const uint32_t p = rt.merge_pointer(node);
          partial_seen += p > 0 && p < rt.collapsible_children(node);
        }
        ASSERT_TRUE(valid_triangulation(rt.mesh())) << "round " << round;
        expect_active_list_matches(rt);
      }
      EXPECT_GT(accepted * 20, tried) << accepted << " of " << tried;
      EXPECT_GT(partial_seen, 0u);
    }
  }
}

// With the construction dependencies (what the replay uses), random
// operations still find legal ones, every state is valid, and from any
// state reached, fan-splitting in reverse construction order gives the input
// exactly and fan-merging in construction order the coarsest mesh: there is
// no dead end.
TEST(FanRuntime, ConstructionDependenciesLeaveNoDeadEnd) {
  std::vector<Case> cases = small_cases();
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    FanBuildResult r = build(c.mesh);
    FanRuntimeOptions options;
    options.construction_dependencies = true;
    Result<FanRuntime> created = FanRuntime::create(c.mesh, r.hierarchy, options);
    ASSERT_TRUE(created.is_ok()) << created.status().message();
    FanRuntime rt = std::move(created).value();
    std::mt19937 rng(777);
    uint64_t accepted = 0;
    for (int start = 0; start < 2; ++start) {
      if (start == 1) {
        ASSERT_TRUE(rt.merge_all());
      }
      for (int op = 0; op < 3000; ++op) {
        const std::vector<uint32_t> active = rt.active().nodes();
        const uint32_t picked = active[rng() % active.size()];
        const uint32_t parent = rt.parent(picked);
        switch (rng() % 4) {
          case 0:
            accepted += parent != kNoNode && rt.advance(parent);
            break;
          case 1:
            accepted += rt.retreat(picked);
            break;
          case 2:
            accepted += parent != kNoNode && rt.fan_merge(parent);
            break;
          default:
            accepted += rt.fan_split(picked);
            break;
        }
      }
      ASSERT_TRUE(valid_triangulation(rt.mesh()));
      expect_active_list_matches(rt);
      ASSERT_TRUE(rt.split_all());
      EXPECT_EQ(rt.mesh().triangles, c.mesh.triangles);
      ASSERT_TRUE(rt.merge_all());
      EXPECT_EQ(rt.mesh().triangles, r.coarsest.triangles);
      ASSERT_TRUE(rt.split_all());
    }
    EXPECT_GT(accepted, 100u);
  }
}

TEST(ActiveNodeList, BlocksOf256AndSwapWithLastOnRemoval) {
  ActiveNodeList list;
  list.reset(1000);
  for (uint32_t i = 0; i < 600; ++i)
    list.add(i);
  EXPECT_EQ(list.block_count(), 3u);
  EXPECT_EQ(list.block_size(0), 256u);
  EXPECT_EQ(list.block_size(2), 600u - 512u);
  list.remove(5);
  EXPECT_EQ(list.block(0)[5], 599u);  // the last entry took its place
  EXPECT_FALSE(list.contains(5));
  list.add(700);
  EXPECT_EQ(list.nodes().back(), 700u);
  for (uint32_t i = 0; i < 600; ++i) {
    if (i != 5) list.remove(i);
  }
  EXPECT_EQ(list.size(), 1u);
  EXPECT_EQ(list.block_count(), 1u);
  EXPECT_EQ(list.block(0)[0], 700u);
}

TEST(FanhSection, RoundTripAndValidation) {
  const TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  const FanHierarchy h = build(mesh).hierarchy;
  Result<Bytes> bytes = encode_fanh(h);
  ASSERT_TRUE(bytes.is_ok());
  FanhSummary summary;
  Result<FanHierarchy> back = decode_fanh(bytes.value().data(), bytes.value().size(), &summary);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(back.value().children, h.children);
  EXPECT_EQ(back.value().child_start, h.child_start);
  EXPECT_EQ(back.value().error, h.error);
  EXPECT_EQ(back.value().removed, h.removed);
  EXPECT_EQ(back.value().removed_start, h.removed_start);
  EXPECT_EQ(back.value().modified, h.modified);
  EXPECT_EQ(back.value().modified_start, h.modified_start);
  EXPECT_EQ(summary.internal_count, h.internal_count());
  EXPECT_TRUE(validate_fanh_payload(bytes.value().data(), bytes.value().size(), mesh).empty());
  Result<FanhSummary> fixed = read_fanh_summary(bytes.value().data(), bytes.value().size());
  ASSERT_TRUE(fixed.is_ok());
  EXPECT_EQ(fixed.value().modified_entries, h.modified.size());
}

TEST(FanhSection, EveryTruncationAndAppendedByteIsRejected) {
  const TriangleMesh mesh = test_meshes::torus(12, 8);
  Result<Bytes> bytes = encode_fanh(build(mesh).hierarchy);
  ASSERT_TRUE(bytes.is_ok());
  const Bytes& b = bytes.value();
  for (size_t n = 0; n < b.size(); ++n)
    EXPECT_FALSE(decode_fanh(b.data(), n).is_ok()) << n;
  Bytes longer = b;
  longer.push_back(0);
  EXPECT_FALSE(decode_fanh(longer.data(), longer.size()).is_ok());
  // Flipped bits never crash; whatever decodes passes the structure checks.
  for (size_t i = 0; i < b.size(); ++i) {
    Bytes flipped = b;
    flipped[i] ^= static_cast<uint8_t>(1u << (i % 8));
    Result<FanHierarchy> d = decode_fanh(flipped.data(), flipped.size());
    if (d.is_ok()) {
      EXPECT_TRUE(validate_fanh_structure(d.value()).empty());
      validate_fanh(d.value(), mesh);
    }
  }
}

TEST(FanhSection, ValidationNamesBrokenForestsAndLists) {
  const TriangleMesh mesh = test_meshes::torus(12, 8);
  const FanHierarchy h = build(mesh).hierarchy;
  ASSERT_GE(h.internal_count(), 2u);
  FanHierarchy twice = h;
  twice.children[twice.child_start[1] + 1] = twice.children[1];
  std::vector<std::string> f = validate_fanh_structure(twice);
  ASSERT_FALSE(f.empty());
  EXPECT_NE(f.front().find("a child twice"), std::string::npos) << f.front();
  FanHierarchy late = h;
  late.children[0] = static_cast<uint32_t>(h.node_count() - 1);
  EXPECT_FALSE(validate_fanh_structure(late).empty());
  FanHierarchy wrong_list = h;
  std::swap(wrong_list.removed.front(), wrong_list.modified.front());
  f = validate_fanh(wrong_list, mesh);
  ASSERT_FALSE(f.empty());
  EXPECT_NE(f.front().find("node"), std::string::npos) << f.front();
  Result<Bytes> bad = encode_fanh(twice);
  EXPECT_FALSE(bad.is_ok());
  Result<FanRuntime> rt = FanRuntime::create(mesh, twice);
  EXPECT_FALSE(rt.is_ok());
}

TEST(FanRuntime, RefusesOperationsTheStateDoesNotAllow) {
  const TriangleMesh mesh = test_meshes::torus(24, 16);
  const FanHierarchy h = build(mesh).hierarchy;
  FanRuntime rt = runtime(mesh, h);
  const uint32_t leaf = 0;
  EXPECT_FALSE(rt.advance(leaf));
  EXPECT_FALSE(rt.fan_merge(leaf));
  EXPECT_FALSE(rt.retreat(leaf));
  EXPECT_FALSE(rt.advance(static_cast<uint32_t>(rt.node_count())));  // out of range
  // The last node is made from earlier ones: it cannot merge before them
  // (its children are not fully merged), and nothing can be split at the input.
  const uint32_t last = static_cast<uint32_t>(rt.node_count() - 1);
  bool has_internal_child = false;
  for (uint32_t i = 0; i <= rt.collapsible_children(last); ++i)
    has_internal_child = has_internal_child || !rt.is_leaf(rt.child(last, i));
  if (has_internal_child) {
    EXPECT_FALSE(rt.fan_merge(last));
  }
  for (uint32_t node = rt.leaf_count(); node < rt.node_count(); ++node)
    EXPECT_FALSE(rt.retreat(node));
  ASSERT_TRUE(rt.merge_all());
  const TriangleMesh coarsest = rt.mesh();
  // A merged child is held by its parent: it cannot split while the parent is merged.
  for (uint32_t node = rt.leaf_count(); node < rt.node_count(); ++node) {
    if (rt.parent(node) == kNoNode) continue;
    EXPECT_TRUE(rt.held(node));
    EXPECT_FALSE(rt.fan_split(node));
    EXPECT_FALSE(rt.retreat(node));
    break;
  }
  EXPECT_FALSE(rt.advance(last));                      // already fully merged
  EXPECT_EQ(rt.mesh().triangles, coarsest.triangles);  // the refusals changed nothing
}

Bytes fan_container(const TriangleMesh& mesh, const FanHierarchy& h, bool with_base) {
  ContainerWriter writer;
  if (with_base) {
    EXPECT_TRUE(writer.add_section(kBaseTag, encode_base(mesh, {}).value(), true).is_ok());
  }
  EXPECT_TRUE(writer.add_section(kFanhTag, encode_fanh(h).value(), true).is_ok());
  return writer.finish().value();
}

TEST(FanhSection, ContainerValidationReplaysTheListsOverBase) {
  const TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  const FanHierarchy h = build(mesh).hierarchy;
  Bytes good = fan_container(mesh, h, true);
  Result<Container> c = read_container(good.data(), good.size());
  ASSERT_TRUE(c.is_ok()) << c.status().message();
  EXPECT_TRUE(validate_sections(c.value()).empty());

  FanHierarchy wrong = h;
  std::swap(wrong.modified[0], wrong.modified[wrong.modified.size() / 2]);
  Bytes bad = fan_container(mesh, wrong, true);
  c = read_container(bad.data(), bad.size());
  ASSERT_TRUE(c.is_ok());
  std::vector<SectionFinding> findings = validate_sections(c.value());
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].tag, "FANH");
  EXPECT_NE(findings[0].message.find("modified triangle"), std::string::npos)
      << findings[0].message;

  Bytes alone = fan_container(mesh, h, false);
  c = read_container(alone.data(), alone.size());
  ASSERT_TRUE(c.is_ok());
  findings = validate_sections(c.value());
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_NE(findings[0].message.find("no BASE"), std::string::npos) << findings[0].message;
}

// The build's order of operations depends on the exact order of each
// vertex's triangle list: the flat lists must behave as std::vector with
// swap-remove, through the inline-to-pool move and the pool's growth.
TEST(FanMeshState, IncidenceListsKeepVectorOrder) {
  constexpr uint32_t kLists = 5;
  fan_internal::IncidenceLists lists;
  lists.init(kLists, {0, 3, 20, 14, 15});
  std::vector<std::vector<uint32_t>> expected(kLists);
  std::mt19937 random(7);
  for (int step = 0; step < 20000; ++step) {
    const uint32_t v = random() % kLists;
    const uint32_t t = random() % 64;
    if (random() % 3 != 0 || expected[v].empty()) {
      lists.push_back(v, t);
      expected[v].push_back(t);
    } else {
      lists.remove(v, t);
      auto& e = expected[v];
      auto it = std::find(e.begin(), e.end(), t);
      if (it != e.end()) {
        *it = e.back();
        e.pop_back();
      }
    }
    const fan_internal::TriangleList got = lists[v];
    ASSERT_EQ(std::vector<uint32_t>(got.begin(), got.end()), expected[v]) << "step " << step;
  }
  for (uint32_t v = 0; v < kLists; ++v) {
    const fan_internal::TriangleList got = lists[v];
    EXPECT_EQ(std::vector<uint32_t>(got.begin(), got.end()), expected[v]);
    EXPECT_EQ(lists.size(v), expected[v].size());
  }
}

}  // namespace
}  // namespace lodbake
