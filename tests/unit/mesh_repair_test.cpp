// repair_mesh() on in-memory versions of the ../shared/data/bad/ cases: the
// repaired mesh must check clean, the report must say what happened, and
// per-vertex and per-corner attributes must follow their vertices and
// corners through removals, splits and flips.
#include "lib/repair/mesh_repair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "lib/check/mesh_check.h"
#include "tests/unit/test_meshes.h"

namespace lodbake {
namespace {

using namespace test_meshes;  // NOLINT: test shapes only

// Gives `mesh` a per-vertex attribute that names each vertex (normals) and a
// per-corner one that names each corner (texcoords), so the repaired mesh
// says where every vertex and corner came from.
TriangleMesh with_tracking_attributes(TriangleMesh mesh) {
  mesh.normals = vertex_id_attribute(mesh.positions.size(), 3);
  mesh.texcoords = distinct_corner_attribute(mesh.triangles.size(), 2);
  return mesh;
}

struct Provenance {
  std::vector<uint64_t> source_triangle;  // per output triangle
  uint64_t reversed = 0;
};

// Checks that every output vertex carries the position and attribute of its
// input vertex and every output corner the attribute of the input corner at
// the same vertex, with output triangles in input order; returns where each
// triangle came from.
Provenance check_provenance(const TriangleMesh& input, const TriangleMesh& output) {
  Provenance p;
  EXPECT_EQ(output.normals.binding, AttributeBinding::kPerVertex);
  EXPECT_EQ(output.texcoords.binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(output.normals.value_count(), output.positions.size());
  EXPECT_EQ(output.texcoords.corners.size(), output.triangles.size());
  EXPECT_EQ(output.texcoords.values, input.texcoords.values);
  auto origin = [&](uint32_t v) { return static_cast<uint32_t>(output.normals.values[3 * v]); };
  for (uint32_t v = 0; v < output.positions.size(); ++v) {
    uint32_t o = origin(v);
    EXPECT_LT(o, input.positions.size());
    if (o >= input.positions.size()) return p;
    EXPECT_EQ(output.positions[v], input.positions[o]) << "vertex " << v;
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(output.normals.values[3 * v + c], input.normals.values[3 * o + c]);
    }
  }
  for (size_t t = 0; t < output.triangles.size(); ++t) {
    const Triangle& corners = output.texcoords.corners[t];
    const uint64_t source = corners[0] / 3;
    p.source_triangle.push_back(source);
    std::array<uint32_t, 3> slot;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(corners[k] / 3, source) << "triangle " << t << " mixes input triangles";
      slot[k] = corners[k] % 3;
      EXPECT_EQ(origin(output.triangles[t][k]), input.triangles[source][slot[k]])
          << "triangle " << t << " corner " << k;
    }
    const bool same = slot == std::array<uint32_t, 3>{0, 1, 2};
    const bool reversed = slot == std::array<uint32_t, 3>{2, 1, 0};
    EXPECT_TRUE(same || reversed) << "triangle " << t;
    if (reversed) ++p.reversed;
    if (t > 0) {
      EXPECT_LT(p.source_triangle[t - 1], source) << "input order not kept";
    }
  }
  return p;
}

void expect_clean(const TriangleMesh& mesh) {
  MeshCheckReport r = check_mesh(mesh);
  EXPECT_FALSE(r.has_problems()) << (r.problems().empty() ? "" : r.problems().front());
}

double signed_volume(const TriangleMesh& mesh) {
  double sum = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3f& a = mesh.positions[t[0]];
    const Vec3f& b = mesh.positions[t[1]];
    const Vec3f& c = mesh.positions[t[2]];
    sum += a[0] * (double{b[1]} * c[2] - double{b[2]} * c[1]) -
           a[1] * (double{b[0]} * c[2] - double{b[2]} * c[0]) +
           a[2] * (double{b[0]} * c[1] - double{b[1]} * c[0]);
  }
  return sum / 6;
}

struct Repaired {
  TriangleMesh mesh;
  RepairReport report;
  Provenance provenance;
};

