// parse_ply: the real meshes of ../shared/data (counts from MANIFEST.md, the
// full dragon from the build folder), every PLY in bad/ (outcomes from its
// README), and small in-memory files for each feature and failure.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "lib/meshio/gzip.h"
#include "lib/meshio/mesh_readers.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::env_or_fail;
using testing_util::expect_rejected;
using testing_util::has_note;
using testing_util::read_bytes;
using testing_util::text_bytes;

// The bytes of `path`, gunzipped when they are gzip data.
Bytes load(const std::string& path) {
  Bytes bytes = read_bytes(path);
  if (!is_gzip(bytes)) return bytes;
  Result<Bytes> plain = gunzip(bytes.data(), bytes.size());
  EXPECT_TRUE(plain.is_ok()) << path << ": " << plain.status().message();
  return plain.is_ok() ? std::move(plain).value() : Bytes{};
}

Bytes shared(const std::string& relative) {
  return load(env_or_fail("LODBAKE_SHARED_DATA") + "/" + relative);
}

Result<TriangleMesh> parse(const std::string& text, ImportReport* report = nullptr) {
  return parse_ply(reinterpret_cast<const uint8_t*>(text.data()), text.size(), report);
}

Result<TriangleMesh> parse(const Bytes& bytes, ImportReport* report = nullptr) {
  return parse_ply(bytes.data(), bytes.size(), report);
}

void expect_valid_indices(const TriangleMesh& mesh) {
  for (const Triangle& t : mesh.triangles) {
    for (uint32_t v : t)
      ASSERT_LT(v, mesh.positions.size());
  }
}

// ---------------------------------------------------------------- real meshes

struct ManifestRow {
  const char* file;
  size_t vertices;
  size_t triangles;
};

TEST(PlyReaderManifest, EveryPlyMeshHasTheManifestCounts) {
  const ManifestRow rows[] = {
      {"meshes/stanford_bun_zipper.ply", 35947, 69451},
      {"meshes/stanford_dragon_vrip_res4.ply.gz", 5205, 11102},
      {"meshes/stanford_dragon_vrip_res3.ply.gz", 22998, 47794},
      {"meshes/stanford_dragon_vrip_res2.ply.gz", 100250, 202520},
  };
  for (const ManifestRow& row : rows) {
    SCOPED_TRACE(row.file);
    ImportReport report;
    Result<TriangleMesh> mesh = parse(shared(row.file), &report);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    EXPECT_EQ(mesh.value().vertex_count(), row.vertices);
    EXPECT_EQ(mesh.value().triangle_count(), row.triangles);
    EXPECT_EQ(report.file_faces, row.triangles);
    EXPECT_EQ(report.format, "ply-ascii");
    expect_valid_indices(mesh.value());
  }
}

TEST(PlyReaderManifest, BunnyNotesItsExtraVertexProperties) {
  ImportReport report;
  Result<TriangleMesh> mesh = parse(shared("meshes/stanford_bun_zipper.ply"), &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_TRUE(has_note(report, "ignored vertex property 'confidence'"));
  EXPECT_TRUE(has_note(report, "ignored vertex property 'intensity'"));
  EXPECT_EQ(report.notes.size(), 2u);
  EXPECT_FALSE(mesh.value().normals.present());
  // First vertex line: -0.0378297 0.12794 0.00447467 0.850855 0.5
  EXPECT_EQ(mesh.value().positions[0], (Vec3f{-0.0378297f, 0.12794f, 0.00447467f}));
}

TEST(PlyReaderManifest, FullDragonFromTheBuildFolder) {
  const std::string path = env_or_fail("LODBAKE_DRAGON_PLY");
  Bytes bytes = load(path);
  ASSERT_EQ(bytes.size(), 33831477u);
  auto start = std::chrono::steady_clock::now();
  ImportReport report;
  Result<TriangleMesh> mesh = parse(bytes, &report);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().vertex_count(), 437645u);
  EXPECT_EQ(mesh.value().triangle_count(), 871414u);
  expect_valid_indices(mesh.value());
  // Informational only: timing depends on the machine and the build type.
  std::printf("parse_ply(dragon_vrip.ply, 33.8 MB): %.3f s\n", seconds);
  RecordProperty("dragon_parse_ms", static_cast<int>(seconds * 1000));
}

