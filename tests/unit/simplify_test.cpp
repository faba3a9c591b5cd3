// simplify(): stop criteria, determinism, boundary locking, placements,
// attributes and the refusal of inputs the engine cannot take.
#include "lib/simplify/simplify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

#include "formats/support/quantization.h"
#include "lib/check/mesh_check.h"
#include "lib/simplify/mesh_topology.h"
#include "lib/simplify/pm_replay.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

SimplifyResult run(const TriangleMesh& mesh, const SimplifyOptions& options) {
  Result<SimplifyResult> result = simplify(mesh, options);
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  if (!result.is_ok()) return SimplifyResult();
  return std::move(result).value();
}

void expect_clean(const TriangleMesh& mesh) {
  const MeshCheckReport r = check_mesh(mesh);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.non_manifold_vertices, 0u);
  EXPECT_EQ(r.inconsistent_orientation_edges, 0u);
  EXPECT_EQ(r.degenerate_triangles, 0u);
  EXPECT_EQ(r.unreferenced_vertices, 0u);
}

// Per-corner texture coordinates with a seam along x = 0: each face's
// corners take u = 0 or 1 by the side of its centroid, so the vertices on
// x = 0 carry two values.
void add_seam_at_x0(TriangleMesh* mesh) {
  MeshAttribute& tc = mesh->texcoords;
  tc = MeshAttribute();
  tc.binding = AttributeBinding::kPerCorner;
  tc.components = 2;
  for (const Triangle& t : mesh->triangles) {
    const double cx =
        (double{mesh->positions[t[0]][0]} + mesh->positions[t[1]][0] + mesh->positions[t[2]][0]) /
        3;
    Triangle c;
    for (int k = 0; k < 3; ++k) {
      c[k] = static_cast<uint32_t>(tc.values.size() / 2);
      tc.values.push_back(cx < 0 ? 0.0f : 1.0f);
      tc.values.push_back(0.0f);
    }
    tc.corners.push_back(c);
  }
}

std::set<Vec3f> boundary_positions(const TriangleMesh& mesh) {
  std::set<std::pair<uint32_t, uint32_t>> half_edges;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      half_edges.insert({t[k], t[(k + 1) % 3]});
  }
  std::set<Vec3f> out;
  for (const auto& e : half_edges) {
    if (!half_edges.count({e.second, e.first})) {
      out.insert(mesh.positions[e.first]);
      out.insert(mesh.positions[e.second]);
    }
  }
  return out;
}

TEST(Simplify, StopsAtTargetTriangles) {
  const TriangleMesh bunny = load_clean_mesh("npm_bunny.obj");
  SimplifyOptions options;
  options.target_triangles = 1000;
  const SimplifyResult r = run(bunny, options);
  EXPECT_LE(r.mesh.triangles.size(), 1000u);
  EXPECT_GE(r.mesh.triangles.size(), 998u);
  EXPECT_EQ(r.stats.output_triangles, r.mesh.triangles.size());
  EXPECT_EQ(r.stats.input_triangles, bunny.triangles.size());
  EXPECT_EQ(r.stats.collapses, (bunny.triangles.size() - r.mesh.triangles.size()) / 2);
  expect_clean(r.mesh);
  // A closed genus-0 mesh stays closed and genus 0.
  const MeshCheckReport check = check_mesh(r.mesh);
  EXPECT_TRUE(check.closed());
  EXPECT_EQ(check.genus, 0);
}

TEST(Simplify, StopsAtRatioAndTheFirstCriterionReached) {
  const TriangleMesh bunny = load_clean_mesh("npm_bunny.obj");
  SimplifyOptions options;
  options.target_ratio = 0.25;
  const size_t quarter = bunny.triangles.size() / 4;
  SimplifyResult r = run(bunny, options);
  EXPECT_LE(r.mesh.triangles.size(), quarter);
  EXPECT_GE(r.mesh.triangles.size(), quarter - 1);
  options.target_triangles = 100;  // reached after the ratio
  r = run(bunny, options);
  EXPECT_GE(r.mesh.triangles.size(), quarter - 1);
}

TEST(Simplify, StopsAtMaxError) {
  const TriangleMesh bunny = load_clean_mesh("npm_bunny.obj");
  SimplifyOptions options;
  options.max_error = 0.002;
  options.record_pm = true;
  const SimplifyResult r = run(bunny, options);
  EXPECT_LE(r.stats.max_collapse_error, 0.002);
  EXPECT_LT(r.mesh.triangles.size(), bunny.triangles.size());
  EXPECT_GT(r.mesh.triangles.size(), 100u);
  // Without a limit it goes further, beyond that error.
  options.max_error.reset();
  const SimplifyResult all = run(bunny, options);
  EXPECT_LT(all.mesh.triangles.size(), r.mesh.triangles.size());
  EXPECT_GT(all.stats.max_collapse_error, 0.002);
  // max_error 0 on a curved mesh: nothing but exactly flat collapses.
  options.max_error = 0.0;
  EXPECT_EQ(run(bunny, options).mesh.triangles.size(), bunny.triangles.size());
}

