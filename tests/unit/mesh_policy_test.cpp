// check_usable(): what is always refused, what a policy may refuse, and the
// one-line messages.
#include "lib/check/mesh_policy.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "lib/check/mesh_check.h"
#include "tests/unit/test_meshes.h"

namespace lodbake {
namespace {

using namespace test_meshes;  // NOLINT: test shapes only

Status usable(const TriangleMesh& mesh, const UsePolicy& policy = UsePolicy()) {
  return check_usable(check_mesh(mesh), policy);
}

TEST(MeshPolicy, CleanMeshesAreUsable) {
  EXPECT_TRUE(usable(tetrahedron()).is_ok());
  EXPECT_TRUE(usable(open_square()).is_ok());
  UsePolicy strict;
  strict.refuse_non_manifold_vertices = true;
  strict.refuse_inconsistent_orientation = true;
  strict.refuse_degenerate_triangles = true;
  strict.refuse_duplicate_triangles = true;
  strict.refuse_unreferenced_vertices = true;
  EXPECT_TRUE(usable(torus(8, 6), strict).is_ok());
}

TEST(MeshPolicy, NonFiniteCoordinatesAreAlwaysRefused) {
  TriangleMesh mesh = tetrahedron();
  mesh.positions[1][2] = std::numeric_limits<float>::quiet_NaN();
  Status s = usable(mesh);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(s.message(),
            "1 vertex with a non-finite coordinate (NaN or infinity): vertex 1 "
            "(use --repair to fix)");
}

TEST(MeshPolicy, NonManifoldEdgesAreAlwaysRefused) {
  Status s = usable(three_on_an_edge());
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(s.message(),
            "1 non-manifold edge (more than two faces): edge 0-1 (use --repair to fix)");
}

TEST(MeshPolicy, OutOfRangeIndicesAreRefusedWithoutPointingAtRepair) {
  TriangleMesh mesh = tetrahedron();
  mesh.triangles[1][2] = 7;
  Status s = usable(mesh);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(s.message(), "1 triangle with a vertex index out of range (4 vertices): triangle 1");
}

TEST(MeshPolicy, EmptyMeshIsRefused) {
  Status s = usable(TriangleMesh());
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(s.message(), "the mesh has no triangles");
}

TEST(MeshPolicy, OptionalProblemsAreRefusedOnlyWhenAsked) {
  struct Case {
    TriangleMesh mesh;
    bool UsePolicy::*flag;
    std::string message_start;
  };
  const Case cases[] = {
      {bowtie(), &UsePolicy::refuse_non_manifold_vertices, "1 non-manifold vertex"},
      {tetrahedron_one_flipped(), &UsePolicy::refuse_inconsistent_orientation,
       "3 edges with inconsistent orientation"},
      {make({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}),
       &UsePolicy::refuse_degenerate_triangles, "1 degenerate triangle with zero area"},
      {make({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {2, 1, 0}}),
       &UsePolicy::refuse_duplicate_triangles, "1 duplicate triangle"},
      {tetrahedron_with_unreferenced(), &UsePolicy::refuse_unreferenced_vertices,
       "3 unreferenced vertices"},
  };
  for (const Case& c : cases) {
    EXPECT_TRUE(usable(c.mesh).is_ok()) << c.message_start;
    UsePolicy policy;
    policy.*c.flag = true;
    Status s = usable(c.mesh, policy);
    EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << c.message_start;
    EXPECT_EQ(s.message().rfind(c.message_start, 0), 0u) << s.message();
    EXPECT_NE(s.message().find("(use --repair to fix)"), std::string::npos) << s.message();
  }
}

TEST(MeshPolicy, NamesTheFirstBlockingProblem) {
  // Duplicates make non-manifold edges: the edges block, the duplicates are
  // tolerated by default, so the message is about the edges.
  Status s = usable(tetrahedron_with_duplicates());
  EXPECT_EQ(s.message().rfind("3 non-manifold edges (more than two faces): edges 1-2, 1-3, 2-3", 0),
            0u)
      << s.message();
}

TEST(MeshPolicy, TwoManifoldRefusesWhatTheEngineCannotTake) {
  const UsePolicy policy = UsePolicy::two_manifold();
  EXPECT_TRUE(policy.refuse_non_manifold_vertices);
  EXPECT_TRUE(policy.refuse_inconsistent_orientation);
  EXPECT_TRUE(policy.refuse_degenerate_triangles);
  EXPECT_TRUE(policy.refuse_duplicate_triangles);
  EXPECT_FALSE(policy.refuse_unreferenced_vertices);  // the tools drop them
  EXPECT_TRUE(usable(torus(8, 6), policy).is_ok());
  EXPECT_TRUE(usable(tetrahedron_with_unreferenced(), policy).is_ok());
  EXPECT_FALSE(usable(bowtie(), policy).is_ok());
}

TEST(MeshPolicy, FirstRefusedProblemFollowsTheCheckOrder) {
  const UsePolicy policy = UsePolicy::two_manifold();
  EXPECT_EQ(first_refused_problem(check_mesh(tetrahedron()), policy), std::nullopt);
  EXPECT_EQ(first_refused_problem(check_mesh(bowtie()), policy), MeshProblem::kNonManifoldVertices);
  EXPECT_EQ(first_refused_problem(check_mesh(bowtie()), UsePolicy()), std::nullopt);
  EXPECT_EQ(first_refused_problem(check_mesh(tetrahedron_with_duplicates()), policy),
            MeshProblem::kNonManifoldEdges);
  EXPECT_EQ(first_refused_problem(check_mesh(tetrahedron_one_flipped()), policy),
            MeshProblem::kInconsistentOrientation);
  TriangleMesh mesh = bowtie();
  mesh.positions[3][0] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(first_refused_problem(check_mesh(mesh), policy), MeshProblem::kNonFiniteCoordinates);
  mesh.triangles[0][1] = 9;
  EXPECT_EQ(first_refused_problem(check_mesh(mesh), policy), MeshProblem::kOutOfRangeIndices);
}

TEST(MeshPolicy, TheDefaultRepairFixesTopologyButNotCoordinates) {
  for (MeshProblem problem :
       {MeshProblem::kNonManifoldEdges, MeshProblem::kNonManifoldVertices,
        MeshProblem::kRepeatedIndexTriangles, MeshProblem::kZeroAreaTriangles,
        MeshProblem::kDuplicateTriangles, MeshProblem::kInconsistentOrientation}) {
    EXPECT_TRUE(fixed_by_default_repair(problem)) << static_cast<int>(problem);
  }
  EXPECT_FALSE(fixed_by_default_repair(MeshProblem::kNonFiniteCoordinates));
  EXPECT_FALSE(fixed_by_default_repair(MeshProblem::kOutOfRangeIndices));
  EXPECT_FALSE(fixed_by_default_repair(MeshProblem::kUnreferencedVertices));
}

}  // namespace
}  // namespace lodbake