// ------------------------------------------------------------------ bad/*.ply

TEST(PlyReaderBadInputs, EachFileHasItsDocumentedOutcome) {
  testing_util::expect_bad_files_rejected(
      {
          {"bad/assimp_empty.ply", "empty file"},
          {"bad/hw_garbage.ply", "bad magic"},
          {"bad/hw_bad_magic.ply", "bad magic"},
          {"bad/hw_missing_end_header.ply", "no 'end_header' line"},
          {"bad/hw_truncated_ascii.ply", "element 'vertex' declares 8 items"},
          {"bad/hw_truncated_binary_le.ply",
           "the body ends after 80 bytes, but element 'face' declares 4 items, which need at least "
           "100 bytes"},
          {"bad/hw_face_list_overrun.ply", "list length 255 overruns the file"},
          {"bad/hw_huge_count_binary.ply", "element 'vertex' declares 2000000000 items"},
          {"bad/hw_huge_count_ascii.ply", "element 'vertex' declares 4294967295 items"},
          {"bad/hw_wrong_endian.ply", "out of range (4 vertices)"},
          {"bad/hw_nan_inf_binary.ply", "non-finite"},
      },
      [](const char* file) { return parse(shared(file)); });
}

TEST(PlyReaderBadInputs, PlySavedAsObjIsReadByContent) {
  Result<TriangleMesh> mesh = parse(shared("bad/hw_ply_named.obj"));
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().vertex_count(), 4u);
  EXPECT_EQ(mesh.value().triangle_count(), 4u);
}

TEST(PlyReaderBadInputs, BigEndianOctahedronIsReadExactly) {
  ImportReport report;
  Result<TriangleMesh> result = parse(shared("bad/hw_valid_binary_big_endian.ply"), &report);
  ASSERT_TRUE(result.is_ok()) << result.status().message();
  const TriangleMesh& mesh = result.value();
  EXPECT_EQ(report.format, "ply-binary-be");
  const std::vector<Vec3f> positions = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                        {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  const std::vector<Triangle> triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                           {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  EXPECT_EQ(mesh.positions, positions);
  EXPECT_EQ(mesh.triangles, triangles);
  // Outward winding: each face normal points away from the centre.
  for (const Triangle& t : mesh.triangles) {
    const Vec3f& a = mesh.positions[t[0]];
    const Vec3f& b = mesh.positions[t[1]];
    const Vec3f& c = mesh.positions[t[2]];
    float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                  e1[0] * e2[1] - e1[1] * e2[0]};
    EXPECT_GT(
        n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]),
        0.0f);
  }
  for (const char* colour : {"'red'", "'green'", "'blue'"}) {
    EXPECT_TRUE(has_note(report, std::string("ignored vertex property ") + colour)) << colour;
  }
}

// ------------------------------------------------------- in-memory PLY builder

const char* type_name(int type) {
  static const char* const kNames[] = {"char", "uchar", "short", "ushort",
                                       "int",  "uint",  "float", "double"};
  return kNames[type];
}
const char* type_alias(int type) {
  static const char* const kNames[] = {"int8",  "uint8",  "int16",   "uint16",
                                       "int32", "uint32", "float32", "float64"};
  return kNames[type];
}