Repaired repair_tracked(const TriangleMesh& shape) {
  Repaired out;
  TriangleMesh input = with_tracking_attributes(shape);
  out.mesh = input;
  Status s = repair_mesh(out.mesh, &out.report);
  EXPECT_TRUE(s.is_ok()) << s.message();
  if (!s.is_ok()) return out;
  expect_clean(out.mesh);
  out.provenance = check_provenance(input, out.mesh);
  EXPECT_EQ(out.provenance.reversed, out.report.flipped_triangles);
  return out;
}

TEST(MeshRepair, CleanMeshIsLeftAsItIs) {
  TriangleMesh input = with_tracking_attributes(torus(10, 6));
  TriangleMesh mesh = input;
  RepairReport report;
  ASSERT_TRUE(repair_mesh(mesh, &report).is_ok());
  EXPECT_FALSE(report.changed());
  EXPECT_TRUE(report.actions().empty());
  EXPECT_EQ(mesh, input);
}

TEST(MeshRepair, BowtieVertexIsSplit) {
  Repaired r = repair_tracked(bowtie());
  EXPECT_EQ(r.report.split_non_manifold_vertices, 1u);
  EXPECT_EQ(r.report.added_vertices, 1u);
  EXPECT_EQ(r.mesh.positions.size(), 6u);
  EXPECT_EQ(r.mesh.positions[5], (Vec3f{0, 0, 0}));  // the copy is appended
  EXPECT_EQ(check_mesh(r.mesh).components, 2u);
  EXPECT_EQ(
      r.report.actions(),
      std::vector<std::string>{"split 1 vertex whose faces form separate fans, adding 1 vertex"});
}

TEST(MeshRepair, TwoConesBecomeTwoClosedCones) {
  Repaired r = repair_tracked(two_cones());
  EXPECT_EQ(r.report.split_non_manifold_vertices, 1u);
  EXPECT_EQ(r.mesh.triangles.size(), 24u);
  MeshCheckReport c = check_mesh(r.mesh);
  EXPECT_EQ(c.components, 2u);
  EXPECT_TRUE(c.closed());
  EXPECT_EQ(r.report.flipped_triangles, 0u);
}

TEST(MeshRepair, ThreeTrianglesOnAnEdgeAreCutApart) {
  Repaired r = repair_tracked(three_on_an_edge());
  EXPECT_EQ(r.report.split_non_manifold_edges, 1u);
  EXPECT_EQ(r.report.split_non_manifold_vertices, 2u);  // both ends of the edge
  EXPECT_EQ(r.report.added_vertices, 4u);
  EXPECT_EQ(r.mesh.triangles.size(), 3u);
  EXPECT_EQ(check_mesh(r.mesh).components, 3u);
}

TEST(MeshRepair, FourTrianglesOnAnEdgeAreCutApart) {
  Repaired r = repair_tracked(four_on_an_edge());
  EXPECT_EQ(r.report.split_non_manifold_edges, 1u);
  EXPECT_EQ(r.mesh.triangles.size(), 12u);
  MeshCheckReport c = check_mesh(r.mesh);
  EXPECT_EQ(c.non_manifold_edges, 0u);
  EXPECT_GE(c.components, 2u);
}

TEST(MeshRepair, DuplicatesInBothWindingsGoAndTheFirstCopyStays) {
  Repaired r = repair_tracked(tetrahedron_with_duplicates());
  EXPECT_EQ(r.report.removed_duplicate_triangles, 2u);
  EXPECT_EQ(r.provenance.source_triangle, (std::vector<uint64_t>{0, 1, 2, 3}));
  EXPECT_EQ(check_mesh(r.mesh).genus, 0);
  EXPECT_EQ(r.report.split_non_manifold_edges, 0u);  // gone with the duplicates
}

TEST(MeshRepair, FlippedFaceIsFlippedBackWithItsCorners) {
  Repaired r = repair_tracked(tetrahedron_one_flipped());
  EXPECT_EQ(r.report.flipped_triangles, 1u);
  EXPECT_EQ(r.mesh.triangles[2], (Triangle{3, 2, 0}));
  EXPECT_EQ(r.mesh.texcoords.corners[2], (Triangle{8, 7, 6}));  // corners reversed with it
  EXPECT_EQ(check_mesh(r.mesh).genus, 0);
  EXPECT_GT(signed_volume(r.mesh), 0);
}