// Optimal placement ranks collapses by a summed quadric, not by their error:
// max_error is checked per collapse on the mean, and the records keep it.
TEST(Simplify, StopsAtMaxErrorInOptimalPlacement) {
  const TriangleMesh bunny = load_clean_mesh("npm_bunny.obj");
  SimplifyOptions options;
  options.placement = Placement::kOptimal;
  options.record_pm = true;
  options.max_error = 0.002;
  const SimplifyResult r = run(bunny, options);
  EXPECT_LE(r.stats.max_collapse_error, 0.002);
  EXPECT_GT(r.stats.max_collapse_error, 0.001);
  ASSERT_TRUE(r.pm.has_value());
  ASSERT_FALSE(r.pm->splits.empty());
  // The records keep the same errors as lengths: the largest is the
  // reported one times the diagonal (every vertex of this bunny is used).
  float largest = 0;
  for (const VertexSplit& split : r.pm->splits)
    largest = std::max(largest, split.error);
  Vec3f lo, hi;
  bounding_box(bunny.positions, &lo, &hi);
  const double diagonal = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  EXPECT_NEAR(largest / diagonal, r.stats.max_collapse_error, 1e-5 * r.stats.max_collapse_error);
  options.max_error = 0.001;
  const SimplifyResult tighter = run(bunny, options);
  EXPECT_LE(tighter.stats.max_collapse_error, 0.001);
  EXPECT_GT(tighter.mesh.triangles.size(), r.mesh.triangles.size());
  options.max_error.reset();
  EXPECT_LT(run(bunny, options).mesh.triangles.size(), r.mesh.triangles.size());
  expect_clean(r.mesh);
}

TEST(Simplify, RunsToTheEndWithoutCriteria) {
  // The tetrahedron cannot lose a vertex; a closed genus-0 mesh ends as a
  // handful of triangles.
  const TriangleMesh tet = load_clean_mesh("cgal_tetrahedron.off");
  EXPECT_EQ(run(tet, SimplifyOptions()).mesh.triangles.size(), 4u);
  const TriangleMesh bunny = load_clean_mesh("npm_bunny.obj");
  const SimplifyResult r = run(bunny, SimplifyOptions());
  EXPECT_LE(r.mesh.triangles.size(), 16u);
  expect_clean(r.mesh);
}

TEST(Simplify, IsDeterministic) {
  const TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  for (int variant = 0; variant < 3; ++variant) {
    SimplifyOptions options;
    options.placement = variant == 1 ? Placement::kOptimal : Placement::kHalf;
    options.height_guard = variant == 2;
    options.record_pm = true;
    options.target_ratio = 0.1;
    const SimplifyResult a = run(mesh, options);
    const SimplifyResult b = run(mesh, options);
    EXPECT_EQ(a.mesh, b.mesh);
    ASSERT_TRUE(a.pm && b.pm);
    EXPECT_EQ(*a.pm, *b.pm);
  }
}

// simplify(TriangleMesh&&) frees the input's geometry early; its result is
// the const& overload's, per-vertex attributes of the PM included (in
// optimal placement the engine's values move, the PM's are the input's).
TEST(Simplify, TakingTheInputGivesTheSameResult) {
  TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  mesh.normals.binding = AttributeBinding::kPerVertex;
  mesh.normals.components = 3;
  for (const Vec3f& p : mesh.positions) {
    const float len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int k = 0; k < 3; ++k)
      mesh.normals.values.push_back(len > 0 ? p[k] / len : 0);
  }
  for (int variant = 0; variant < 3; ++variant) {
    SimplifyOptions options;
    options.placement = variant == 1 ? Placement::kOptimal : Placement::kHalf;
    options.height_guard = variant == 2;
    options.record_pm = variant != 2;
    options.target_ratio = 0.2;
    options.threads = 2;
    const SimplifyResult expected = run(mesh, options);
    TriangleMesh handed = mesh;
    Result<SimplifyResult> taken = simplify(std::move(handed), options);
    ASSERT_TRUE(taken.is_ok()) << taken.status().message();
    EXPECT_EQ(taken.value().mesh, expected.mesh) << "variant " << variant;
    ASSERT_EQ(taken.value().pm.has_value(), expected.pm.has_value());
    if (expected.pm) {
      EXPECT_EQ(*taken.value().pm, *expected.pm) << "variant " << variant;
    }
    EXPECT_EQ(taken.value().stats.collapses, expected.stats.collapses);
    EXPECT_TRUE(handed.positions.empty());
    EXPECT_TRUE(handed.triangles.empty());
    EXPECT_EQ(handed.normals, mesh.normals);
  }
  // A mesh the engine refuses is refused alike.
  TriangleMesh bad = mesh;
  bad.triangles.push_back(bad.triangles[0]);
  const Result<SimplifyResult> by_ref = simplify(bad, SimplifyOptions());
  const Result<SimplifyResult> by_move = simplify(std::move(bad), SimplifyOptions());
  ASSERT_FALSE(by_ref.is_ok());
  ASSERT_FALSE(by_move.is_ok());
  EXPECT_EQ(by_move.status().message(), by_ref.status().message());
}