// Appends a value of PLY type `type` (0..7 as in type_name) in either byte order.
void put(Bytes* out, int type, double value, bool big_endian) {
  uint8_t raw[8];
  size_t n = 0;
  switch (type) {
    case 0: {
      int8_t v = static_cast<int8_t>(value);
      std::memcpy(raw, &v, n = 1);
      break;
    }
    case 1: {
      uint8_t v = static_cast<uint8_t>(value);
      std::memcpy(raw, &v, n = 1);
      break;
    }
    case 2: {
      int16_t v = static_cast<int16_t>(value);
      std::memcpy(raw, &v, n = 2);
      break;
    }
    case 3: {
      uint16_t v = static_cast<uint16_t>(value);
      std::memcpy(raw, &v, n = 2);
      break;
    }
    case 4: {
      int32_t v = static_cast<int32_t>(value);
      std::memcpy(raw, &v, n = 4);
      break;
    }
    case 5: {
      uint32_t v = static_cast<uint32_t>(value);
      std::memcpy(raw, &v, n = 4);
      break;
    }
    case 6: {
      float v = static_cast<float>(value);
      std::memcpy(raw, &v, n = 4);
      break;
    }
    default: {
      std::memcpy(raw, &value, n = 8);
      break;
    }
  }
  if (big_endian) {
    for (size_t i = 0; i < n / 2; ++i)
      std::swap(raw[i], raw[n - 1 - i]);
  }
  out->insert(out->end(), raw, raw + n);
}

const char* kTetraAscii =
    "ply\n"
    "format ascii 1.0\n"
    "comment a tetrahedron\n"
    "obj_info made by hand\n"
    "element vertex 4\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 4\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0\n"
    "1 0 0\n"
    "0 1 0\n"
    "0 0 1\n"
    "3 0 2 1\n"
    "3 0 1 3\n"
    "3 0 3 2\n"
    "3 1 2 3\n";

const std::vector<Vec3f> kTetraPositions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<Triangle> kTetraTriangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

