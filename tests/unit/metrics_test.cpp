// measure_surface_distance: exact answers on shapes whose distances are known
// in closed form, the one-sided/symmetric relation, the sample counts,
// determinism across runs and thread counts on a real scan, and the errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include "lib/meshio/mesh_import.h"
#include "lib/metrics/surface_distance.h"
#include "tests/unit/test_meshes.h"

namespace lodbake {
namespace {

// The unit cube [0,1]^3 moved by (dx, 0, 0), outward-wound.
TriangleMesh cube(float dx) {
  std::vector<Vec3f> p;
  for (int i = 0; i < 8; ++i) {
    p.push_back({static_cast<float>(i & 1) + dx, static_cast<float>((i >> 1) & 1),
                 static_cast<float>((i >> 2) & 1)});
  }
  return test_meshes::make(p, {{0, 2, 3},
                               {0, 3, 1},
                               {4, 5, 7},
                               {4, 7, 6},
                               {0, 1, 5},
                               {0, 5, 4},
                               {2, 6, 7},
                               {2, 7, 3},
                               {0, 4, 6},
                               {0, 6, 2},
                               {1, 3, 7},
                               {1, 7, 5}});
}

// An n x n grid of squares over [0,1]^2 at height z; the centre vertex
// (n even) raised by `bump`.
TriangleMesh grid(int n, float z, float bump) {
  std::vector<Vec3f> p;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const bool centre = i == n / 2 && j == n / 2;
      p.push_back({static_cast<float>(i) / n, static_cast<float>(j) / n, z + (centre ? bump : 0)});
    }
  }
  std::vector<Triangle> t;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t v = static_cast<uint32_t>(j * (n + 1) + i);
      const uint32_t row = static_cast<uint32_t>(n + 1);
      t.push_back({v, v + 1, v + row + 1});
      t.push_back({v, v + row + 1, v + row});
    }
  }
  return test_meshes::make(p, t);
}

TriangleMesh load_shared(const std::string& name) {
  const char* dir = std::getenv("LODBAKE_SHARED_DATA");
  EXPECT_NE(dir, nullptr) << "LODBAKE_SHARED_DATA is not set";
  if (dir == nullptr) return {};
  ImportReport report;
  auto mesh = import_mesh_file(std::string(dir) + "/meshes/" + name, &report);
  EXPECT_TRUE(mesh.is_ok()) << mesh.status().message();
  return mesh.is_ok() ? std::move(mesh).value() : TriangleMesh();
}

// Enough samples for every expectation here, few enough for sanitizer builds.
DistanceOptions small_budget() {
  DistanceOptions options;
  options.area_samples = 20000;
  return options;
}

void expect_identical(const SurfaceDistance& x, const SurfaceDistance& y) {
  EXPECT_EQ(x.a_to_b.max, y.a_to_b.max);
  EXPECT_EQ(x.a_to_b.mean, y.a_to_b.mean);
  EXPECT_EQ(x.b_to_a.max, y.b_to_a.max);
  EXPECT_EQ(x.b_to_a.mean, y.b_to_a.mean);
  EXPECT_EQ(x.a_to_b.area_samples, y.a_to_b.area_samples);
  EXPECT_EQ(x.b_to_a.vertex_samples, y.b_to_a.vertex_samples);
  EXPECT_EQ(x.hausdorff, y.hausdorff);
  EXPECT_EQ(x.mean, y.mean);
  EXPECT_EQ(x.hausdorff_relative, y.hausdorff_relative);
  EXPECT_EQ(x.mean_relative, y.mean_relative);
}

TEST(SurfaceDistance, IdenticalMeshesAreAtZero) {
  const TriangleMesh c = cube(0);
  auto d = measure_surface_distance(c, c, small_budget());
  ASSERT_TRUE(d.is_ok()) << d.status().message();
  EXPECT_EQ(d.value().hausdorff, 0);
  EXPECT_EQ(d.value().mean, 0);
  EXPECT_NEAR(d.value().diagonal, std::sqrt(3.0), 1e-12);

  const TriangleMesh bunny = load_shared("stanford_bun_zipper.ply");
  auto db = measure_surface_distance(bunny, bunny, small_budget());
  ASSERT_TRUE(db.is_ok()) << db.status().message();
  // Area samples are computed points, so their closest point on the same
  // triangle can differ from them by rounding only.
  EXPECT_LT(db.value().hausdorff_relative, 1e-12);
  EXPECT_LT(db.value().mean_relative, 1e-13);
}