// The guard only adds refusals: on the bunny it refuses thousands of
// collapses, reaches the same target and gives another sequence.
TEST(Simplify, HeightGuardRefusesCollapsesAndStillReachesTheTarget) {
  const TriangleMesh bunny = load_clean_mesh("stanford_bun_zipper.ply");
  SimplifyOptions options;
  options.target_ratio = 0.1;
  const SimplifyResult plain = run(bunny, options);
  options.height_guard = true;
  const SimplifyResult guarded = run(bunny, options);
  EXPECT_EQ(plain.stats.refused_height, 0u);
  EXPECT_GT(guarded.stats.refused_height, 1000u);
  // Early in a pass a height refusal does not move the pass's limit on, so
  // the passes remove fewer triangles each and there are more of them.
  EXPECT_GT(plain.stats.passes, 1u);
  EXPECT_GT(guarded.stats.passes, plain.stats.passes);
  EXPECT_EQ(guarded.stats.output_triangles, plain.stats.output_triangles);
  EXPECT_FALSE(guarded.mesh == plain.mesh);
  expect_clean(guarded.mesh);
}

// A tilted plane far from the origin: the costs, the pass limits and the
// heights are all the rounding of the float positions, so the guard, which
// compares heights with costs, must still let the plane be simplified.
TEST(Simplify, HeightGuardSimplifiesATiltedPlane) {
  TriangleMesh plane;
  const int n = 40;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float x = static_cast<float>(i) / n;
      const float y = static_cast<float>(j) / n;
      plane.positions.push_back(
          {1000 + 0.6f * x + 0.3f * y, -500 + 0.2f * x + 0.7f * y, 250 + 0.4f * x - 0.5f * y});
    }
  }
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i;
      plane.triangles.push_back({a, a + 1, a + n + 2});
      plane.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  }
  SimplifyOptions options;
  options.target_ratio = 0.1;
  options.height_guard = true;
  const SimplifyResult r = run(plane, options);
  EXPECT_LE(r.mesh.triangle_count(), plane.triangle_count() / 10);
  expect_clean(r.mesh);
}

// With max_error the guard's scale is capped by it; the error bound holds.
TEST(Simplify, HeightGuardKeepsTheMaxError) {
  const TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  SimplifyOptions options;
  options.max_error = 0.004;
  options.height_guard = true;
  options.record_pm = true;
  const SimplifyResult r = run(mesh, options);
  EXPECT_GT(r.stats.collapses, 100u);
  EXPECT_GT(r.stats.refused_height, 0u);
  EXPECT_LE(r.stats.max_collapse_error, 0.004);
  expect_clean(r.mesh);
}

// The factor scales the allowance: a larger one refuses fewer collapses
// (on the bunny at 10%: 31,506 refused tries at the default 4/3, 8,059 at
// 3), each still reaching the target with a clean mesh, by another
// sequence.
TEST(Simplify, HeightGuardFactorSetsHowManyCollapsesItRefuses) {
  const TriangleMesh bunny = load_clean_mesh("stanford_bun_zipper.ply");
  SimplifyOptions options;
  options.target_ratio = 0.1;
  options.height_guard = true;
  const SimplifyResult by_default = run(bunny, options);
  EXPECT_GT(by_default.stats.refused_height, 20000u);
  uint64_t previous = by_default.stats.refused_height;
  for (double factor : {3.0, 30.0}) {
    options.height_guard_factor = factor;
    const SimplifyResult r = run(bunny, options);
    EXPECT_FALSE(r.mesh == by_default.mesh) << factor;
    EXPECT_LT(r.stats.refused_height, previous / 2) << factor;
    EXPECT_GT(r.stats.refused_height, 0u) << factor;
    EXPECT_LE(r.stats.output_triangles, bunny.triangle_count() / 10) << factor;
    expect_clean(r.mesh);
    previous = r.stats.refused_height;
  }
}