// The tetrahedron as a binary file with the given vertex, list-length and
// index types.
Bytes binary_tetra(int coord_type, int count_type, int index_type, bool big_endian,
                   bool aliases = false) {
  auto name = aliases ? type_alias : type_name;
  std::string header = std::string("ply\nformat ") +
                       (big_endian ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\nelement vertex 4\n";
  for (const char* axis : {"x", "y", "z"}) {
    header += std::string("property ") + name(coord_type) + " " + axis + "\n";
  }
  header += std::string("element face 4\nproperty list ") + name(count_type) + " " +
            name(index_type) + " vertex_indices\nend_header\n";
  Bytes out = text_bytes(header);
  for (const Vec3f& p : kTetraPositions) {
    for (float c : p)
      put(&out, coord_type, c, big_endian);
  }
  for (const Triangle& t : kTetraTriangles) {
    put(&out, count_type, 3, big_endian);
    for (uint32_t v : t)
      put(&out, index_type, v, big_endian);
  }
  return out;
}

// ------------------------------------------------------------------- features

TEST(PlyReader, AsciiTetrahedron) {
  ImportReport report;
  Result<TriangleMesh> mesh = parse(kTetraAscii, &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().positions, kTetraPositions);
  EXPECT_EQ(mesh.value().triangles, kTetraTriangles);
  EXPECT_EQ(report.format, "ply-ascii");
  EXPECT_EQ(report.file_faces, 4u);
  EXPECT_TRUE(report.notes.empty());
}

TEST(PlyReader, CrLfLinesAndWrappedValues) {
  std::string text = kTetraAscii;
  std::string crlf;
  for (char c : text)
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  Result<TriangleMesh> a = parse(crlf);
  ASSERT_TRUE(a.is_ok()) << a.status().message();
  EXPECT_EQ(a.value().triangles, kTetraTriangles);
  // Values are a token stream: one vertex spread over two lines still reads.
  std::string wrapped = text;
  wrapped.replace(wrapped.find("1 0 0\n"), 6, "1\n0 0\n");
  Result<TriangleMesh> b = parse(wrapped);
  ASSERT_TRUE(b.is_ok()) << b.status().message();
  EXPECT_EQ(b.value().positions, kTetraPositions);
}

TEST(PlyReader, EveryScalarTypeInBothByteOrders) {
  for (bool big_endian : {false, true}) {
    for (int coord = 0; coord < 8; ++coord) {
      for (int index = 0; index < 6; ++index) {
        for (int count : {0, 1, 3, 5}) {
          for (bool aliases : {false, true}) {
            SCOPED_TRACE(std::string(type_name(coord)) + " coords, " + type_name(count) + " " +
                         type_name(index) + " lists, " + (big_endian ? "BE" : "LE") +
                         (aliases ? ", alias names" : ""));
            ImportReport report;
            Result<TriangleMesh> mesh =
                parse(binary_tetra(coord, count, index, big_endian, aliases), &report);
            ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
            EXPECT_EQ(mesh.value().positions, kTetraPositions);
            EXPECT_EQ(mesh.value().triangles, kTetraTriangles);
            EXPECT_EQ(report.format, big_endian ? "ply-binary-be" : "ply-binary-le");
            EXPECT_TRUE(report.notes.empty());
          }
        }
      }
    }
  }
}

TEST(PlyReader, AsciiScalarTypesAndRanges) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty int8 a\nproperty uint8 b\nproperty int16 c\n"
      "property uint16 d\nproperty int32 e\nproperty uint32 f\nproperty float64 g\n"
      "element face 1\nproperty list uint8 uint32 vertex_indices\nend_header\n";
  const std::string faces = "3 0 1 2\n";
  std::string extremes =
      "0 0 0 -128 255 -32768 65535 -2147483648 4294967295 1e300\n"
      "1 0 0 127 0 32767 0 2147483647 0 -1e-300\n"
      "+0 1 0 0 0 0 0 0 0 0\n";
  Result<TriangleMesh> ok = parse(head + extremes + faces);
  ASSERT_TRUE(ok.is_ok()) << ok.status().message();
  EXPECT_EQ(ok.value().positions[2], (Vec3f{0, 1, 0}));
  // One past each end of the range of each integer type.
  const char* overflows[] = {"-129", "256", "-32769", "65536", "-2147483649", "4294967296"};
  for (int column = 0; column < 6; ++column) {
    std::string values[6] = {"0", "0", "0", "0", "0", "0"};
    values[column] = overflows[column];
    std::string line = "0 0 0";
    for (const std::string& v : values)
      line += " " + v;
    line += " 0\n";
    SCOPED_TRACE(line);
    expect_rejected(parse(head + line + extremes.substr(extremes.find('\n') + 1) + faces),
                    "does not fit type");
  }
  expect_rejected(
      parse(head + "0 0 0 0 0 0 0 0 0 1.5x\n" + extremes.substr(extremes.find('\n') + 1) + faces),
      "line 17: expected a number, found '1.5x'");
  expect_rejected(
      parse(head + "0 0 0 0.5 0 0 0 0 0 0\n" + extremes.substr(extremes.find('\n') + 1) + faces),
      "expected an integer, found '0.5'");
}

TEST(PlyReader, NormalsAndTextureCoordinatesAreRead) {
  const char* pairs[][2] = {
      {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& pair : pairs) {
    SCOPED_TRACE(pair[0]);
    std::string text = std::string(
                           "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\n"
                           "property double y\nproperty double z\nproperty float nx\n"
                           "property float ny\nproperty float nz\nproperty float ") +
                       pair[0] + "\nproperty float " + pair[1] +
                       "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                       "0 0 0 0 0 1 0.25 0.5\n1 0 0 0 0 1 1 0\n0 1 0 0 0 -1 0 1\n3 0 1 2\n";
    ImportReport report;
    Result<TriangleMesh> result = parse(text, &report);
    ASSERT_TRUE(result.is_ok()) << result.status().message();
    const TriangleMesh& mesh = result.value();
    EXPECT_EQ(mesh.normals.binding, AttributeBinding::kPerVertex);
    EXPECT_EQ(mesh.normals.components, 3u);
    EXPECT_EQ(mesh.normals.values, (std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, -1}));
    EXPECT_EQ(mesh.texcoords.binding, AttributeBinding::kPerVertex);
    EXPECT_EQ(mesh.texcoords.components, 2u);
    EXPECT_EQ(mesh.texcoords.values, (std::vector<float>{0.25f, 0.5f, 1, 0, 0, 1}));
    EXPECT_TRUE(report.notes.empty());
  }
}

