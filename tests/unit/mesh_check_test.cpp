// check_mesh() on meshes built in memory, each with counts known by hand,
// plus the exact zero-area predicate on inputs where plain double
// arithmetic gets the answer wrong.
#include "lib/check/mesh_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lib/check/exact_predicates.h"
#include "tests/unit/test_meshes.h"

namespace lodbake {
namespace {

using namespace test_meshes;  // NOLINT: test shapes only

TEST(MeshCheck, TetrahedronIsClosedManifoldGenusZero) {
  MeshCheckReport r = check_mesh(tetrahedron());
  EXPECT_EQ(r.vertices, 4u);
  EXPECT_EQ(r.triangles, 4u);
  EXPECT_EQ(r.edges, 6u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_EQ(r.boundary_loops, 0u);
  EXPECT_EQ(r.inconsistent_orientation_edges, 0u);
  EXPECT_EQ(r.genus, 0);
  EXPECT_FALSE(r.has_problems());
  EXPECT_TRUE(r.problems().empty());
  EXPECT_EQ(r.bbox_min, (Vec3f{0, 0, 0}));
  EXPECT_EQ(r.bbox_max, (Vec3f{1, 1, 1}));
}

TEST(MeshCheck, OpenSquareHasOneBoundaryLoop) {
  MeshCheckReport r = check_mesh(open_square());
  EXPECT_EQ(r.edges, 5u);
  EXPECT_EQ(r.boundary_edges, 4u);
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_FALSE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_EQ(r.genus, -1);  // only defined for closed meshes
  EXPECT_FALSE(r.has_problems());
}

TEST(MeshCheck, BowtieHasOneNonManifoldVertexAndOneLoop) {
  MeshCheckReport r = check_mesh(bowtie());
  EXPECT_EQ(r.non_manifold_vertices, 1u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.samples.non_manifold_vertices, std::vector<uint64_t>{0});
  EXPECT_EQ(r.boundary_edges, 6u);
  // The two triangle outlines touch at vertex 0: one connected boundary.
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.components, 1u);
  ASSERT_EQ(r.problems().size(), 1u);
  EXPECT_EQ(r.problems()[0],
            "1 non-manifold vertex (faces around it form separate fans): vertex 0");
}

TEST(MeshCheck, TwoConesOnOneApexAreClosedButNotManifold) {
  MeshCheckReport r = check_mesh(two_cones());
  EXPECT_EQ(r.triangles, 24u);
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.non_manifold_vertices, 1u);
  EXPECT_EQ(r.inconsistent_orientation_edges, 0u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.genus, -1);
}

TEST(MeshCheck, ThreeTrianglesOnAnEdge) {
  MeshCheckReport r = check_mesh(three_on_an_edge());
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.samples.non_manifold_edges, (std::vector<VertexPair>{{0, 1}}));
  // Faces around vertices 0 and 1 hang together through edge 0-1: the
  // problem is the edge, not the vertices.
  EXPECT_EQ(r.non_manifold_vertices, 0u);
  EXPECT_EQ(r.boundary_edges, 6u);
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.problems()[0], "1 non-manifold edge (more than two faces): edge 0-1");
}

TEST(MeshCheck, FourTrianglesOnAnEdge) {
  MeshCheckReport r = check_mesh(four_on_an_edge());
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.non_manifold_vertices, 0u);
  EXPECT_EQ(r.boundary_edges, 8u);
  EXPECT_EQ(r.boundary_loops, 2u);
}

TEST(MeshCheck, FlippedFaceGivesThreeInconsistentEdges) {
  MeshCheckReport r = check_mesh(tetrahedron_one_flipped());
  EXPECT_EQ(r.inconsistent_orientation_edges, 3u);
  EXPECT_EQ(r.samples.inconsistent_orientation_edges,
            (std::vector<VertexPair>{{0, 2}, {0, 3}, {2, 3}}));
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_EQ(r.genus, -1);  // needs consistent orientation
  EXPECT_EQ(r.problems()[0],
            "3 edges with inconsistent orientation (both faces walk it the same way): "
            "edges 0-2, 0-3, 2-3");
}

TEST(MeshCheck, DegenerateTrianglesRepeatedAndZeroArea) {
  MeshCheckReport r = check_mesh(square_with_degenerates());
  EXPECT_EQ(r.repeated_index_triangles, 2u);  // (1 2 2), (3 3 3)
  EXPECT_EQ(r.samples.repeated_index_triangles, (std::vector<uint64_t>{3, 5}));
  EXPECT_EQ(r.zero_area_triangles, 2u);  // collinear (0 5 1), coincident (0 4 3)
  EXPECT_EQ(r.samples.zero_area_triangles, (std::vector<uint64_t>{2, 4}));
  EXPECT_EQ(r.degenerate_triangles, 4u);
  // Repeated-index triangles are out of the topology, zero-area ones are in:
  // edges 0-1 0-2 1-2 2-3 0-3 (square) + 0-5 1-5 + 0-4 3-4.
  EXPECT_EQ(r.edges, 9u);
  EXPECT_EQ(r.unreferenced_vertices, 0u);
  EXPECT_EQ(r.problems().size(), 3u);  // repeated, zero area, and the 0-3 edge both walk 3->0
  EXPECT_EQ(r.inconsistent_orientation_edges, 1u);
}