TEST(Simplify, HeightGuardFactorMustBeFiniteAndPositive) {
  const TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  for (double factor : {0.0, -1.0, std::numeric_limits<double>::infinity(),
                        std::numeric_limits<double>::quiet_NaN()}) {
    SimplifyOptions options;
    options.height_guard = true;
    options.height_guard_factor = factor;
    Result<SimplifyResult> r = simplify(mesh, options);
    ASSERT_FALSE(r.is_ok()) << factor;
    EXPECT_EQ(r.status().kind(), ErrorKind::kUsage);
    EXPECT_NE(r.status().message().find("factor"), std::string::npos);
  }
  // Without the guard the factor is not used.
  SimplifyOptions options;
  options.height_guard_factor = 0;
  options.target_ratio = 0.5;
  EXPECT_TRUE(simplify(mesh, options).is_ok());
}

TEST(Simplify, HeightGuardNeedsHalfPlacement) {
  const TriangleMesh mesh = load_clean_mesh("cgal_elephant.off");
  SimplifyOptions options;
  options.placement = Placement::kOptimal;
  options.height_guard = true;
  Result<SimplifyResult> r = simplify(mesh, options);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kUsage);
  EXPECT_NE(r.status().message().find("half placement"), std::string::npos);
}

// The listing, the quadric set-up, the input check and the assembly run in
// as many parts as threads; the result must not depend on how many. The
// bunny is above every size from which the parts run in parallel
// (simplify_threads_test.cpp compares 1, 2 and 7 threads on more meshes).
TEST(Simplify, OneThreadAndTwoGiveTheSameResult) {
  const TriangleMesh bunny = load_clean_mesh("stanford_bun_zipper.ply");
  for (Placement placement : {Placement::kHalf, Placement::kOptimal}) {
    for (double ratio : {0.5, 0.02}) {
      SimplifyOptions options;
      options.placement = placement;
      options.record_pm = placement == Placement::kHalf;
      options.target_ratio = ratio;
      options.threads = 1;
      const SimplifyResult one = run(bunny, options);
      options.threads = 2;
      const SimplifyResult two = run(bunny, options);
      EXPECT_EQ(one.mesh, two.mesh) << ratio;
      EXPECT_EQ(one.pm, two.pm) << ratio;
      EXPECT_EQ(one.stats.collapses, two.stats.collapses);
      EXPECT_LT(one.mesh.triangles.size(), bunny.triangles.size());
    }
  }
  // Per-corner values (a seam along x = 0) take the corner-list path.
  TriangleMesh seamed = bunny;
  add_seam_at_x0(&seamed);
  SimplifyOptions options;
  options.target_ratio = 0.1;
  options.threads = 1;
  const SimplifyResult one = run(seamed, options);
  options.threads = 2;
  EXPECT_EQ(one.mesh, run(seamed, options).mesh);
  // The height guard's refusals are made in the walk, which one thread runs.
  SimplifyOptions guarded;
  guarded.height_guard = true;
  guarded.record_pm = true;
  guarded.target_ratio = 0.05;
  guarded.threads = 1;
  const SimplifyResult guarded_one = run(bunny, guarded);
  guarded.threads = 2;
  const SimplifyResult guarded_two = run(bunny, guarded);
  EXPECT_EQ(guarded_one.mesh, guarded_two.mesh);
  EXPECT_EQ(guarded_one.pm, guarded_two.pm);
  EXPECT_EQ(guarded_one.stats.refused_height, guarded_two.stats.refused_height);
}

// The input check's parts report the first problem in vertex order, as
// one thread does.
TEST(Simplify, TwoThreadsNameTheFirstProblemOfTheInput) {
  TriangleMesh mesh = load_clean_mesh("stanford_bun_zipper.ply");
  const auto n = static_cast<uint32_t>(mesh.positions.size());
  // Two triangles hanging off a vertex near each end: two non-manifold
  // vertices, one in each half.
  for (uint32_t v : {n - 5, 7u}) {
    const Vec3f p = mesh.positions[v];
    const auto a = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back({p[0] + 1, p[1], p[2]});
    mesh.positions.push_back({p[0], p[1] + 1, p[2]});
    mesh.triangles.push_back({v, a, a + 1});
  }
  std::string messages[2];
  for (unsigned threads : {1u, 2u}) {
    SimplifyOptions options;
    options.threads = threads;
    const Result<SimplifyResult> r = simplify(mesh, options);
    ASSERT_FALSE(r.is_ok());
    EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
    messages[threads - 1] = r.status().message();
  }
  EXPECT_EQ(messages[0], messages[1]);
  EXPECT_NE(messages[0].find("vertex 7:"), std::string::npos) << messages[0];

  // The check itself, in the ids it is given (simplify() names the problem
  // in input ids by checking the input again on one thread).
  for (unsigned threads : {2u, 7u}) {
    const ParallelScope scope(threads);
    simplify_internal::MeshTopology topology;
    const Status status = simplify_internal::build_topology(mesh, &topology, false, &scope);
    EXPECT_EQ(status.message(), messages[0]);
  }
}