TEST(PlyReader, BinaryDoubleAttributesAndPartialNormalsNoted) {
  Bytes bytes = text_bytes(
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\n"
      "property double y\nproperty double z\nproperty double nx\nproperty double ny\n"
      "property float u\nproperty float v\n"
      "element face 1\nproperty list uchar uint vertex_indices\nend_header\n");
  const double values[3][7] = {
      {0, 0, 0, 1, 0, 0.5, 0.25}, {1, 0, 0, 0, 1, 1, 1}, {0, 1, 0, 1, 1, 0, 0}};
  for (const auto& row : values) {
    for (int k = 0; k < 7; ++k)
      put(&bytes, k < 5 ? 7 : 6, row[k], false);
  }
  put(&bytes, 1, 3, false);
  for (int v = 0; v < 3; ++v)
    put(&bytes, 5, v, false);
  ImportReport report;
  Result<TriangleMesh> result = parse(bytes, &report);
  ASSERT_TRUE(result.is_ok()) << result.status().message();
  EXPECT_FALSE(result.value().normals.present());
  EXPECT_EQ(result.value().texcoords.values, (std::vector<float>{0.5f, 0.25f, 1, 1, 0, 0}));
  EXPECT_TRUE(has_note(report, "ignored vertex property 'nx'"));
  EXPECT_TRUE(has_note(report, "ignored vertex property 'ny'"));
}

TEST(PlyReader, UnknownElementsAreSkippedInBothEncodings) {
  // An 'edge' element with a list and scalars between vertices and faces, a
  // 'material' element with no properties, and extra face properties.
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement edge 2\nproperty int vertex1\nproperty list uchar float w\n"
      "property uchar flag\nelement material 1000000000000\n"
      "element face 4\nproperty uchar red\nproperty list uchar int vertex_indices\n"
      "property list int short extra\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "0 3 1.5 2.5 3.5 7\n1 0 9\n"
      "5 3 0 2 1 0\n5 3 0 1 3 2 1 2\n5 3 0 3 2 1 -7\n5 3 1 2 3 0\n";
  ImportReport report;
  Result<TriangleMesh> a = parse(ascii, &report);
  ASSERT_TRUE(a.is_ok()) << a.status().message();
  EXPECT_EQ(a.value().positions, kTetraPositions);
  EXPECT_EQ(a.value().triangles, kTetraTriangles);
  EXPECT_TRUE(has_note(report, "skipped element 'edge' (2 items)"));
  EXPECT_TRUE(has_note(report, "skipped element 'material' (1000000000000 items)"));
  EXPECT_TRUE(has_note(report, "ignored face property 'red'"));
  EXPECT_TRUE(has_note(report, "ignored face list property 'extra'"));

  for (bool big_endian : {false, true}) {
    SCOPED_TRACE(big_endian ? "BE" : "LE");
    Bytes bytes = text_bytes(std::string("ply\nformat ") +
                             (big_endian ? "binary_big_endian" : "binary_little_endian") +
                             " 1.0\nelement edge 2\nproperty int vertex1\n"
                             "property list uchar float w\nproperty uchar flag\n"
                             "element vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement material 1000000000000\n"
                             "element face 4\nproperty uchar red\n"
                             "property list uchar int vertex_indices\n"
                             "property list int short extra\nend_header\n");
    put(&bytes, 4, 0, big_endian);
    put(&bytes, 1, 3, big_endian);
    for (float w : {1.5f, 2.5f, 3.5f})
      put(&bytes, 6, w, big_endian);
    put(&bytes, 1, 7, big_endian);
    put(&bytes, 4, 1, big_endian);
    put(&bytes, 1, 0, big_endian);
    put(&bytes, 1, 9, big_endian);
    for (const Vec3f& p : kTetraPositions) {
      for (float c : p)
        put(&bytes, 6, c, big_endian);
    }
    for (size_t f = 0; f < kTetraTriangles.size(); ++f) {
      put(&bytes, 1, 5, big_endian);
      put(&bytes, 1, 3, big_endian);
      for (uint32_t v : kTetraTriangles[f])
        put(&bytes, 4, v, big_endian);
      put(&bytes, 4, static_cast<double>(f), big_endian);
      for (size_t k = 0; k < f; ++k)
        put(&bytes, 2, -1, big_endian);
    }
    Result<TriangleMesh> b = parse(bytes);
    ASSERT_TRUE(b.is_ok()) << b.status().message();
    EXPECT_EQ(b.value().positions, kTetraPositions);
    EXPECT_EQ(b.value().triangles, kTetraTriangles);
  }
}

