// parse_off: every OFF of ../shared/data/meshes with MANIFEST.md's counts,
// every OFF of bad/ with the outcome its README requires, and small
// in-memory files for each header variant and failure.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "lib/meshio/mesh_readers.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::all_notes;
using testing_util::expect_bad_files_rejected;
using testing_util::expect_error;
using testing_util::expect_rejected;
using testing_util::has_note;
using testing_util::shared_file;

Result<TriangleMesh> parse(const std::string& text, ImportReport* report = nullptr) {
  return parse_off(reinterpret_cast<const uint8_t*>(text.data()), text.size(), report);
}

Result<TriangleMesh> parse_shared(const std::string& relative, ImportReport* report = nullptr) {
  Bytes bytes = shared_file(relative);
  return parse_off(bytes.data(), bytes.size(), report);
}

struct Expected {
  const char* file;
  size_t vertices;
  size_t triangles;  // after splitting polygons
  uint64_t file_faces;
};

TEST(OffReader, SharedMeshesHaveManifestCounts) {
  const Expected expected[] = {
      {"meshes/cgal_tetrahedron.off", 4, 4, 4},
      {"meshes/cgal_degtri_sliding.off", 8, 8, 8},
      {"meshes/cgal_cube_quad.off", 8, 12, 6},
      {"meshes/cgal_mpi.off", 90, 180, 52},
      {"meshes/cgal_oblong-shuffled.off", 424, 840, 840},
      {"meshes/igl_decimated-knight.off", 502, 1000, 1000},
      {"meshes/cgal_blobby_3cc.off", 1820, 3417, 3417},
      {"meshes/assimp_Wuson.off", 3205, 3732, 3732},
      {"meshes/cgal_elephant-with-holes.off", 2798, 4463, 4463},
      {"meshes/cgal_mushroom.off", 2337, 4608, 4608},
      {"meshes/cgal_elephant.off", 2775, 5558, 5558},
      {"meshes/igl_fertility.off", 4494, 9000, 9000},
      {"meshes/cgal_knot2.off", 5760, 11520, 11520},
      {"meshes/cgal_fandisk.off", 6475, 12946, 12946},
      {"meshes/cgal_cheese.off", 8629, 17786, 17786},
      {"meshes/cgal_camel.off", 9770, 19536, 19536},
      {"meshes/cgal_ChineseDragon-10kv.off", 10000, 19994, 19994},
      {"meshes/igl_camelhead.off", 11381, 22704, 22704},
      {"meshes/cgal_man.off", 17495, 34986, 34986},
      {"meshes/cgal_armadillo.off", 26002, 52000, 52000},
      {"meshes/cgal_bunny00.off", 37706, 75408, 75408},
      {"meshes/cgal_refined_elephant.off", 44460, 88928, 88928},
  };
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.file);
    ImportReport report;
    Result<TriangleMesh> mesh = parse_shared(e.file, &report);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    EXPECT_EQ(mesh.value().vertex_count(), e.vertices);
    EXPECT_EQ(mesh.value().triangle_count(), e.triangles);
    EXPECT_EQ(report.file_faces, e.file_faces);
    EXPECT_EQ(report.format, "off");
    EXPECT_TRUE(report.notes.empty() || e.triangles != e.file_faces) << all_notes(report);
    for (const Triangle& t : mesh.value().triangles) {
      for (uint32_t i : t)
        ASSERT_LT(i, e.vertices);
    }
  }
}

TEST(OffReader, PolygonsAreFannedAndCounted) {
  ImportReport report;
  Result<TriangleMesh> cube = parse_shared("meshes/cgal_cube_quad.off", &report);
  ASSERT_TRUE(cube.is_ok());
  EXPECT_EQ(report.polygons_triangulated, 6u);
  // First quad "4  0 3 7 4" (convex) as the fan (0, i, i+1) of its corners.
  EXPECT_EQ(cube.value().triangles[0], (Triangle{0, 3, 7}));
  EXPECT_EQ(cube.value().triangles[1], (Triangle{0, 7, 4}));
  ImportReport mpi_report;
  ASSERT_TRUE(parse_shared("meshes/cgal_mpi.off", &mpi_report).is_ok());
  EXPECT_EQ(mpi_report.polygons_triangulated, 52u - 13u);
}