TEST(SurfaceDistance, CubeOffsetByDIsAtD) {
  const float d = 0.125f;
  auto result = measure_surface_distance(cube(0), cube(d), small_budget());
  ASSERT_TRUE(result.is_ok()) << result.status().message();
  const SurfaceDistance& r = result.value();
  // The face x=0 of the first cube lies at d from the second one's face
  // x=d everywhere, and no point of either surface is farther than d.
  EXPECT_NEAR(r.a_to_b.max, d, 1e-12);
  EXPECT_NEAR(r.b_to_a.max, d, 1e-12);
  EXPECT_NEAR(r.hausdorff, d, 1e-12);
  EXPECT_NEAR(r.hausdorff_relative, d / std::sqrt(3.0), 1e-12);
  EXPECT_GT(r.mean, 0);
  EXPECT_LT(r.mean, d);
}

TEST(SurfaceDistance, ParallelPlanesGiveTheirGapAsMaxAndMean) {
  const double gap = 0.25;
  auto result =
      measure_surface_distance(grid(4, 0, 0), grid(2, static_cast<float>(gap), 0), small_budget());
  ASSERT_TRUE(result.is_ok()) << result.status().message();
  const SurfaceDistance& r = result.value();
  EXPECT_NEAR(r.a_to_b.max, gap, 1e-12);
  EXPECT_NEAR(r.a_to_b.mean, gap, 1e-12);
  EXPECT_NEAR(r.b_to_a.mean, gap, 1e-12);
  EXPECT_NEAR(r.mean, gap, 1e-12);
  EXPECT_NEAR(r.hausdorff, gap, 1e-12);
}

TEST(SurfaceDistance, BumpHeightIsTheHausdorffDistance) {
  const float h = 0.0625f;
  const TriangleMesh bumped = grid(8, 0, h);
  const TriangleMesh flat = grid(8, 0, 0);
  auto result = measure_surface_distance(bumped, flat, small_budget());
  ASSERT_TRUE(result.is_ok()) << result.status().message();
  const SurfaceDistance& r = result.value();
  // The apex is h above the flat plane; every point of the flat plane is
  // closer than h to the slanted faces around the apex.
  EXPECT_NEAR(r.a_to_b.max, h, 1e-12);
  EXPECT_GT(r.b_to_a.max, 0);
  EXPECT_LT(r.b_to_a.max, h * 0.999);
  EXPECT_EQ(r.hausdorff, std::max(r.a_to_b.max, r.b_to_a.max));
  EXPECT_EQ(r.mean, 0.5 * (r.a_to_b.mean + r.b_to_a.mean));

  // One-sided values swap with the arguments; the symmetric ones do not move.
  auto swapped = measure_surface_distance(flat, bumped, small_budget());
  ASSERT_TRUE(swapped.is_ok());
  EXPECT_EQ(swapped.value().a_to_b.max, r.b_to_a.max);
  EXPECT_EQ(swapped.value().b_to_a.max, r.a_to_b.max);
  EXPECT_EQ(swapped.value().hausdorff, r.hausdorff);
  EXPECT_EQ(swapped.value().mean, r.mean);
}

TEST(SurfaceDistance, AreaSamplesFindDistancesAwayFromVertices) {
  // The coarse square's vertices are its corners, which lie on the bumped
  // grid: only samples inside its triangles see the bump.
  const float h = 0.0625f;
  auto result = measure_surface_distance(grid(1, 0, 0), grid(8, 0, h), small_budget());
  ASSERT_TRUE(result.is_ok());
  EXPECT_GT(result.value().a_to_b.max, 0.5 * h);
  EXPECT_LT(result.value().a_to_b.max, h);

  DistanceOptions vertices_only;
  vertices_only.area_samples = 0;
  auto coarse = measure_surface_distance(grid(1, 0, 0), grid(8, 0, h), vertices_only);
  ASSERT_TRUE(coarse.is_ok());
  EXPECT_EQ(coarse.value().a_to_b.max, 0);
  EXPECT_EQ(coarse.value().a_to_b.area_samples, 0u);
}

TEST(SurfaceDistance, SampleCountsAndDiagonalFollowTheReferencedVertices) {
  TriangleMesh a = cube(0);
  a.positions.push_back({100, 100, 100});  // unreferenced: not sampled, not in the box
  DistanceOptions options;
  options.area_samples = 1000;
  auto result = measure_surface_distance(a, grid(2, 0, 0), options);
  ASSERT_TRUE(result.is_ok());
  const SurfaceDistance& r = result.value();
  EXPECT_EQ(r.a_to_b.vertex_samples, 8u);
  EXPECT_EQ(r.a_to_b.area_samples, 1000u);
  EXPECT_EQ(r.b_to_a.vertex_samples, 9u);
  EXPECT_EQ(r.b_to_a.area_samples, 1000u);
  EXPECT_NEAR(r.diagonal, std::sqrt(3.0), 1e-12);
  // The cube's top face is at 1 from the square z=0, its bottom face on it.
  EXPECT_NEAR(r.a_to_b.max, 1, 1e-12);
  EXPECT_EQ(r.b_to_a.max, 0);
}

