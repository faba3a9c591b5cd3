// The two fast paths the replay modes validate with at every step, each
// against the slower reference it stands for: sort_canonical_triangles()
// against rotate-then-std::sort, check_triangulation() against the same
// fields of check_mesh(), on random lists with every kind of problem.
#include "formats/mesh/canonical_triangles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "lib/check/mesh_check.h"

namespace lodbake {
namespace {

std::vector<Triangle> random_triangles(std::mt19937* random, size_t count, uint32_t vertices) {
  std::uniform_int_distribution<uint32_t> index(0, vertices - 1);
  std::vector<Triangle> triangles(count);
  for (Triangle& t : triangles)
    t = {index(*random), index(*random), index(*random)};
  return triangles;
}

std::vector<Triangle> reference_sort(std::vector<Triangle> triangles) {
  for (Triangle& t : triangles) {
    Triangle least = t;
    for (int k = 0; k < 2; ++k) {
      t = {t[1], t[2], t[0]};
      least = std::min(least, t);
    }
    t = least;
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

TEST(CanonicalTriangles, RotationKeepsTheOrientation) {
  EXPECT_EQ(canonical_triangle({5, 2, 9}), (Triangle{2, 9, 5}));
  EXPECT_EQ(canonical_triangle({5, 9, 2}), (Triangle{2, 5, 9}));
  EXPECT_EQ(canonical_triangle({1, 9, 2}), (Triangle{1, 9, 2}));
}

TEST(CanonicalTriangles, SortEqualsTheReferenceOnDenseAndSparseLists) {
  std::mt19937 random(7);
  // Dense (the bucket sort), sparse (its fallback) and small lists.
  for (const auto& [count, vertices] : std::vector<std::pair<size_t, uint32_t>>{
           {5000, 300}, {5000, 4000}, {200, 4000000}, {40, 10}, {0, 1}}) {
    std::vector<Triangle> triangles = random_triangles(&random, count, vertices);
    const std::vector<Triangle> expected = reference_sort(triangles);
    sort_canonical_triangles(&triangles);
    EXPECT_EQ(triangles, expected) << count << " triangles over " << vertices << " vertices";
  }
}

TEST(CheckTriangulation, AgreesWithCheckMeshOnRandomProblemMeshes) {
  std::mt19937 random(11);
  for (int round = 0; round < 40; ++round) {
    const uint32_t vertices = 8 + round * 5;
    TriangleMesh mesh;
    mesh.positions.assign(vertices, Vec3f{0, 0, 0});
    // Indices up to one past the end give out-of-range triangles too.
    mesh.triangles = random_triangles(&random, 30 + round * 7, vertices + 1);
    const MeshCheckReport full = check_mesh(mesh);
    const MeshCheckReport fast = check_triangulation(mesh);
    EXPECT_EQ(fast.out_of_range_triangles, full.out_of_range_triangles);
    EXPECT_EQ(fast.repeated_index_triangles, full.repeated_index_triangles);
    EXPECT_EQ(fast.duplicate_triangles, full.duplicate_triangles);
    EXPECT_EQ(fast.edges, full.edges);
    EXPECT_EQ(fast.boundary_edges, full.boundary_edges);
    EXPECT_EQ(fast.non_manifold_edges, full.non_manifold_edges);
    EXPECT_EQ(fast.inconsistent_orientation_edges, full.inconsistent_orientation_edges);
    EXPECT_EQ(fast.samples.non_manifold_edges, full.samples.non_manifold_edges);
    EXPECT_EQ(fast.samples.duplicate_triangles, full.samples.duplicate_triangles);
    EXPECT_GT(full.non_manifold_edges + full.inconsistent_orientation_edges, 0u) << round;
  }
}

}  // namespace
}  // namespace lodbake