// A fan of `k` triangles around vertex 0 on a circle of rim vertices 1..k:
// a cycle when `closed`, else a chain (the last triangle left out).
TriangleMesh fan_mesh(uint32_t k, bool closed) {
  TriangleMesh mesh;
  mesh.positions.push_back({0, 0, 0});
  for (uint32_t i = 0; i < k; ++i) {
    const double a = 2 * 3.14159265358979 * i / k;
    mesh.positions.push_back({static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0});
  }
  for (uint32_t i = 0; i + (closed ? 0 : 1) < k; ++i)
    mesh.triangles.push_back({0, 1 + i, 1 + (i + 1) % k});
  return mesh;
}

// The input check takes a vectorised path for fans of up to 8 faces, a
// wider one up to 16 and a sorting path above; all must agree on what a
// fan is.
TEST(Simplify, InputCheckTellsFansOfEverySize) {
  for (uint32_t k = 3; k <= 20; ++k) {
    SCOPED_TRACE("fan of " + std::to_string(k));
    for (bool closed : {true, false}) {
      simplify_internal::MeshTopology topology;
      ASSERT_TRUE(simplify_internal::build_topology(fan_mesh(k, closed), &topology).is_ok());
      EXPECT_EQ(topology.boundary[0], closed ? 0 : 1);
      EXPECT_EQ(topology.boundary[1], 1);
    }
    // Two closed fans sharing vertex 0 (a bowtie of k faces in all).
    if (k >= 6) {
      TriangleMesh bowtie = fan_mesh(k / 2, true);
      const TriangleMesh other = fan_mesh(k - k / 2, true);
      const auto offset = static_cast<uint32_t>(bowtie.positions.size()) - 1;
      for (size_t v = 1; v < other.positions.size(); ++v) {
        const Vec3f p = other.positions[v];
        bowtie.positions.push_back({p[0], p[1], p[2] + 1});
      }
      for (const Triangle& t : other.triangles)
        bowtie.triangles.push_back({0, t[1] + offset, t[2] + offset});
      simplify_internal::MeshTopology topology;
      const Status status = simplify_internal::build_topology(bowtie, &topology);
      EXPECT_EQ(
          status.message(),
          "vertex 0: its faces form 2 separate fans (non-manifold vertex; use --repair to fix)");
    }
    // One face turned over: its edges to vertex 0 are walked twice the same way.
    TriangleMesh flipped = fan_mesh(k, true);
    std::swap(flipped.triangles[k / 2][1], flipped.triangles[k / 2][2]);
    simplify_internal::MeshTopology topology;
    const Status status = simplify_internal::build_topology(flipped, &topology);
    EXPECT_NE(status.message().find("is walked the same way by two faces"), std::string::npos)
        << status.message();
  }
}

TEST(Simplify, HalfPlacementKeepsInputPositions) {
  const TriangleMesh mesh = load_clean_mesh("cgal_fandisk.off");
  SimplifyOptions options;
  options.target_ratio = 0.2;
  const SimplifyResult half = run(mesh, options);
  const std::set<Vec3f> input(mesh.positions.begin(), mesh.positions.end());
  for (const Vec3f& p : half.mesh.positions)
    EXPECT_TRUE(input.count(p));

  options.placement = Placement::kOptimal;
  const SimplifyResult optimal = run(mesh, options);
  expect_clean(optimal.mesh);
  size_t moved = 0;
  for (const Vec3f& p : optimal.mesh.positions)
    moved += !input.count(p);
  EXPECT_GT(moved, optimal.mesh.positions.size() / 4);
}

TEST(Simplify, LockBorderKeepsBoundaryVertices) {
  const TriangleMesh mesh = load_clean_mesh("igl_camelhead.off");
  const std::set<Vec3f> border = boundary_positions(mesh);
  ASSERT_FALSE(border.empty());
  for (Placement placement : {Placement::kHalf, Placement::kOptimal}) {
    SimplifyOptions options;
    options.placement = placement;
    options.lock_border = true;
    options.target_ratio = 0.05;
    const SimplifyResult r = run(mesh, options);
    EXPECT_EQ(boundary_positions(r.mesh), border);
    expect_clean(r.mesh);
  }
  // Without the lock the border is simplified too.
  SimplifyOptions options;
  options.target_ratio = 0.05;
  EXPECT_LT(boundary_positions(run(mesh, options).mesh).size(), border.size());
}

