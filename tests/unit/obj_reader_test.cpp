// parse_obj: every OBJ of ../shared/data/meshes with MANIFEST.md's counts,
// every OBJ of bad/ with the outcome its README requires, and small
// in-memory files for each feature and failure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "lib/meshio/mesh_readers.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::all_notes;
using testing_util::expect_bad_files_rejected;
using testing_util::expect_rejected;
using testing_util::has_note;
using testing_util::shared_file;

Result<TriangleMesh> parse(const std::string& text, ImportReport* report = nullptr) {
  return parse_obj(reinterpret_cast<const uint8_t*>(text.data()), text.size(), report);
}

Result<TriangleMesh> parse_shared(const std::string& relative, ImportReport* report = nullptr) {
  Bytes bytes = shared_file(relative);
  return parse_obj(bytes.data(), bytes.size(), report);
}

// Every index of the mesh and of its attributes is in range.
void expect_consistent(const TriangleMesh& mesh) {
  for (const Triangle& t : mesh.triangles) {
    for (uint32_t i : t)
      ASSERT_LT(i, mesh.positions.size());
  }
  for (const MeshAttribute* a : {&mesh.normals, &mesh.texcoords}) {
    if (a->binding == AttributeBinding::kPerVertex) {
      EXPECT_EQ(a->value_count(), mesh.positions.size());
    } else if (a->binding == AttributeBinding::kPerCorner) {
      ASSERT_EQ(a->corners.size(), mesh.triangles.size());
      for (const Triangle& t : a->corners) {
        for (uint32_t i : t)
          ASSERT_LT(i, a->value_count());
      }
    }
  }
}

struct Expected {
  const char* file;
  size_t vertices;
  size_t triangles;
  uint64_t file_faces;
  AttributeBinding normals;
  AttributeBinding texcoords;
};

TEST(ObjReader, SharedMeshesHaveManifestCounts) {
  const AttributeBinding kNone = AttributeBinding::kNone;
  const AttributeBinding kVertex = AttributeBinding::kPerVertex;
  const AttributeBinding kCorner = AttributeBinding::kPerCorner;
  const Expected expected[] = {
      {"meshes/draco_test_nm.obj", 114, 170, 170, kVertex, kNone},
      {"meshes/c3d_suzanne.obj", 507, 968, 500, kVertex, kNone},
      {"meshes/c3d_beetle.obj", 1148, 2053, 2053, kCorner, kNone},
      {"meshes/npm_bunny.obj", 1839, 3674, 3674, kNone, kNone},
      {"meshes/c3d_spot.obj", 2930, 5856, 5856, kNone, kCorner},
      {"meshes/c3d_teapot.obj", 3644, 6320, 6320, kNone, kNone},
      {"meshes/c3d_rocker-arm.obj", 10044, 20088, 20088, kNone, kNone},
      {"meshes/igl_armadillo.obj", 43243, 86482, 86482, kNone, kNone},
  };
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.file);
    ImportReport report;
    Result<TriangleMesh> mesh = parse_shared(e.file, &report);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    EXPECT_EQ(mesh.value().vertex_count(), e.vertices);
    EXPECT_EQ(mesh.value().triangle_count(), e.triangles);
    EXPECT_EQ(report.file_faces, e.file_faces);
    EXPECT_EQ(report.format, "obj");
    EXPECT_EQ(mesh.value().normals.binding, e.normals);
    EXPECT_EQ(mesh.value().texcoords.binding, e.texcoords);
    expect_consistent(mesh.value());
  }
}

TEST(ObjReader, SuzanneQuadsAreSplitAndNoted) {
  ImportReport report;
  Result<TriangleMesh> mesh = parse_shared("meshes/c3d_suzanne.obj", &report);
  ASSERT_TRUE(mesh.is_ok());
  EXPECT_EQ(report.polygons_triangulated, 468u);
  // Per-vertex normals: one value per vertex, equal to the file's vn lines.
  EXPECT_EQ(mesh.value().normals.values.size(), 507u * 3);
}

TEST(ObjReader, BeetleNotesItsIgnoredStatements) {
  ImportReport report;
  ASSERT_TRUE(parse_shared("meshes/c3d_beetle.obj", &report).is_ok());
  EXPECT_TRUE(has_note(report, "ignored 1 'mtllib' statement (materials)")) << all_notes(report);
  EXPECT_TRUE(has_note(report, "ignored 1 'o' statement (object names)")) << all_notes(report);
  EXPECT_TRUE(has_note(report, "ignored 1 's' statement (smoothing groups)")) << all_notes(report);
}

