// parse_off: every OFF of ../shared/data/meshes with MANIFEST.md's counts,
// every OFF of bad/ with the outcome its README requires, and small
// in-memory files for each header variant and failure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
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
      {"OFF BINARY\n", ErrorKind::kInvalidInput,
       "byte 11: expected the vertex count, found the end of the file"},
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

// --- binary OFF ------------------------------------------------------------

// The bytes of a binary OFF, built word by word in one byte order.
class BinaryOff {
 public:
  BinaryOff(bool big_endian, const std::string& header = "OFF BINARY\n")
      : big_endian_(big_endian), bytes_(header) {}
  BinaryOff& i32(int64_t value) {
    const uint32_t bits = static_cast<uint32_t>(value);
    for (int i = 0; i < 4; ++i) {
      const int shift = big_endian_ ? 24 - 8 * i : 8 * i;
      bytes_.push_back(static_cast<char>((bits >> shift) & 0xFF));
    }
    return *this;
  }
  BinaryOff& f32(float value) {
    uint32_t bits = 0;
    std::memcpy(&bits, &value, 4);
    return i32(bits);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  bool big_endian_;
  std::string bytes_;
};

// A unit cube of 8 vertices and 6 quads (12 triangles); with `face_colours`,
// faces carry 0, 3, 4, 1, 0 and 2 colour values (Geomview's layout).
std::string binary_cube(bool big_endian, bool face_colours) {
  BinaryOff off(big_endian);
  off.i32(8).i32(6).i32(12);
  for (int v = 0; v < 8; ++v)
    off.f32(v & 1 ? 1.5f : -0.25f).f32(v & 2 ? 1.0f : 0.0f).f32(v & 4 ? 0.1f : 0.0f);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  const int colours[6] = {0, 3, 4, 1, 0, 2};
  for (int f = 0; f < 6; ++f) {
    off.i32(4);
    for (int c : quads[f])
      off.i32(c);
    if (face_colours) {
      off.i32(colours[f]);
      for (int k = 0; k < colours[f]; ++k)
        off.f32(0.5f);
    }
  }
  return off.bytes();
}

const char kTextCube[] =
    "OFF\n8 6 12\n-0.25 0 0\n1.5 0 0\n-0.25 1 0\n1.5 1 0\n-0.25 0 0.1\n1.5 0 0.1\n-0.25 1 0.1\n"
    "1.5 1 0.1\n4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";

TEST(OffReaderBinary, BothLayoutsReadTheSameMeshAsText) {
  Result<TriangleMesh> text = parse(kTextCube);
  ASSERT_TRUE(text.is_ok()) << text.status().message();
  ASSERT_EQ(text.value().triangle_count(), 12u);
  struct Case {
    bool big_endian;
    bool face_colours;
    const char* note;
  } cases[] = {
      {true, true, "big-endian, faces with colour counts (Geomview)"},
      {false, false, "little-endian, faces without colour counts (pmp-library)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.note);
    ImportReport report;
    Result<TriangleMesh> mesh = parse(binary_cube(c.big_endian, c.face_colours), &report);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    EXPECT_EQ(mesh.value(), text.value());
    EXPECT_EQ(report.format, "off-binary");
    EXPECT_EQ(report.file_faces, 6u);
    EXPECT_EQ(report.polygons_triangulated, 6u);
    EXPECT_TRUE(has_note(report, std::string("binary OFF read ") + c.note)) << all_notes(report);
    EXPECT_EQ(has_note(report, "ignored the colours of 4 faces"), c.face_colours)
        << all_notes(report);
  }
}

TEST(OffReaderBinary, HeaderVariants) {
  // Comments before the keyword, blanks and CR LF after BINARY.
  const std::string body = binary_cube(false, false).substr(11);
  Result<TriangleMesh> crlf = parse("# pmp\nOFF BINARY \r\n" + body);
  ASSERT_TRUE(crlf.is_ok()) << crlf.status().message();
  EXPECT_EQ(crlf.value().triangle_count(), 12u);

  // NOFF with ST: normals and texture coordinates per vertex; nOFF's
  // dimension word; C's four colour floats per vertex skipped with a note.
  for (bool big : {false, true}) {
    BinaryOff off(big, "STCNnOFF BINARY\n");
    off.i32(3).i32(3).i32(1).i32(0);
    for (int v = 0; v < 3; ++v) {
      off.f32(v == 1 ? 1.0f : 0.0f).f32(v == 2 ? 1.0f : 0.0f).f32(0);  // position
      off.f32(0).f32(0).f32(1);                                        // normal
      off.f32(1).f32(0).f32(0).f32(1);                                 // RGBA
      off.f32(0.25f * v).f32(0.5f);                                    // texture
    }
    off.i32(3).i32(0).i32(1).i32(2);
    if (big) off.i32(0);
    ImportReport report;
    Result<TriangleMesh> mesh = parse(off.bytes(), &report);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    EXPECT_EQ(mesh.value().positions, (std::vector<Vec3f>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    EXPECT_EQ(mesh.value().normals.values, (std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}));
    EXPECT_EQ(mesh.value().texcoords.values,
              (std::vector<float>{0, 0.5f, 0.25f, 0.5f, 0.5f, 0.5f}));
    EXPECT_TRUE(has_note(report, "ignored the colours of 3 vertices")) << all_notes(report);
  }

  // 4OFF divides by w.
  BinaryOff homogeneous(false, "4OFF BINARY\n");
  homogeneous.i32(3).i32(1).i32(0);
  homogeneous.f32(0).f32(0).f32(0).f32(1).f32(2).f32(0).f32(0).f32(2).f32(0).f32(4).f32(0).f32(4);
  homogeneous.i32(3).i32(0).i32(1).i32(2);
  Result<TriangleMesh> h = parse(homogeneous.bytes());
  ASSERT_TRUE(h.is_ok()) << h.status().message();
  EXPECT_EQ(h.value().positions[1], (Vec3f{1, 0, 0}));
  EXPECT_EQ(h.value().positions[2], (Vec3f{0, 1, 0}));
}

TEST(OffReaderBinary, TrailingBytesAreNoted) {
  ImportReport report;
  Result<TriangleMesh> mesh = parse(binary_cube(true, true) + "xyz", &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().triangle_count(), 12u);
  EXPECT_TRUE(has_note(report, "ignored 3 bytes after the last face")) << all_notes(report);
}

TEST(OffReaderBinary, Errors) {
  auto with_counts = [](bool big, int64_t nv, int64_t nf) {
    BinaryOff off(big);
    off.i32(nv).i32(nf).i32(0);
    return off;
  };
  auto triangle = [](BinaryOff off, int64_t a, int64_t b, int64_t c) {
    off.f32(0).f32(0).f32(0).f32(1).f32(0).f32(0).f32(0).f32(1).f32(0);
    off.i32(3).i32(a).i32(b).i32(c);
    return off.bytes();
  };
  struct Case {
    std::string bytes;
    std::string message;
  } cases[] = {
      {"OFF BINARY junk\n" + std::string(40, '\0'),
       "byte 11: expected the end of the line after 'OFF BINARY'"},
      {with_counts(false, 0x7FFFFFFF, 1).bytes() + std::string(64, '\0'),
       "header declares 2147483647 vertices and 1 faces, which need at least 25769803780 bytes, "
       "but "
       "64 bytes follow the counts (read little-endian"},
      {with_counts(true, 3, 0x7FFFFFFF).bytes() + std::string(64, '\0'),
       "header declares 3 vertices and 2147483647 faces"},
      {with_counts(false, -3, 1).bytes() + std::string(64, '\0'), "byte 11: negative vertex count"},
      {with_counts(false, 3, 0).bytes() + std::string(36, '\0'), "header declares no faces"},
      {triangle(with_counts(false, 3, 1), 0, 1, 3), "face 0: index 3 out of range (3 vertices)"},
      {triangle(with_counts(false, 3, 1), 0, 1, -1), "face 0: index -1 out of range (3 vertices)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    expect_rejected(parse(c.bytes), c.message);
  }

  // A face whose corner count exceeds the bytes left, a colour count over 4.
  BinaryOff corners = with_counts(false, 3, 1);
  corners.f32(0).f32(0).f32(0).f32(1).f32(0).f32(0).f32(0).f32(1).f32(0);
  corners.i32(1000000).i32(0).i32(1).i32(2);
  expect_rejected(parse(corners.bytes()), "byte 59: face 0 declares 1000000 corners but only 12");
  BinaryOff colours = with_counts(true, 3, 2);
  colours.f32(0).f32(0).f32(0).f32(1).f32(0).f32(0).f32(0).f32(1).f32(0);
  colours.i32(3).i32(0).i32(1).i32(2).i32(5);
  for (int k = 0; k < 5; ++k)
    colours.f32(0.5f);
  colours.i32(3).i32(0).i32(1).i32(2).i32(0);
  expect_rejected(parse(colours.bytes()), "byte 75: face 0: colour count 5 (at most 4)");
  BinaryOff overrun = with_counts(true, 3, 2);
  overrun.f32(0).f32(0).f32(0).f32(1).f32(0).f32(0).f32(0).f32(1).f32(0);
  overrun.i32(3).i32(0).i32(1).i32(2).i32(0).i32(3).i32(0).i32(1).i32(2).i32(2).f32(0.5f);
  expect_rejected(parse(overrun.bytes()), "byte 95: face 1: colour count 2 overruns the file");

  // Non-finite coordinates, as in the text form.
  BinaryOff nan = with_counts(false, 3, 1);
  nan.f32(0).f32(std::nanf("")).f32(0).f32(1).f32(0).f32(0).f32(0).f32(1).f32(0);
  nan.i32(3).i32(0).i32(1).i32(2);
  expect_rejected(parse(nan.bytes()), "byte 27: vertex 0: a value is not finite");
}

TEST(OffReaderBinary, EveryPrefixOfBothLayoutsFailsCleanly) {
  for (bool geomview : {true, false}) {
    SCOPED_TRACE(geomview ? "Geomview" : "pmp-library");
    const std::string bytes = binary_cube(geomview, geomview);
    for (size_t n = 0; n < bytes.size(); ++n) {
      Result<TriangleMesh> mesh =
          parse_off(reinterpret_cast<const uint8_t*>(bytes.data()), n, nullptr);
      // Cut anywhere, the file is refused with one line; a few cuts inside
      // the last face's colour floats could in principle still describe a
      // shorter valid layout, so only the message contract is required.
      if (!mesh.is_ok()) {
        const std::string& message = mesh.status().message();
        EXPECT_FALSE(message.empty());
        EXPECT_EQ(message.find('\n'), std::string::npos);
        EXPECT_NE(mesh.status().kind(), ErrorKind::kRuntime);
      } else {
        EXPECT_EQ(mesh.value().triangle_count(), 12u) << "prefix " << n;
      }
    }
  }
  // The pmp cube cut inside its vertices names the counts it read.
  const std::string pmp = binary_cube(false, false);
  expect_rejected(parse(pmp.substr(0, 60)),
                  "header declares 8 vertices and 6 faces, which need at least 192 bytes, but 37 "
                  "bytes follow the counts (read little-endian, faces without colour counts");
  // Cut inside its faces: the walk of the right layout gets furthest.
  expect_rejected(parse(pmp.substr(0, pmp.size() - 2)),
                  "byte 219: face 5 declares 4 corners but only 14 bytes remain");
}

}  // namespace
}  // namespace lodbake
