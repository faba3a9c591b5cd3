// Every mesh of ../shared/data/meshes/, imported with import_mesh_file()
// and checked: the counts must match MANIFEST.md (V, triangles after
// polygons are split, boundary edges and loops, non-manifold edges and
// vertices, components, genus, and the duplicate / unreferenced / zero-area /
// winding notes).
//
// Where MANIFEST counts polygons, the expected values are for triangles: a
// polygon's diagonals are interior edges and do not change the other counts,
// except in two files where the split itself can make problems, so those
// rows check a range instead (see kTriangulationDependent below).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "lib/check/mesh_check.h"
#include "lib/meshio/mesh_import.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

constexpr int64_t kTriangulationDependent = -2;

struct Expected {
  const char* file;
  uint64_t vertices;
  uint64_t triangles;
  uint64_t boundary_edges;
  uint64_t boundary_loops;
  int64_t non_manifold_edges;  // kTriangulationDependent: see the test
  uint64_t non_manifold_vertices;
  uint64_t components;
  int64_t genus;  // -1 where MANIFEST gives none (not closed, manifold, one piece)
  int64_t duplicate_triangles;
  uint64_t unreferenced_vertices;
  int64_t zero_area_triangles;
  uint64_t inconsistent_orientation_edges;
};

constexpr int64_t kTD = kTriangulationDependent;

// clang-format off
const Expected kManifest[] = {
  // file                                   V       tris    bnd   loops nme  nmv comp genus dup  unref zero  winding
  {"cgal_tetrahedron.off",                  4,      4,      0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"cgal_degtri_sliding.off",               8,      8,      6,    1,    0,   0,  1,   -1,   0,   0,    4,    0},
  {"cgal_cube_quad.off",                    8,      12,     0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"draco_test_nm.obj",                     114,    170,    30,   3,    0,   2,  1,   -1,   0,   17,   0,    0},
  // Fanning mpi's polygons gives 2 zero-area triangles (collinear corners);
  // MANIFEST counts polygons and has none.
  {"cgal_mpi.off",                          90,     180,    0,    0,    0,   0,  1,   1,    0,   0,    kTD,  0},
  {"cgal_oblong-shuffled.off",              424,    840,    6,    1,    0,   0,  1,   -1,   0,   0,    0,    623},
  // Two quads on the same four vertices: fanning both from vertex 71 makes
  // one triangle twice (MANIFEST's note), a 4-face edge with it.
  {"c3d_suzanne.obj",                       507,    968,    42,   4,    kTD, 0,  3,   -1,   kTD, 0,    0,    0},
  {"igl_decimated-knight.off",              502,    1000,   0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"c3d_beetle.obj",                        1148,   2053,   296,  23,   47,  0,  2,   -1,   0,   0,    0,    0},
  {"cgal_blobby_3cc.off",                   1820,   3417,   219,  4,    0,   0,  3,   -1,   0,   0,    0,    0},
  {"npm_bunny.obj",                         1839,   3674,   0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"assimp_Wuson.off",                      3205,   3732,   2338, 187,  0,   12, 179, -1,   0,   0,    0,    0},
  {"cgal_elephant-with-holes.off",          2798,   4463,   1353, 106,  0,   0,  1,   -1,   0,   0,    0,    0},
  {"cgal_mushroom.off",                     2337,   4608,   64,   1,    0,   0,  1,   -1,   0,   0,    0,    0},
  {"cgal_elephant.off",                     2775,   5558,   0,    0,    0,   0,  1,   3,    0,   0,    0,    0},
  {"c3d_spot.obj",                          2930,   5856,   0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"c3d_teapot.obj",                        3644,   6320,   1036, 10,   0,   38, 4,   -1,   0,   0,    0,    0},
  {"igl_fertility.off",                     4494,   9000,   0,    0,    0,   0,  1,   4,    0,   0,    0,    0},
  {"stanford_dragon_vrip_res4.ply.gz",      5205,   11102,  0,    0,    803, 7,  1,   -1,   502, 2,    0,    0},
  {"cgal_knot2.off",                        5760,   11520,  0,    0,    0,   0,  2,   -1,   0,   0,    0,    0},
  {"cgal_fandisk.off",                      6475,   12946,  0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"cgal_pig.stl",                          8642,   16848,  1296, 5,    0,   421, 1,  -1,   0,   0,    0,    0},
  {"cgal_cheese.off",                       8629,   17786,  0,    0,    0,   0,  1,   133,  0,   0,    0,    0},
  {"cgal_camel.off",                        9770,   19536,  0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"cgal_ChineseDragon-10kv.off",           10000,  19994,  6,    2,    0,   0,  1,   -1,   0,   0,    0,    0},
  {"c3d_rocker-arm.obj",                    10044,  20088,  0,    0,    0,   0,  1,   1,    0,   0,    0,    0},
  {"igl_camelhead.off",                     11381,  22704,  56,   1,    0,   0,  1,   -1,   0,   0,    0,    0},
  {"cgal_man.off",                          17495,  34986,  0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"stanford_dragon_vrip_res3.ply.gz",      22998,  47794,  0,    0,    2094, 5, 1,   -1,   1254, 16, 0,    0},
  {"cgal_armadillo.off",                    26002,  52000,  0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"draco_bunny.stl",                       34834,  69451,  223,  5,    0,   0,  1,   -1,   0,   0,    0,    0},
  {"stanford_bun_zipper.ply",               35947,  69451,  223,  5,    0,   0,  1,   -1,   0,   1113, 0,    0},
  {"cgal_bunny00.off",                      37706,  75408,  0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"igl_armadillo.obj",                     43243,  86482,  0,    0,    0,   0,  1,   0,    0,   0,    0,    0},
  {"cgal_refined_elephant.off",             44460,  88928,  0,    0,    0,   0,  1,   3,    0,   0,    0,    0},
  {"stanford_dragon_vrip_res2.ply.gz",      100250, 202520, 0,    0,    2534, 16, 7,  -1,   1489, 43, 0,    0},
  {"stanford_dragon_vrip_qp20_cl10.drc",    435545, 871306, 0,    0,    0,   0,  1,   55,   0,   0,    226,  0},
  // Joined from its two .xz parts by JoinedDragon below.
  {"stanford_dragon_vrip.ply",              437645, 871414, 4270, 407,  0,   0,  151, -1,   0,   0,    108,  0},
};
// clang-format on