TEST(PlyReader, FacesBeforeVerticesAndPolygonsKeepFaceOrder) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement face 3\nproperty list uchar int vertex_index\n"
      "element vertex 6\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
      "3 0 1 4\n"
      "4 0 1 2 3\n"  // unit square, convex: fanned from corner 0
      "3 1 5 2\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 -1 0\n2 0.5 0\n";
  ImportReport report;
  Result<TriangleMesh> mesh = parse(text, &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  const std::vector<Triangle> expected = {{0, 1, 4}, {0, 1, 2}, {0, 2, 3}, {1, 5, 2}};
  EXPECT_EQ(mesh.value().triangles, expected);
  EXPECT_EQ(report.file_faces, 3u);
  EXPECT_EQ(report.polygons_triangulated, 1u);
}

TEST(PlyReader, ConcavePolygonIsEarClipped) {
  // An L-shaped hexagon listed from corner 4: a fan from there would leave
  // the polygon (triangle 4 2 3 is clockwise).
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n6 4 5 0 1 2 3\n";
  Result<TriangleMesh> result = parse(text);
  ASSERT_TRUE(result.is_ok()) << result.status().message();
  const TriangleMesh& mesh = result.value();
  ASSERT_EQ(mesh.triangle_count(), 4u);
  double area = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3f& a = mesh.positions[t[0]];
    const Vec3f& b = mesh.positions[t[1]];
    const Vec3f& c = mesh.positions[t[2]];
    double z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    EXPECT_GT(z, 0.0);  // every triangle keeps the polygon's counter-clockwise winding
    area += z / 2;
  }
  EXPECT_DOUBLE_EQ(area, 3.0);
}

TEST(PlyReader, TriangleStripsRestartAndAlternateWinding) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
      "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 2 0\n5 0 0\n6 0 0\n5 1 0\n";
  ImportReport report;
  // Strip 0 1 2 3 4, restart, strip 5 6 7 5, then a repeated 5 (a join).
  Result<TriangleMesh> mesh = parse(head + "11 0 1 2 3 4 -1 5 6 7 5 5\n", &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  const std::vector<Triangle> expected = {{0, 1, 2}, {2, 1, 3}, {2, 3, 4}, {5, 6, 7}, {7, 6, 5}};
  EXPECT_EQ(mesh.value().triangles, expected);
  EXPECT_EQ(report.file_faces, 5u);
  EXPECT_TRUE(has_note(report, "dropped 1 strip triangles with a repeated index"));

  // Binary big-endian strips with the same content.
  Bytes bytes = text_bytes(
      "ply\nformat binary_big_endian 1.0\nelement vertex 8\nproperty float x\n"
      "property float y\nproperty float z\nelement tristrips 1\n"
      "property list int int vertex_indices\nend_header\n");
  const float coords[8][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 2}, {5, 0}, {6, 0}, {5, 1}};
  for (const auto& c : coords) {
    put(&bytes, 6, c[0], true);
    put(&bytes, 6, c[1], true);
    put(&bytes, 6, 0, true);
  }
  const int strip[] = {0, 1, 2, 3, 4, -1, 5, 6, 7, 5, 5};
  put(&bytes, 4, 11, true);
  for (int v : strip)
    put(&bytes, 4, v, true);
  Result<TriangleMesh> binary = parse(bytes);
  ASSERT_TRUE(binary.is_ok()) << binary.status().message();
  EXPECT_EQ(binary.value().triangles, expected);

  expect_rejected(parse(head + "4 0 1 2 -2\n"), "vertex index -2 out of range (8 vertices)");
  expect_rejected(parse(head + "3 0 1 8\n"), "vertex index 8 out of range (8 vertices)");
}