TEST(SurfaceDistance, DeterministicAcrossRunsAndThreadCounts) {
  // A real scan of 20k triangles (small enough for sanitizer builds) and a
  // copy deformed by a smooth field of 0.2% of its size.
  const TriangleMesh scan = load_shared("cgal_ChineseDragon-10kv.off");
  ASSERT_FALSE(scan.triangles.empty());
  float lo = scan.positions[0][0];
  float hi = lo;
  for (const Vec3f& p : scan.positions) {
    lo = std::min({lo, p[0], p[1], p[2]});
    hi = std::max({hi, p[0], p[1], p[2]});
  }
  const float size = hi - lo;
  const float amplitude = 0.002f * size;
  const float frequency = 20.0f / size;
  TriangleMesh moved = scan;
  for (Vec3f& p : moved.positions) {
    p[0] += amplitude * std::sin(frequency * p[1]);
    p[1] += amplitude * std::cos(frequency * p[2]);
  }
  DistanceOptions options = small_budget();
  options.threads = 1;
  auto one = measure_surface_distance(scan, moved, options);
  ASSERT_TRUE(one.is_ok()) << one.status().message();
  EXPECT_GT(one.value().hausdorff, 0);
  EXPECT_GT(one.value().mean, 0);
  // No point moved farther than sqrt(2) * amplitude.
  EXPECT_LE(one.value().hausdorff, amplitude * std::sqrt(2.0) * (1 + 1e-5));
  for (unsigned threads : {2u, 7u, 0u}) {
    options.threads = threads;
    auto again = measure_surface_distance(scan, moved, options);
    ASSERT_TRUE(again.is_ok());
    expect_identical(one.value(), again.value());
  }
}

// A w x w grid over the unit square with random heights, its vertices and
// triangles shuffled.
TriangleMesh random_terrain(uint32_t w, uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> height(0.0f, 0.05f);
  std::vector<uint32_t> slot(w * w);
  for (uint32_t i = 0; i < slot.size(); ++i)
    slot[i] = i;
  std::shuffle(slot.begin(), slot.end(), random);
  TriangleMesh mesh;
  mesh.positions.resize(slot.size());
  for (uint32_t y = 0; y < w; ++y)
    for (uint32_t x = 0; x < w; ++x)
      mesh.positions[slot[y * w + x]] = {static_cast<float>(x) / static_cast<float>(w - 1),
                                         static_cast<float>(y) / static_cast<float>(w - 1),
                                         height(random)};
  for (uint32_t y = 0; y + 1 < w; ++y)
    for (uint32_t x = 0; x + 1 < w; ++x) {
      const uint32_t a = slot[y * w + x], b = slot[y * w + x + 1];
      const uint32_t c = slot[(y + 1) * w + x], d = slot[(y + 1) * w + x + 1];
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), random);
  return mesh;
}

TEST(SurfaceDistance, RandomMeshesGiveEqualDoublesForAnyThreadCount) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const TriangleMesh a = random_terrain(40 + 10 * seed, seed);
    const TriangleMesh b = random_terrain(50, 100 + seed);
    DistanceOptions options = small_budget();
    options.threads = 1;
    auto one = measure_surface_distance(a, b, options);
    ASSERT_TRUE(one.is_ok()) << one.status().message();
    EXPECT_GT(one.value().hausdorff, 0);
    for (unsigned threads : {2u, 7u}) {
      options.threads = threads;
      auto again = measure_surface_distance(a, b, options);
      ASSERT_TRUE(again.is_ok());
      expect_identical(one.value(), again.value());
    }
  }
}

TEST(SurfaceDistance, RejectsMeshesWithoutSurface) {
  const TriangleMesh c = cube(0);
  TriangleMesh empty;
  auto r = measure_surface_distance(empty, c);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(r.status().message(), "first mesh has no triangles");
  r = measure_surface_distance(c, empty);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(), "second mesh has no triangles");

  TriangleMesh flat = test_meshes::make({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}});
  r = measure_surface_distance(c, flat);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(), "second mesh has no triangle with non-zero area");
}

TEST(SurfaceDistance, RejectsBadIndicesAndCoordinates) {
  const TriangleMesh c = cube(0);
  TriangleMesh bad = c;
  bad.triangles[3][1] = 99;
  auto r = measure_surface_distance(c, bad);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(r.status().message(),
            "second mesh: triangle 3 has vertex index 99 out of range (8 vertices)");

  bad = c;
  bad.positions[5][2] = std::numeric_limits<float>::quiet_NaN();
  r = measure_surface_distance(bad, c);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(), "first mesh: vertex 5 has a non-finite coordinate");

  DistanceOptions huge;
  huge.area_samples = uint64_t{1} << 40;
  r = measure_surface_distance(c, c, huge);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
}

}  // namespace
}  // namespace lodbake