std::string shared_data() {
  return testing_util::env_or("LODBAKE_SHARED_DATA", "");
}

// The full dragon, joined from its two xz parts into the build folder by
// the dragon_data target (tests/data/CMakeLists.txt).
std::string joined_dragon() {
  return testing_util::env_or("LODBAKE_DRAGON_PLY", "");
}

void expect_manifest(const Expected& e, const std::string& path) {
  SCOPED_TRACE(e.file);
  ImportReport import_report;
  Result<TriangleMesh> mesh = import_mesh_file(path, &import_report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  MeshCheckReport r = check_mesh(mesh.value());
  EXPECT_EQ(r.vertices, e.vertices);
  EXPECT_EQ(r.triangles, e.triangles);
  EXPECT_EQ(r.boundary_edges, e.boundary_edges);
  EXPECT_EQ(r.boundary_loops, e.boundary_loops);
  EXPECT_EQ(r.non_manifold_vertices, e.non_manifold_vertices);
  EXPECT_EQ(r.components, e.components);
  EXPECT_EQ(r.genus, e.genus);
  EXPECT_EQ(r.unreferenced_vertices, e.unreferenced_vertices);
  EXPECT_EQ(r.inconsistent_orientation_edges, e.inconsistent_orientation_edges);
  EXPECT_EQ(r.non_finite_coordinates, 0u);
  EXPECT_EQ(r.out_of_range_triangles, 0u);
  EXPECT_EQ(r.repeated_index_triangles, 0u);
  if (e.non_manifold_edges == kTriangulationDependent) {
    // Either the split avoids the doubled triangle or it makes exactly the
    // one duplicate MANIFEST describes, and its one 4-face edge.
    EXPECT_LE(r.duplicate_triangles, 1u);
    EXPECT_EQ(r.non_manifold_edges, r.duplicate_triangles);
  } else {
    EXPECT_EQ(r.non_manifold_edges, static_cast<uint64_t>(e.non_manifold_edges));
    EXPECT_EQ(r.duplicate_triangles, static_cast<uint64_t>(e.duplicate_triangles));
  }
  if (e.zero_area_triangles == kTriangulationDependent) {
    EXPECT_LE(r.zero_area_triangles, 2u);
  } else {
    EXPECT_EQ(r.zero_area_triangles, static_cast<uint64_t>(e.zero_area_triangles));
  }
}

TEST(MeshCheckManifest, EveryMeshMatchesItsRow) {
  ASSERT_FALSE(shared_data().empty()) << "LODBAKE_SHARED_DATA is not set";
  for (const Expected& e : kManifest) {
    const std::string name = e.file;
    if (name == "stanford_dragon_vrip.ply") continue;  // JoinedDragon
    expect_manifest(e, shared_data() + "/meshes/" + name);
  }
}

TEST(MeshCheckManifest, JoinedDragon) {
  ASSERT_FALSE(shared_data().empty()) << "LODBAKE_SHARED_DATA is not set";
  const std::string path = joined_dragon();
  ASSERT_FALSE(path.empty()) << "LODBAKE_DRAGON_PLY is not set";
  expect_manifest(kManifest[sizeof(kManifest) / sizeof(kManifest[0]) - 1], path);
}

}  // namespace
}  // namespace lodbake