TEST(MeshRepair, ClosedPieceEndsUpOutwardEvenWhenMostFacesPointIn) {
  TriangleMesh mesh = tetrahedron();
  for (int t = 0; t < 3; ++t)
    std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
  Repaired r = repair_tracked(mesh);
  EXPECT_EQ(r.report.flipped_triangles, 3u);
  EXPECT_GT(signed_volume(r.mesh), 0);
}

TEST(MeshRepair, OpenPieceKeepsTheMajorityWinding) {
  // A fan of four triangles around vertex 0; the first one (CGAL's seed) is
  // the odd one out.
  TriangleMesh mesh = make({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}},
                           {{0, 2, 1}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}});
  Repaired r = repair_tracked(mesh);
  EXPECT_EQ(r.report.flipped_triangles, 1u);
  EXPECT_EQ(r.mesh.triangles[0], (Triangle{1, 2, 0}));
}

TEST(MeshRepair, DegenerateTrianglesGoAndTheirVerticesWithThem) {
  Repaired r = repair_tracked(square_with_degenerates());
  EXPECT_EQ(r.report.removed_degenerate_triangles, 4u);
  EXPECT_EQ(r.report.removed_unreferenced_vertices, 2u);  // 4 and 5 were only in degenerates
  EXPECT_EQ(r.provenance.source_triangle, (std::vector<uint64_t>{0, 1}));
  EXPECT_EQ(r.mesh.positions.size(), 4u);
}

TEST(MeshRepair, TrianglesTouchingNonFiniteVerticesGo) {
  TriangleMesh mesh = tetrahedron();
  mesh.positions[3] = {0, std::numeric_limits<float>::infinity(), 0};
  Repaired r = repair_tracked(mesh);
  EXPECT_EQ(r.report.removed_non_finite_triangles, 3u);
  EXPECT_EQ(r.report.removed_unreferenced_vertices, 1u);
  EXPECT_EQ(r.mesh.positions.size(), 3u);
  EXPECT_EQ(r.provenance.source_triangle, std::vector<uint64_t>{0});
}