TEST(MeshCheck, RepeatedIndexTrianglesStillReferenceTheirVertices) {
  TriangleMesh mesh = make({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}}, {{0, 1, 2}, {3, 3, 1}});
  MeshCheckReport r = check_mesh(mesh);
  EXPECT_EQ(r.unreferenced_vertices, 0u);
  EXPECT_EQ(r.components, 1u);  // the repeated-index triangle joins nothing
  EXPECT_EQ(r.bbox_max, (Vec3f{5, 5, 5}));
}

TEST(MeshCheck, DuplicatesInEitherWindingAreCountedOnceEach) {
  MeshCheckReport r = check_mesh(tetrahedron_with_duplicates());
  EXPECT_EQ(r.duplicate_triangles, 2u);
  EXPECT_EQ(r.samples.duplicate_triangles, (std::vector<uint64_t>{4, 5}));
  // Duplicates take part in the topology: each edge of face (1 2 3) has 4 faces.
  EXPECT_EQ(r.non_manifold_edges, 3u);
  EXPECT_EQ(r.edges, 6u);
  EXPECT_TRUE(r.closed());
}

TEST(MeshCheck, NonFiniteCoordinatesAreCountedAndKeptOutOfTheBox) {
  TriangleMesh mesh = tetrahedron();
  mesh.positions[3] = {std::numeric_limits<float>::quiet_NaN(), 0, 0};
  mesh.positions[2][1] = std::numeric_limits<float>::infinity();
  MeshCheckReport r = check_mesh(mesh);
  EXPECT_EQ(r.non_finite_coordinates, 2u);
  EXPECT_EQ(r.samples.non_finite_vertices, (std::vector<uint64_t>{2, 3}));
  EXPECT_EQ(r.zero_area_triangles, 0u);  // not decided for non-finite corners
  EXPECT_EQ(r.bbox_min, (Vec3f{0, 0, 0}));
  EXPECT_EQ(r.bbox_max, (Vec3f{1, 0, 0}));
  EXPECT_EQ(r.genus, 0);  // topology does not look at coordinates
  EXPECT_EQ(r.problems()[0],
            "2 vertices with a non-finite coordinate (NaN or infinity): vertices 2, 3");
}

TEST(MeshCheck, UnreferencedVerticesDoNotChangeTheBox) {
  MeshCheckReport r = check_mesh(tetrahedron_with_unreferenced());
  EXPECT_EQ(r.unreferenced_vertices, 3u);
  EXPECT_EQ(r.samples.unreferenced_vertices, (std::vector<uint64_t>{2, 5, 6}));
  EXPECT_EQ(r.bbox_min, (Vec3f{0, 0, 0}));
  EXPECT_EQ(r.bbox_max, (Vec3f{1, 1, 1}));
  EXPECT_EQ(r.genus, 0);  // unreferenced vertices are not in V - E + F
  EXPECT_EQ(r.problems()[0], "3 unreferenced vertices (used by no triangle): vertices 2, 5, 6");
}

TEST(MeshCheck, TorusHasGenusOne) {
  MeshCheckReport r = check_mesh(torus(12, 8));
  EXPECT_EQ(r.vertices, 96u);
  EXPECT_EQ(r.triangles, 192u);
  EXPECT_EQ(r.edges, 288u);
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_EQ(r.genus, 1);
  EXPECT_FALSE(r.has_problems());
}

TEST(MeshCheck, TwoComponentsHaveNoGenus) {
  TriangleMesh mesh = tetrahedron();
  TriangleMesh other = torus(6, 5);
  const uint32_t offset = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), other.positions.begin(), other.positions.end());
  for (Triangle t : other.triangles)
    mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  MeshCheckReport r = check_mesh(mesh);
  EXPECT_EQ(r.components, 2u);
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(r.genus, -1);
}

TEST(MeshCheck, MoebiusBandIsInconsistentlyOriented) {
  MeshCheckReport r = check_mesh(moebius_band(10));
  EXPECT_TRUE(r.manifold());
  EXPECT_EQ(r.boundary_loops, 1u);  // a Moebius band has one boundary curve
  EXPECT_EQ(r.boundary_edges, 20u);
  EXPECT_EQ(r.inconsistent_orientation_edges, 1u);  // where the twist closes the strip
}

TEST(MeshCheck, KleinBottleIsClosedManifoldButNotOrientable) {
  MeshCheckReport r = check_mesh(klein_bottle(8, 6));
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_EQ(r.inconsistent_orientation_edges, 6u);  // the glued seam
  EXPECT_EQ(r.genus, -1);
}