TEST(ObjReader, BadFilesAreRejectedWithAClearMessage) {
  expect_bad_files_rejected(
      {
          {"bad/assimp_empty.obj", "empty file"},
          {"bad/hw_garbage.obj", "binary data where text was expected: NUL byte at byte"},
          {"bad/hw_ply_named.obj", "no vertices or faces found (the text starts with 'ply'"},
          {"bad/hw_nan_coords.obj", "line 3: a vertex coordinate 'NaN' is not finite"},
          {"bad/draco_inf_nan.obj", "line 1: a vertex coordinate 'inf' is not finite"},
          {"bad/hw_obj_index_out_of_range.obj", "line 7: vertex index 5 out of range (4 so far)"},
          {"bad/assimp_malformed.obj", "line 23: vertex index 12 out of range (8 so far)"},
          {"bad/hw_short_faces.obj", "line 5: face has 2 corners, at least 3 needed"},
      },
      [](const char* file) { return parse_shared(file); });
}

TEST(ObjReader, DegenerateAndNonManifoldBadFilesAreReadAsStored) {
  // "Handle or reject clearly": the reader keeps them; the mesh check and
  // --repair deal with the topology.
  const Expected cases[] = {
      {"bad/draco_deg_faces.obj", 6, 4, 4, AttributeBinding::kNone, AttributeBinding::kNone},
      {"bad/draco_degenerate_mesh.obj", 3, 1, 1, AttributeBinding::kNone, AttributeBinding::kNone},
      {"bad/draco_non_manifold_wrap.obj", 10, 12, 12, AttributeBinding::kNone,
       AttributeBinding::kNone},
  };
  for (const Expected& e : cases) {
    SCOPED_TRACE(e.file);
    ImportReport report;
    Result<TriangleMesh> mesh = parse_shared(e.file, &report);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    EXPECT_EQ(mesh.value().vertex_count(), e.vertices);
    EXPECT_EQ(mesh.value().triangle_count(), e.triangles);
  }
  Result<TriangleMesh> deg = parse_shared("bad/draco_deg_faces.obj");
  ASSERT_TRUE(deg.is_ok());
  EXPECT_EQ(deg.value().triangles[3], (Triangle{0, 0, 2})) << "repeated index kept as stored";
}