// Two flat sheets meeting along x = 0 without being welded, as scans often
// do: the vertices on the seam are twins, one per sheet. Every collapse
// inside the sheets and along their straight outer borders is free.
TriangleMesh unwelded_sheets(int cells) {
  TriangleMesh mesh;
  const auto row = static_cast<uint32_t>(cells + 1);
  for (int side = 0; side < 2; ++side) {
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    for (int j = 0; j <= cells; ++j) {
      for (int i = 0; i <= cells; ++i) {
        const float x = static_cast<float>(side == 0 ? i - cells : i) / static_cast<float>(cells);
        mesh.positions.push_back({x, static_cast<float>(j) / static_cast<float>(cells), 0.0f});
      }
    }
    for (uint32_t j = 0; j < row - 1; ++j) {
      for (uint32_t i = 0; i < row - 1; ++i) {
        const uint32_t v = base + j * row + i;
        mesh.triangles.push_back({v, v + 1, v + row + 1});
        mesh.triangles.push_back({v, v + row + 1, v + row});
      }
    }
  }
  return mesh;
}

// Removing one twin moves its sheet's border away from the other sheet's,
// opening the crack by up to an edge length, which no plane of the flat
// sheets sees: that length squared is the least error such a collapse has,
// in both placements, so a small max_error keeps every twin.
TEST(Simplify, UnweldedSeamStaysClosed) {
  const int cells = 10;
  const TriangleMesh mesh = unwelded_sheets(cells);
  std::multiset<Vec3f> seam;
  for (const Vec3f& p : mesh.positions) {
    if (p[0] == 0.0f) seam.insert(p);
  }
  ASSERT_EQ(seam.size(), 2u * (cells + 1));
  for (Placement placement : {Placement::kHalf, Placement::kOptimal}) {
    SCOPED_TRACE(placement == Placement::kHalf ? "half" : "optimal");
    SimplifyOptions options;
    options.placement = placement;
    options.max_error = 1e-4;
    const SimplifyResult r = run(mesh, options);
    // The output has no unreferenced vertex (expect_clean), so two vertices
    // at a seam position are the two sheets' corners there.
    std::multiset<Vec3f> kept;
    for (const Vec3f& p : r.mesh.positions) {
      if (p[0] == 0.0f) kept.insert(p);
    }
    EXPECT_EQ(kept, seam);
    // The free collapses were made.
    EXPECT_LT(r.mesh.triangles.size(), mesh.triangles.size() / 2);
    expect_clean(r.mesh);
  }
}

TEST(Simplify, BoundaryWeightKeepsTheBorderCloser) {
  // A flat square with a bumpy middle: with a strong boundary quadric the
  // border keeps more vertices at the same triangle count.
  const TriangleMesh mesh = load_clean_mesh("cgal_mushroom.off");
  SimplifyOptions options;
  options.target_ratio = 0.1;
  options.boundary_weight = 0;
  const size_t weak = boundary_positions(run(mesh, options).mesh).size();
  options.boundary_weight = 100;
  const size_t strong = boundary_positions(run(mesh, options).mesh).size();
  EXPECT_GT(strong, weak);
}