// -------------------------------------------------------------------- failures

std::string tetra_with(const std::string& from, const std::string& to) {
  return testing_util::replace_once(kTetraAscii, from, to);
}

TEST(PlyReaderErrors, HeaderProblemsAreNamed) {
  expect_rejected(parse(tetra_with("ply\n", "PLY\n")), "bad magic");
  expect_rejected(parse(tetra_with("format ascii 1.0\n", "")), "no 'format' line");
  expect_rejected(parse(tetra_with("ascii 1.0", "utf8 1.0")), "line 2: unknown format 'utf8'");
  Result<TriangleMesh> version = parse(tetra_with("ascii 1.0", "ascii 2.0"));
  ASSERT_FALSE(version.is_ok());
  EXPECT_EQ(version.status().kind(), ErrorKind::kUnsupported);
  expect_rejected(parse(tetra_with("comment a tetrahedron\n", "property float w\n")),
                  "line 3: 'property' before any 'element'");
  expect_rejected(parse(tetra_with("property float y", "property float x")),
                  "property 'x' appears twice in element 'vertex'");
  expect_rejected(parse(tetra_with("element face 4", "element vertex 4")),
                  "element 'vertex' is declared twice");
  expect_rejected(parse(tetra_with("property float z", "property quad z")),
                  "unknown property type 'quad'");
  expect_rejected(parse(tetra_with("list uchar int", "list float int")),
                  "list length type 'float' is not an integer type");
  expect_rejected(parse(tetra_with("element vertex 4", "element vertex -4")),
                  "count '-4' is not a non-negative integer");
  expect_rejected(parse(tetra_with("element vertex 4", "element vertex 99999999999999999999")),
                  "below 2^64");
  expect_rejected(parse(tetra_with("comment a tetrahedron", "bogus words")),
                  "line 3: unknown header keyword 'bogus'");
  expect_rejected(parse(tetra_with("end_header\n", "end_header now\n")), "text after 'end_header'");
}