TEST(ObjReader, ConcaveSlitPolygonIsEarClipped) {
  ImportReport report;
  Result<TriangleMesh> mesh = parse_shared("bad/assimp_concave_polygon.obj", &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  const TriangleMesh& m = mesh.value();
  EXPECT_EQ(m.vertex_count(), 64u);
  EXPECT_EQ(m.triangle_count(), 64u) << "one 66-corner polygon";
  EXPECT_EQ(report.polygons_triangulated, 1u);
  EXPECT_FALSE(has_note(report, "could not finish")) << all_notes(report);
  EXPECT_FALSE(has_note(report, "intersect themselves")) << all_notes(report);
  // The ring lies in the plane x = -1.146 and its one normal is +x. Every
  // triangle must face +x (no flipped, overlapping triangles), and together
  // they must cover the polygon's area exactly once.
  double triangle_area = 0;
  for (const Triangle& t : m.triangles) {
    const Vec3f& a = m.positions[t[0]];
    const Vec3f& b = m.positions[t[1]];
    const Vec3f& c = m.positions[t[2]];
    double nx = (double{b[1]} - a[1]) * (double{c[2]} - a[2]) -
                (double{b[2]} - a[2]) * (double{c[1]} - a[1]);
    EXPECT_GE(nx, 0);
    triangle_area += 0.5 * nx;
  }
  // Shoelace area of the stored polygon in (y, z).
  const uint32_t ring[] = {27, 23, 19, 15, 11, 5,  2,  1,  3,  6,  12, 16, 20, 24, 28, 34, 38,
                           42, 46, 50, 54, 60, 63, 64, 62, 59, 53, 49, 45, 41, 37, 31, 32, 35,
                           39, 43, 47, 51, 55, 57, 61, 58, 56, 52, 48, 44, 40, 36, 33, 30, 26,
                           22, 18, 14, 10, 8,  4,  7,  9,  13, 17, 21, 25, 29, 32, 31};
  double polygon_area = 0;
  const size_t n = sizeof(ring) / sizeof(ring[0]);
  for (size_t i = 0; i < n; ++i) {
    const Vec3f& p = m.positions[ring[i] - 1];
    const Vec3f& q = m.positions[ring[(i + 1) % n] - 1];
    polygon_area += 0.5 * (double{p[1]} * q[2] - double{q[1]} * p[2]);
  }
  EXPECT_GT(polygon_area, 0);
  EXPECT_NEAR(triangle_area, polygon_area, 1e-4);
  EXPECT_EQ(m.normals.binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(m.normals.value_count(), 1u);
}

TEST(ObjReader, Utf16FileIsDecoded) {
  ImportReport report;
  Result<TriangleMesh> mesh = parse_shared("bad/assimp_box_UTF16BE.obj", &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().vertex_count(), 8u);
  EXPECT_EQ(mesh.value().triangle_count(), 12u);
  EXPECT_EQ(report.file_faces, 6u);
  EXPECT_TRUE(has_note(report, "decoded UTF-16BE text")) << all_notes(report);
}

TEST(ObjReader, IndexFormsAndRelativeIndices) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "vn 0 0 1\n"
      "f 1/4/1 2/3/1 3/2/1\n"
      "f -4/-1/-1 -2/-3/-1 -1/-4/-1\n";
  Result<TriangleMesh> mesh = parse(text);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  const TriangleMesh& m = mesh.value();
  ASSERT_EQ(m.triangle_count(), 2u);
  EXPECT_EQ(m.triangles[1], (Triangle{0, 2, 3}));
  ASSERT_EQ(m.texcoords.binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(m.texcoords.corners[0], (Triangle{3, 2, 1}));
  EXPECT_EQ(m.texcoords.corners[1], (Triangle{3, 1, 0}));
  ASSERT_EQ(m.normals.binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(m.normals.corners[1], (Triangle{0, 0, 0}));
  expect_consistent(m);
}

TEST(ObjReader, IdentityCornerIndicesBecomePerVertex) {
  Result<TriangleMesh> mesh =
      parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.25\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  ASSERT_TRUE(mesh.is_ok());
  EXPECT_EQ(mesh.value().texcoords.binding, AttributeBinding::kPerVertex);
  EXPECT_EQ(mesh.value().texcoords.values, (std::vector<float>{0.5f, 0.25f, 1, 0, 0, 1}));
  EXPECT_TRUE(mesh.value().texcoords.corners.empty());
}

TEST(ObjReader, PolygonCornersCarryTheirAttributes) {
  // A concave pentagon whose texcoord indices are the reverse of its vertex
  // indices: after ear clipping every output corner keeps its own pair.
  Result<TriangleMesh> mesh = parse(
      "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 1 0.5 0\nv 0 2 0\n"
      "vt 0 0\nvt 0 0\nvt 0 0\nvt 0 0\nvt 0 0\n"
      "f 1/5 2/4 3/3 4/2 5/1\n");
  ASSERT_TRUE(mesh.is_ok());
  const TriangleMesh& m = mesh.value();
  ASSERT_EQ(m.triangle_count(), 3u);
  for (size_t t = 0; t < 3; ++t) {
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(m.texcoords.corners[t][k], 4 - m.triangles[t][k]);
  }
}

TEST(ObjReader, MixedAttributePresenceAcrossFacesDropsTheAttribute) {
  ImportReport report;
  Result<TriangleMesh> mesh =
      parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n", &report);
  ASSERT_TRUE(mesh.is_ok());
  EXPECT_FALSE(mesh.value().texcoords.present());
  EXPECT_TRUE(has_note(report, "dropped texture coordinates: 1 of 2 faces have none"))
      << all_notes(report);
}

TEST(ObjReader, MixedFormsWithinAFaceAreRejected) {
  expect_rejected(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3/1\n"),
                  "line 5: face mixes corners");
}

TEST(ObjReader, IndexErrorsNameTheLine) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  struct Case {
    std::string face;
    std::string message;
  } cases[] = {
      {"f 1 2 0", "line 4: vertex index 0 is invalid (OBJ indices start at 1)"},
      {"f 1 2 4", "line 4: vertex index 4 out of range (3 so far)"},
      {"f 1 2 -4", "line 4: relative vertex index -4 reaches before the first one (3 so far)"},
      {"f 1 2 -9223372036854775808", "relative vertex index"},
      {"f 1 2 99999999999999999999", "expected a vertex index, found '99999999999999999999'"},
      {"f 1/1 2/1 3/1", "line 4: texture coordinate index 1 out of range (0 so far)"},
      {"f 1//1 2//1 3//1", "line 4: normal index 1 out of range (0 so far)"},
      {"f 1/ 2/ 3/", "malformed face corner '1/'"},
      {"f 1/1/ 2 3", "malformed face corner '1/1/'"},
      {"f 1//1/1 2 3", "malformed face corner"},
      {"f 1 2 x", "expected a vertex index, found 'x'"},
      {"f", "line 4: face has 0 corners, at least 3 needed"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.face);
    expect_rejected(parse(vertices + c.face + "\n"), c.message);
  }
}

TEST(ObjReader, VertexErrors) {
  struct Case {
    std::string text;
    std::string message;
  } cases[] = {
      {"v 0 0\nf 1 1 1\n", "line 1: expected a vertex coordinate, found the end of the line"},
      {"v 0 zero 0\n", "line 1: expected a vertex coordinate, found 'zero'"},
      {"v 0 0 1e39\n", "line 1: a vertex coordinate '1e39' is out of range"},
      {"\n\nvt nan 0\n", "line 3: a texture coordinate 'nan' is not finite"},
      {"vt 0 -inf\n", "line 1: texture coordinate '-inf' is not finite"},
      {"vn 0 0 1 1\n", "line 1: 'vn' takes 3 numbers"},
      {"v 0 0 0\n", "no faces found (1 vertices)"},
      {"# only a comment\n", "no vertices or faces found"},
      {"OFF\n3 1 0\n", "an OFF file?"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    expect_rejected(parse(c.text), c.message);
  }
}

TEST(ObjReader, ExtrasAreNotedNotErrors) {
  ImportReport report;
  Result<TriangleMesh> mesh = parse(
      "mtllib a.mtl\no thing\ng g1\ng g2\ns off\nusemtl red\n"
      "v 0 0 0 1 0 0\nv 1 0 0 0.5\nv 0 1 0\n"
      "vt 0 0 0\nvn 0 0 1\nl 1 2\np 1\n"
      "f 1 2 3 # trailing comment\n"
      "frobnicate 1 2\n",
      &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().triangle_count(), 1u);
  EXPECT_TRUE(has_note(report, "ignored 2 'g' statements (groups)")) << all_notes(report);
  EXPECT_TRUE(has_note(report, "ignored 1 'usemtl' statement (materials)"));
  EXPECT_TRUE(has_note(report, "ignored 1 'l' statement (line elements)"));
  EXPECT_TRUE(has_note(report, "ignored 1 'p' statement (point elements)"));
  EXPECT_TRUE(has_note(report, "(w or a vertex colour) on 2 'v' lines"));
  EXPECT_TRUE(has_note(report, "ignored the values after u v on 1 'vt' lines"));
  EXPECT_TRUE(has_note(report, "ignored 1 texture coordinates ('vt') that no face uses"));
  EXPECT_TRUE(has_note(report, "ignored 1 normals ('vn') that no face uses"));
  EXPECT_TRUE(has_note(report, "ignored 1 lines with an unknown statement"));
}

TEST(ObjReader, LineEndingsContinuationAndSigns) {
  Result<TriangleMesh> mesh =
      parse("v +1 -0 .5\r\nv 1e0 1 0\rv 0 1 0\r\n  \tf 1 2 \\\n 3\nf 3 2 1");
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().triangle_count(), 2u);
  EXPECT_EQ(mesh.value().positions[0], (Vec3f{1, -0.0f, 0.5f}));
  // Errors after a continuation count the joined lines.
  expect_rejected(parse("v 0 0 0\nf 1 \\\n 1 \\\n 1 x\n"), "line 4: expected a vertex index");
}

TEST(ObjReader, EveryPrefixParsesOrFailsCleanly) {
  Bytes bytes = shared_file("meshes/draco_test_nm.obj");
  size_t ok = 0;
  for (size_t n = 0; n <= bytes.size(); ++n) {
    Result<TriangleMesh> mesh = parse_obj(bytes.data(), n, nullptr);
    if (mesh.is_ok()) {
      ++ok;
      expect_consistent(mesh.value());
    } else {
      EXPECT_FALSE(mesh.status().message().empty());
    }
  }
  EXPECT_GT(ok, 0u) << "prefixes that end after a complete face parse";
}

}  // namespace
}  // namespace lodbake