TEST(Simplify, PerVertexAttributesFollowTheSurvivor) {
  TriangleMesh mesh = load_clean_mesh("npm_bunny.obj");
  // Attributes derived from the position, so each survivor can be checked.
  mesh.normals.binding = AttributeBinding::kPerVertex;
  mesh.normals.components = 3;
  mesh.texcoords.binding = AttributeBinding::kPerVertex;
  mesh.texcoords.components = 2;
  mesh.normals.values.clear();
  mesh.texcoords.values.clear();
  for (const Vec3f& p : mesh.positions) {
    const double len = std::sqrt(double{p[0]} * p[0] + double{p[1]} * p[1] + double{p[2]} * p[2]);
    for (int k = 0; k < 3; ++k)
      mesh.normals.values.push_back(static_cast<float>(p[k] / len));
    mesh.texcoords.values.push_back(p[0]);
    mesh.texcoords.values.push_back(p[1]);
  }
  SimplifyOptions options;
  options.target_ratio = 0.1;
  options.record_pm = true;
  const SimplifyResult half = run(mesh, options);
  ASSERT_EQ(half.mesh.texcoords.value_count(), half.mesh.positions.size());
  ASSERT_EQ(half.mesh.normals.value_count(), half.mesh.positions.size());
  for (size_t v = 0; v < half.mesh.positions.size(); ++v) {
    EXPECT_EQ(half.mesh.texcoords.values[2 * v], half.mesh.positions[v][0]);
    EXPECT_EQ(half.mesh.texcoords.values[2 * v + 1], half.mesh.positions[v][1]);
  }
  ASSERT_TRUE(half.pm);
  // Half placement: the PM's base is the simplified mesh, attributes included.
  EXPECT_EQ(half.pm->base, half.mesh);
  EXPECT_EQ(half.pm->texcoords.value_count(), mesh.positions.size());

  options.placement = Placement::kOptimal;
  const SimplifyResult optimal = run(mesh, options);
  for (size_t v = 0; v < optimal.mesh.positions.size(); ++v) {
    const float* n = &optimal.mesh.normals.values[3 * v];
    EXPECT_NEAR(double{n[0]} * n[0] + double{n[1]} * n[1] + double{n[2]} * n[2], 1.0, 1e-5);
    // Interpolated along the edge: near the moved vertex's own direction.
    const Vec3f& p = optimal.mesh.positions[v];
    const double len = std::sqrt(double{p[0]} * p[0] + double{p[1]} * p[1] + double{p[2]} * p[2]);
    EXPECT_GT((n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / len, 0.9);
  }
}

TEST(Simplify, SeamVerticesAreLockedUnlessPermissive) {
  TriangleMesh mesh = load_clean_mesh("npm_bunny.obj");
  // Per-corner texture coordinates: a seam along x = 0 (vertices there carry
  // two values, one per side).
  add_seam_at_x0(&mesh);
  const MeshAttribute& tc = mesh.texcoords;
  std::set<uint32_t> seam;
  // The seam vertices: used by triangles on both sides.
  std::vector<int> side(mesh.positions.size(), -1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int s = tc.values[2 * tc.corners[t][0]] == 0.0f ? 0 : 1;
    for (uint32_t v : mesh.triangles[t]) {
      if (side[v] >= 0 && side[v] != s) seam.insert(v);
      side[v] = s;
    }
  }
  ASSERT_GT(seam.size(), 10u);
  SimplifyOptions options;
  options.target_ratio = 0.1;
  const SimplifyResult r = run(mesh, options);
  ASSERT_EQ(r.mesh.texcoords.corners.size(), r.mesh.triangles.size());
  std::set<Vec3f> kept(r.mesh.positions.begin(), r.mesh.positions.end());
  for (uint32_t v : seam)
    EXPECT_TRUE(kept.count(mesh.positions[v]));
  // Every output triangle still lies on one side: corners agree.
  for (const Triangle& c : r.mesh.texcoords.corners) {
    EXPECT_EQ(r.mesh.texcoords.values[2 * c[0]], r.mesh.texcoords.values[2 * c[1]]);
    EXPECT_EQ(r.mesh.texcoords.values[2 * c[0]], r.mesh.texcoords.values[2 * c[2]]);
  }
  options.permissive = true;
  const SimplifyResult p = run(mesh, options);
  std::set<Vec3f> kept_p(p.mesh.positions.begin(), p.mesh.positions.end());
  size_t seam_kept = 0;
  for (uint32_t v : seam)
    seam_kept += kept_p.count(mesh.positions[v]);
  EXPECT_LT(seam_kept, seam.size());
  // A PM cannot carry per-corner values: refused, not dropped.
  options.record_pm = true;
  EXPECT_EQ(simplify(mesh, options).status().kind(), ErrorKind::kUnsupported);
}

// The engine rewrites a pass's triangles after the pass (apply_aliases):
// corners moved from a removed vertex must still take the survivor's value.
// Each corner gets its own value index holding its vertex's (x, y), so no
// vertex is on a seam, and a moved corner that kept the removed vertex's
// value would no longer match its new vertex's position.
TEST(Simplify, CornersMovedToTheSurvivorTakeItsValues) {
  TriangleMesh mesh = load_clean_mesh("npm_bunny.obj");
  MeshAttribute& tc = mesh.texcoords;
  tc.binding = AttributeBinding::kPerCorner;
  tc.components = 2;
  tc.values.clear();
  tc.corners.clear();
  for (const Triangle& t : mesh.triangles) {
    Triangle c;
    for (int k = 0; k < 3; ++k) {
      c[k] = static_cast<uint32_t>(tc.values.size() / 2);
      tc.values.push_back(mesh.positions[t[k]][0]);
      tc.values.push_back(mesh.positions[t[k]][1]);
    }
    tc.corners.push_back(c);
  }
  auto mismatches = [](const TriangleMesh& m) {
    size_t count = 0;
    for (size_t t = 0; t < m.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const Vec3f& p = m.positions[m.triangles[t][k]];
        const uint32_t value = m.texcoords.corners[t][k];
        if (m.texcoords.values[2 * value] != p[0] || m.texcoords.values[2 * value + 1] != p[1]) {
          ++count;
        }
      }
    }
    return count;
  };
  SimplifyOptions options;
  options.target_ratio = 0.1;
  const SimplifyResult r = run(mesh, options);
  ASSERT_EQ(r.mesh.texcoords.corners.size(), r.mesh.triangles.size());
  EXPECT_LE(r.mesh.triangles.size(), mesh.triangles.size() / 10);
  EXPECT_EQ(mismatches(r.mesh), 0u);
  // With `permissive` moved corners keep their own values: the check above
  // can see a corner that was not rewritten.
  options.permissive = true;
  const SimplifyResult p = run(mesh, options);
  EXPECT_GT(mismatches(p.mesh), 0u);
}