TEST(OffReader, BadFilesAreRejectedWithAClearMessage) {
  expect_bad_files_rejected(
      {
          {"bad/assimp_empty.off", "empty file"},
          {"bad/hw_garbage.off", "binary data where text was expected"},
          {"bad/hw_huge_count.off",
           "header declares 2000000000 vertices but the file has room for at most 4"},
          {"bad/assimp_OutOfMemory.off",
           "header declares 353535235358 vertices but the file has room for at most 48"},
          {"bad/hw_negative_count.off", "line 3: negative vertex count -3"},
          {"bad/hw_non_numeric.off", "line 4: expected a vertex coordinate, found 'zero'"},
          // Its 3 vertices leave too few bytes for 4 faces: the bound catches it
          // before the 0-gon is read (a 0-gon on its own is tested below).
          {"bad/assimp_invalid.off",
           "header declares 4 faces but the file has room for at most 3 after the vertices"},
          {"bad/hw_nan_coords.off", "line 5: a vertex coordinate 'nan' is not finite"},
          {"bad/hw_off_two_vertex_face.off", "line 9: face has 2 corners, at least 3 needed"},
      },
      [](const char* file) { return parse_shared(file); });
}

TEST(OffReader, HandleOrRejectBadFilesAreReadAsStored) {
  const Expected cases[] = {
      {"bad/hw_nonmanifold_edge_3tris.off", 5, 3, 3},
      {"bad/hw_nonmanifold_vertex_two_cones.off", 15, 24, 24},
      {"bad/hw_nonmanifold_vertex_bowtie.off", 5, 2, 2},
      {"bad/hw_degenerate_zero_area.off", 6, 6, 6},
      {"bad/hw_duplicate_faces.off", 4, 6, 6},
      {"bad/hw_inconsistent_orientation.off", 4, 4, 4},
      {"bad/hw_unreferenced_vertices.off", 7, 4, 4},
  };
  for (const Expected& e : cases) {
    SCOPED_TRACE(e.file);
    Result<TriangleMesh> mesh = parse_shared(e.file);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    EXPECT_EQ(mesh.value().vertex_count(), e.vertices);
    EXPECT_EQ(mesh.value().triangle_count(), e.triangles);
  }
  Result<TriangleMesh> deg = parse_shared("bad/hw_degenerate_zero_area.off");
  ASSERT_TRUE(deg.is_ok());
  EXPECT_EQ(deg.value().triangles[5], (Triangle{3, 3, 3})) << "kept for the mesh check";
}

TEST(OffReader, HeaderVariants) {
  // Counts on the keyword line, comments everywhere, no edge count.
  Result<TriangleMesh> plain =
      parse("# c\nOFF 3 1 # counts\n0 0 0 # v0\n1 0 0\n# between\n0 1 0\n3 0 1 2 # f\n");
  ASSERT_TRUE(plain.is_ok()) << plain.status().message();
  EXPECT_EQ(plain.value().triangle_count(), 1u);
  Result<TriangleMesh> no_edges = parse("OFF\n3 1\n0 0 0 1 0 0 0 1 0\n3 0 1 2\n");
  ASSERT_TRUE(no_edges.is_ok()) << no_edges.status().message();
  EXPECT_EQ(no_edges.value().positions[2], (Vec3f{0, 1, 0})) << "vertices may share a line";

  Result<TriangleMesh> noff =
      parse("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 -1\n3 0 1 2\n");
  ASSERT_TRUE(noff.is_ok()) << noff.status().message();
  EXPECT_EQ(noff.value().normals.binding, AttributeBinding::kPerVertex);
  EXPECT_EQ(noff.value().normals.values, (std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, -1}));

  ImportReport report;
  Result<TriangleMesh> coff =
      parse("COFF\n3 1 0\n0 0 0 255 0 0\n1 0 0 0 255 0 255\n0 1 0 0.1 0.2 0.3 1\n3 0 1 2 1 0 0\n",
            &report);
  ASSERT_TRUE(coff.is_ok()) << coff.status().message();
  EXPECT_FALSE(coff.value().normals.present());
  EXPECT_TRUE(has_note(report, "ignored the colours of 3 vertices")) << all_notes(report);
  EXPECT_TRUE(has_note(report, "ignored the colours of 1 faces")) << all_notes(report);

  Result<TriangleMesh> stcnoff = parse(
      "STCNOFF\n3 1 0\n0 0 0 0 0 1 9 9 9 0.25 0.5\n1 0 0 0 0 1 9 9 9 1 0\n"
      "0 1 0 0 0 1 9 9 9 9 0 1\n3 0 1 2\n");
  ASSERT_TRUE(stcnoff.is_ok()) << stcnoff.status().message();
  EXPECT_EQ(stcnoff.value().texcoords.binding, AttributeBinding::kPerVertex);
  EXPECT_EQ(stcnoff.value().texcoords.values, (std::vector<float>{0.25f, 0.5f, 1, 0, 0, 1}));
  EXPECT_EQ(stcnoff.value().normals.value_count(), 3u);

  Result<TriangleMesh> stoff = parse("STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n");
  ASSERT_TRUE(stoff.is_ok()) << stoff.status().message();
  EXPECT_EQ(stoff.value().texcoords.values, (std::vector<float>{0, 0, 1, 0, 0, 1}));

  Result<TriangleMesh> homogeneous = parse("4OFF\n3 1 0\n0 0 0 1\n2 0 0 2\n0 4 0 4\n3 0 1 2\n");
  ASSERT_TRUE(homogeneous.is_ok()) << homogeneous.status().message();
  EXPECT_EQ(homogeneous.value().positions[1], (Vec3f{1, 0, 0}));
  EXPECT_EQ(homogeneous.value().positions[2], (Vec3f{0, 1, 0}));

  Result<TriangleMesh> ndim = parse("nOFF\n3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ASSERT_TRUE(ndim.is_ok()) << ndim.status().message();
}