TEST(MeshRepair, UnreferencedVerticesGoAndTheRestKeepTheirOrder) {
  Repaired r = repair_tracked(tetrahedron_with_unreferenced());
  EXPECT_EQ(r.report.removed_unreferenced_vertices, 3u);
  EXPECT_EQ(r.mesh.positions, (std::vector<Vec3f>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
  EXPECT_EQ(r.mesh.triangles, (std::vector<Triangle>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
}

TEST(MeshRepair, MoebiusBandWithOnlyBoundaryVerticesIsCut) {
  Repaired r = repair_tracked(moebius_band(10));
  EXPECT_GT(r.report.added_vertices, 0u);
  EXPECT_EQ(r.mesh.triangles.size(), 20u);
}

TEST(MeshRepair, KleinBottleIsCutIntoAnOrientableSurface) {
  TriangleMesh shape = klein_bottle(8, 6);
  ASSERT_GT(check_mesh(shape).inconsistent_orientation_edges, 0u);
  ASSERT_TRUE(check_mesh(shape).closed());
  Repaired r = repair_tracked(shape);
  EXPECT_GT(r.report.split_non_manifold_vertices, 0u);
  EXPECT_EQ(r.mesh.triangles.size(), shape.triangles.size());
  EXPECT_FALSE(check_mesh(r.mesh).closed());  // cutting opened it
}

TEST(MeshRepair, NothingLeftIsAnError) {
  TriangleMesh mesh = make({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {{0, 1, 2}, {0, 0, 1}});
  TriangleMesh before = mesh;
  Status s = repair_mesh(mesh, nullptr);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(s.message(), "no triangle is left after repair: removed 2 degenerate triangles");
  EXPECT_EQ(mesh, before);
}

TEST(MeshRepair, OutOfRangeIndexIsRefusedAndTheMeshUntouched) {
  TriangleMesh mesh = bowtie();
  mesh.triangles[1][1] = 5;
  TriangleMesh before = mesh;
  Status s = repair_mesh(mesh, nullptr);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(s.message(), "triangle 1: vertex index 5 out of range (5 vertices)");
  EXPECT_EQ(mesh, before);
}

TEST(MeshRepair, InconsistentAttributesAreRefused) {
  TriangleMesh mesh = with_tracking_attributes(bowtie());
  mesh.texcoords.corners[1][2] = 99;
  Status s = repair_mesh(mesh, nullptr);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(s.message(), "texture coordinates: triangle 1 uses value 99 of 6");
  mesh = with_tracking_attributes(bowtie());
  mesh.normals.values.resize(12);
  s = repair_mesh(mesh, nullptr);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(s.message(), "normals: 4 per-vertex values for 5 vertices");
}

// A torus with every kind of damage, made by a fixed pseudo-random sequence.
TriangleMesh damaged_torus() {
  TriangleMesh mesh = torus(24, 16);
  uint32_t state = 12345;
  auto next = [&state](uint32_t bound) {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) % bound;
  };
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  const size_t m = mesh.triangles.size();
  for (int i = 0; i < 40; ++i) {
    Triangle& t = mesh.triangles[next(static_cast<uint32_t>(m))];
    std::swap(t[0], t[1]);  // flips
  }
  for (int i = 0; i < 10; ++i)
    mesh.triangles.push_back(mesh.triangles[next(static_cast<uint32_t>(m))]);
  for (int i = 0; i < 10; ++i) {  // fins on existing edges: non-manifold edges
    Triangle t = mesh.triangles[next(static_cast<uint32_t>(m))];
    mesh.positions.push_back({0, 0, static_cast<float>(5 + i)});
    mesh.triangles.push_back({t[0], t[1], static_cast<uint32_t>(mesh.positions.size() - 1)});
  }
  for (int i = 0; i < 5; ++i) {  // triangles hanging on one vertex: non-manifold vertices
    uint32_t v = next(n);
    uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back({10, static_cast<float>(i), 0});
    mesh.positions.push_back({10, static_cast<float>(i), 1});
    mesh.triangles.push_back({v, base, base + 1});
  }
  mesh.triangles.push_back({3, 3, 4});
  mesh.positions.push_back({std::numeric_limits<float>::quiet_NaN(), 0, 0});
  mesh.triangles.push_back({0, 1, static_cast<uint32_t>(mesh.positions.size() - 1)});
  mesh.positions.push_back({7, 7, 7});  // unreferenced
  return mesh;
}

TEST(MeshRepair, DamagedTorusComesOutCleanDeterministicAndStable) {
  TriangleMesh shape = damaged_torus();
  MeshCheckReport before = check_mesh(shape);
  ASSERT_GT(before.non_manifold_edges, 0u);
  ASSERT_GT(before.non_manifold_vertices, 0u);
  ASSERT_GT(before.inconsistent_orientation_edges, 0u);
  ASSERT_GT(before.duplicate_triangles, 0u);
  Repaired first = repair_tracked(shape);
  EXPECT_EQ(first.report.removed_duplicate_triangles, before.duplicate_triangles);
  EXPECT_EQ(first.report.removed_non_finite_triangles, 1u);
  EXPECT_EQ(first.report.removed_degenerate_triangles, 1u);
  EXPECT_GT(first.report.flipped_triangles, 0u);

  Repaired second = repair_tracked(shape);
  EXPECT_EQ(first.mesh, second.mesh);

  TriangleMesh again = first.mesh;
  RepairReport again_report;
  ASSERT_TRUE(repair_mesh(again, &again_report).is_ok());
  EXPECT_FALSE(again_report.changed());
  EXPECT_EQ(again, first.mesh);
}

TEST(MeshRepair, ActionsListEveryNonZeroCount) {
  RepairReport report;
  report.removed_non_finite_triangles = 1;
  report.removed_degenerate_triangles = 2;
  report.removed_duplicate_triangles = 1;
  report.split_non_manifold_edges = 2;
  report.split_non_manifold_vertices = 3;
  report.added_vertices = 4;
  report.flipped_triangles = 1;
  report.removed_unreferenced_vertices = 2;
  EXPECT_EQ(report.actions(),
            (std::vector<std::string>{
                "removed 1 triangle touching a vertex with a non-finite coordinate",
                "removed 2 degenerate triangles (repeated vertex or zero area)",
                "removed 1 duplicate triangle",
                "cut apart 2 non-manifold edges (more than two faces)",
                "split 3 vertices whose faces form separate fans, adding 4 vertices",
                "flipped 1 triangle for consistent orientation",
                "removed 2 unreferenced vertices",
            }));
}

}  // namespace
}  // namespace lodbake