// The largest angle, in degrees, by which one collapse of the recorded PM
// turned a face it moved: the PM is collapsed from the full mesh back to its
// base, and each face around vt that survives is compared before and after vt
// becomes vs.
double largest_turn_degrees(const ProgressiveMesh& pm) {
  Result<PmRefiner> refiner = PmRefiner::create(pm);
  EXPECT_TRUE(refiner.is_ok());
  if (!refiner.is_ok()) return 0;
  PmRefiner& r = refiner.value();
  EXPECT_TRUE(r.refine_to(pm.full_vertex_count()).is_ok());
  auto normal = [](const std::vector<Vec3f>& p, const Triangle& t) {
    std::array<double, 3> a{}, b{};
    for (int k = 0; k < 3; ++k) {
      a[k] = double{p[t[1]][k]} - p[t[0]][k];
      b[k] = double{p[t[2]][k]} - p[t[0]][k];
    }
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                 a[0] * b[1] - a[1] * b[0]};
  };
  double largest = 0;
  while (r.applied_splits() > 0) {
    const uint32_t vt = static_cast<uint32_t>(r.vertex_count() - 1);
    const uint32_t vs = pm.splits[r.applied_splits() - 1].vs;
    const TriangleMesh before = r.mesh();
    EXPECT_TRUE(r.collapse_last().is_ok());
    const std::vector<Vec3f>& after_positions = r.mesh().positions;
    for (const Triangle& t : before.triangles) {
      const bool has_vt = t[0] == vt || t[1] == vt || t[2] == vt;
      const bool has_vs = t[0] == vs || t[1] == vs || t[2] == vs;
      if (!has_vt || has_vs) continue;
      Triangle moved = t;
      for (uint32_t& v : moved)
        if (v == vt) v = vs;
      const auto n0 = normal(before.positions, t);
      const auto n1 = normal(after_positions, moved);
      const double l0 = std::sqrt(n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2]);
      const double l1 = std::sqrt(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
      if (!(l0 > 0 && l1 > 0)) continue;
      const double c = (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2]) / (l0 * l1);
      largest =
          std::max(largest, std::acos(std::max(-1.0, std::min(1.0, c))) * 180 / 3.14159265358979);
    }
  }
  return largest;
}

// --max-normal-change: no collapse turns a moved face by more than the
// limit; the default limit lets collapses turn faces further, so the tight
// one changed the collapse sequence.
TEST(Simplify, NormalChangeLimitBoundsEveryCollapse) {
  const TriangleMesh mesh = load_clean_mesh("cgal_fandisk.off");
  SimplifyOptions options;
  options.record_pm = true;
  options.target_triangles = 200;
  const SimplifyResult loose = run(mesh, options);
  ASSERT_TRUE(loose.pm.has_value());
  EXPECT_GT(largest_turn_degrees(*loose.pm), 30.0);
  options.max_normal_change_degrees = 30.0;
  const SimplifyResult tight = run(mesh, options);
  ASSERT_TRUE(tight.pm.has_value());
  EXPECT_LE(largest_turn_degrees(*tight.pm), 30.0 + 1e-3);
  EXPECT_FALSE(tight.pm->splits == loose.pm->splits);
  expect_clean(tight.mesh);
}

TEST(Simplify, RefusesMeshesItCannotTake) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  // Edge 0-1 in three faces.
  mesh.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  Result<SimplifyResult> r = simplify(mesh, SimplifyOptions());
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(r.status().message().find("edge 0-1"), std::string::npos) << r.status().message();

  // Two triangles touching at vertex 0 only: a non-manifold vertex.
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 3, 4}};
  r = simplify(mesh, SimplifyOptions());
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.status().message().find("vertex 0"), std::string::npos) << r.status().message();

  // Inconsistent orientation.
  mesh.triangles = {{0, 1, 2}, {0, 1, 4}};
  EXPECT_FALSE(simplify(mesh, SimplifyOptions()).is_ok());
  mesh.triangles = {{0, 1, 7}};
  EXPECT_FALSE(simplify(mesh, SimplifyOptions()).is_ok());
  mesh.triangles = {{0, 1, 1}};
  EXPECT_FALSE(simplify(mesh, SimplifyOptions()).is_ok());

  SimplifyOptions bad;
  bad.target_ratio = 1.5;
  mesh.triangles = {{0, 1, 2}};
  EXPECT_EQ(simplify(mesh, bad).status().kind(), ErrorKind::kUsage);
}

}  // namespace
}  // namespace lodbake