TEST(PlyReaderErrors, PlanProblemsAreNamed) {
  expect_rejected(parse(tetra_with("property float z\n", "")), "no 'z' property");
  expect_rejected(parse(tetra_with("property float z", "property list uchar float z")),
                  "vertex property 'z' is a list");
  expect_rejected(parse(tetra_with("vertex_indices", "corners")),
                  "element 'face' has no 'vertex_indices' list");
  expect_rejected(parse(tetra_with("list uchar int vertex_indices", "int vertex_indices")),
                  "is a single value, not a list");
  expect_rejected(parse(tetra_with("list uchar int vertex_indices",
                                   "list uchar float "
                                   "vertex_indices")),
                  "has float entries; vertex indices must be integers");
  expect_rejected(parse("ply\nformat ascii 1.0\nelement face 0\n"
                        "property list uchar int vertex_indices\nend_header\n"),
                  "no 'vertex' element");
  expect_rejected(parse("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                        "property float y\nproperty float z\nend_header\n1 2 3\n"),
                  "point cloud, not a mesh");
}

TEST(PlyReaderErrors, BodyProblemsAreNamed) {
  expect_rejected(parse(tetra_with("3 1 2 3\n", "3 1 2 4\n")),
                  "line 19: face 4 of 4: vertex index 4 out of range (4 vertices)");
  expect_rejected(parse(tetra_with("3 1 2 3\n", "3 1 -2 3\n")), "vertex index -2 out of range");
  expect_rejected(parse(tetra_with("3 1 2 3\n", "2 1 2 3\n")),
                  "face 4 of 4 has 2 corners; a face needs at least 3");
  expect_rejected(parse(tetra_with("0 0 1\n", "0 zero 1\n")),
                  "line 15: expected a number, found 'zero'");
  expect_rejected(parse(tetra_with("0 0 1\n", "0 nan 1\n")), "vertex 4 of 4 has a non-finite y");
  // Long numbers get the file past the size bound, so the cut is found while reading.
  const std::string padded =
      tetra_with("0 0 1\n", "0.000000000000000 0.000000000000000 1.000000000000000\n");
  expect_rejected(parse(padded.substr(0, padded.size() - 2)),
                  "line 19: the file ends inside face 4 of 4, property 'vertex_indices'");
  expect_rejected(parse(tetra_with("3 1 2 3\n", "200 1 2 3\n")), "list length 200 overruns");
  expect_rejected(parse(tetra_with("element face 4", "element face 400")),
                  "element 'face' declares 400 items");

  ImportReport report;
  Result<TriangleMesh> trailing = parse(std::string(kTetraAscii) + "\n  extra words\n", &report);
  ASSERT_TRUE(trailing.is_ok()) << trailing.status().message();
  EXPECT_TRUE(has_note(report, "ignored 12 bytes after the last element"));

  Bytes binary = binary_tetra(6, 1, 4, false);
  binary[binary.size() - 4] = 9;  // low byte of the last face's last index
  expect_rejected(parse(binary), "face 4 of 4: vertex index 9 out of range (4 vertices)");
  Bytes negative_length = binary_tetra(6, 0, 4, false);
  negative_length[negative_length.size() - 13] = 0xff;  // the last face's char length: -1
  expect_rejected(parse(negative_length), "negative list length -1");
}

TEST(PlyReaderErrors, EveryTruncationOfABinaryFileIsRejected) {
  for (bool big_endian : {false, true}) {
    Bytes full = binary_tetra(7, 1, 5, big_endian);
    ASSERT_TRUE(parse(full).is_ok());
    for (size_t length = 0; length < full.size(); ++length) {
      Bytes cut(full.begin(), full.begin() + static_cast<ptrdiff_t>(length));
      Result<TriangleMesh> result = parse(cut);
      EXPECT_FALSE(result.is_ok()) << "length " << length;
    }
  }
}

TEST(PlyReaderErrors, EveryTruncationOfAnAsciiFileFailsCleanlyOrReadsAPrefix) {
  const std::string full = kTetraAscii;
  for (size_t length = 0; length < full.size(); ++length) {
    Result<TriangleMesh> result = parse(full.substr(0, length));
    if (result.is_ok()) {
      // Only a cut inside the very last number can still parse.
      EXPECT_GE(length, full.size() - 2) << "length " << length;
      expect_valid_indices(result.value());
    }
  }
}

TEST(PlyReaderErrors, ByteFlipsNeverCrash) {
  Bytes full = binary_tetra(6, 1, 4, false);
  for (size_t i = 0; i < full.size(); ++i) {
    for (uint8_t value : {uint8_t{0x00}, uint8_t{0xff}, uint8_t{0x80}, uint8_t{'9'}}) {
      Bytes copy = full;
      copy[i] = value;
      Result<TriangleMesh> result = parse(copy);
      if (result.is_ok()) expect_valid_indices(result.value());
    }
  }
}

}  // namespace
}  // namespace lodbake