TEST(OffReader, HeaderErrors) {
  struct Case {
    std::string text;
    ErrorKind kind;
    std::string message;
  } cases[] = {
      {"PLY\n3 1 0\n", ErrorKind::kInvalidInput,
       "line 1: expected an OFF keyword (OFF, COFF, NOFF, STOFF, ...), found 'PLY'"},
      {"# nothing else\n", ErrorKind::kInvalidInput, "no OFF keyword"},
      {"OFF BINARY\n", ErrorKind::kUnsupported, "binary OFF ('OFF BINARY') is not supported"},
      {"nOFF 4 3 1 0\n", ErrorKind::kUnsupported, "vertices of dimension 4 are not supported"},
      {"OFF\n3\n", ErrorKind::kInvalidInput, "expected the face count, found the end of the file"},
      {"OFF\n3 x 0\n", ErrorKind::kInvalidInput, "line 2: expected the face count, found 'x'"},
      {"OFF\n3 1 -1\n0 0 0 1 0 0 0 1 0 3 0 1 2\n", ErrorKind::kInvalidInput,
       "negative edge count -1"},
      {"OFF\n3 99999999999999999999 0\n", ErrorKind::kInvalidInput,
       "face count '99999999999999999999' is out of range"},
      {"OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", ErrorKind::kInvalidInput, "header declares no faces"},
      {"OFF\n3 1000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", ErrorKind::kInvalidInput,
       "header declares 1000 faces but the file has room for at most"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    expect_error(parse(c.text), c.kind, c.message);
  }
}

TEST(OffReader, BodyErrors) {
  const std::string head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  struct Case {
    std::string text;
    std::string message;
  } cases[] = {
      {head + "3 0 1 3\n", "line 6: face index 3 out of range (3 vertices)"},
      {head + "3 0 1 -1\n", "line 6: face index -1 out of range (3 vertices)"},
      {head + "3 0 1\n", "face ends after 2 of its 3 corners"},
      {head + "3 0 1 2.5\n", "line 6: expected a face index, found '2.5'"},
      {head + "0\n# padding\n", "line 6: face has 0 corners, at least 3 needed"},
      {head + "x 0 1 2\n", "line 6: expected a face's corner count, found 'x'"},
      {head + "3 0 1 2 1 2 3 4 5\n", "line 6: more than 4 colour values after the face's 3"},
      {head + "9999 0 1 2\n", "line 6: face declares 9999 corners but only"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n# padding padding padding\n",
       "found the end of the file (2 of 3 vertices read)"},
      {"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# padding padding\n",
       "expected a face, found the end of the file (1 of 2 faces read)"},
      {"COFF\n3 1 0\n0 0 0 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1 2\n",
       "line 3: expected 3 or 4 colour values after the vertex, found 2 values"},
      {"4OFF\n3 1 0\n0 0 0 0\n1 0 0 1\n0 1 0 1\n3 0 1 2\n",
       "line 3: homogeneous vertex with w = 0"},
      {"OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n",
       "line 4: a vertex coordinate 'inf' is not finite"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    expect_rejected(parse(c.text), c.message);
  }
}

TEST(OffReader, TrailingTextIsNoted) {
  ImportReport report;
  Result<TriangleMesh> mesh =
      parse("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n# end\n", &report);
  ASSERT_TRUE(mesh.is_ok());
  EXPECT_EQ(mesh.value().triangle_count(), 1u);
  EXPECT_TRUE(has_note(report, "bytes after the last face (from line 7)")) << all_notes(report);
}

TEST(OffReader, EveryPrefixParsesOrFailsCleanly) {
  Bytes bytes = shared_file("meshes/cgal_mpi.off");
  size_t ok = 0;
  for (size_t n = 0; n <= bytes.size(); ++n) {
    Result<TriangleMesh> mesh = parse_off(bytes.data(), n, nullptr);
    if (mesh.is_ok()) {
      ++ok;
      EXPECT_EQ(mesh.value().triangle_count(), 180u);
    } else {
      EXPECT_FALSE(mesh.status().message().empty());
    }
  }
  // Only prefixes that keep all 52 faces the header declares can succeed:
  // the whole file, without its final line ends, or with the last index cut
  // to a shorter valid one.
  EXPECT_GE(ok, 1u);
  EXPECT_LE(ok, 5u);
}

}  // namespace
}  // namespace lodbake