TEST(MeshCheck, OutOfRangeIndicesAreCountedNotFollowed) {
  TriangleMesh mesh = tetrahedron();
  mesh.triangles.push_back({0, 1, 99});
  mesh.triangles.push_back({4, 4, 4});
  MeshCheckReport r = check_mesh(mesh);
  EXPECT_EQ(r.out_of_range_triangles, 2u);
  EXPECT_EQ(r.samples.out_of_range_triangles, (std::vector<uint64_t>{4, 5}));
  EXPECT_EQ(r.repeated_index_triangles, 0u);
  EXPECT_EQ(r.genus, 0);  // the rest is still the tetrahedron
  EXPECT_EQ(r.problems()[0],
            "2 triangles with a vertex index out of range (4 vertices): triangles 4, 5");
}

TEST(MeshCheck, EmptyMeshHasNothing) {
  MeshCheckReport r = check_mesh(TriangleMesh());
  EXPECT_EQ(r.triangles, 0u);
  EXPECT_EQ(r.components, 0u);
  EXPECT_EQ(r.genus, -1);
  EXPECT_FALSE(r.has_problems());
}

TEST(MeshCheck, SamplesAreTheFirstThreeAndTheLineSaysThereAreMore) {
  TriangleMesh mesh = open_square();
  for (int i = 0; i < 5; ++i)
    mesh.positions.push_back({9, 9, 9});
  MeshCheckReport r = check_mesh(mesh);
  EXPECT_EQ(r.unreferenced_vertices, 5u);
  EXPECT_EQ(r.samples.unreferenced_vertices, (std::vector<uint64_t>{4, 5, 6}));
  EXPECT_EQ(r.describe(MeshProblem::kUnreferencedVertices),
            "5 unreferenced vertices (used by no triangle): vertices 4, 5, 6, ...");
  EXPECT_EQ(r.describe(MeshProblem::kNonManifoldEdges), "");
}

TEST(MeshCheck, CountsDoNotDependOnTriangleOrderOrRotation) {
  TriangleMesh mesh = torus(9, 7);
  mesh.triangles.push_back(mesh.triangles[5]);  // a duplicate
  MeshCheckReport a = check_mesh(mesh);
  TriangleMesh shuffled = mesh;
  std::reverse(shuffled.triangles.begin(), shuffled.triangles.end());
  for (Triangle& t : shuffled.triangles)
    t = {t[1], t[2], t[0]};
  MeshCheckReport b = check_mesh(shuffled);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.non_manifold_edges, b.non_manifold_edges);
  EXPECT_EQ(a.duplicate_triangles, 1u);
  EXPECT_EQ(b.duplicate_triangles, 1u);
  EXPECT_EQ(a.non_manifold_edges, 3u);
}

TEST(ExactPredicates, CollinearAndCoincidentPointsHaveZeroArea) {
  EXPECT_TRUE(is_zero_area_triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
  EXPECT_TRUE(is_zero_area_triangle({0, 0, 0}, {0, 0, 0}, {2, 3, 4}));
  EXPECT_TRUE(is_zero_area_triangle({1, 2, 3}, {1, 2, 3}, {1, 2, 3}));
  EXPECT_TRUE(is_zero_area_triangle({0.1f, 0.3f, 0}, {0.2f, 0.6f, 0}, {0.4f, 1.2f, 0}));
  EXPECT_FALSE(is_zero_area_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  EXPECT_FALSE(is_zero_area_triangle({0, 0, 0}, {1, 1, 1}, {2, 2, std::nextafter(2.0f, 3.0f)}));
}

TEST(ExactPredicates, DecidesWhereDoubleArithmeticRoundsAway) {
  const float tiny = std::ldexp(1.0f, -100);
  // (tiny, 0) lies off the line y = x through (1, 1) and (2, 2), but in
  // double 1 - tiny rounds to 1 and the naive determinant is exactly 0.
  EXPECT_FALSE(is_zero_area_triangle({1, 1, 0}, {2, 2, 0}, {tiny, 0, 0}));
  // (tiny, tiny) lies on it.
  EXPECT_TRUE(is_zero_area_triangle({1, 1, 0}, {2, 2, 0}, {tiny, tiny, 0}));
  // Smallest subnormal against the largest float.
  const float denormal = std::numeric_limits<float>::denorm_min();
  const float huge = std::numeric_limits<float>::max();
  EXPECT_FALSE(is_zero_area_triangle({huge, huge, huge}, {denormal, 0, 0}, {0, 0, 0}));
  EXPECT_TRUE(is_zero_area_triangle({huge, huge, huge}, {denormal, denormal, denormal}, {0, 0, 0}));
  EXPECT_TRUE(is_zero_area_triangle({-huge, -huge, -huge}, {huge, huge, huge}, {0, 0, 0}));
}

}  // namespace
}  // namespace lodbake
