// write_obj, write_off, write_ply, split_corner_attributes and
// drops_attributes: exact round trips through the readers on real meshes
// (with per-vertex and per-corner attributes), byte layout, determinism and
// the refusal of inconsistent meshes.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "lib/meshio/corner_split.h"
#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/mesh_writers.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::shared_file;

TriangleMesh load(const std::string& relative) {
  Bytes bytes = shared_file(relative);
  const bool obj = relative.size() > 4 && relative.substr(relative.size() - 4) == ".obj";
  Result<TriangleMesh> mesh = obj ? parse_obj(bytes.data(), bytes.size(), nullptr)
                                  : parse_off(bytes.data(), bytes.size(), nullptr);
  EXPECT_TRUE(mesh.is_ok()) << relative << ": " << mesh.status().message();
  return mesh.is_ok() ? std::move(mesh).value() : TriangleMesh{};
}

std::string as_text(const Bytes& bytes) {
  return std::string(bytes.begin(), bytes.end());
}

// A quad split in two whose corners disagree on normals and texture
// coordinates along the shared diagonal, plus an unreferenced vertex 4.
TriangleMesh corner_mesh() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {9, 9, 9}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.normals.binding = AttributeBinding::kPerCorner;
  m.normals.components = 3;
  m.normals.values = {0, 0, 1, 0, 1, 0};
  m.normals.corners = {{0, 0, 0}, {1, 1, 1}};
  m.texcoords.binding = AttributeBinding::kPerCorner;
  m.texcoords.components = 2;
  m.texcoords.values = {0, 0, 1, 0, 1, 1, 0, 1};
  m.texcoords.corners = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(MeshWriters, ObjRoundTripIsExactOnRealMeshes) {
  for (const char* file : {"meshes/c3d_suzanne.obj", "meshes/c3d_beetle.obj", "meshes/c3d_spot.obj",
                           "meshes/cgal_mpi.off", "meshes/igl_decimated-knight.off"}) {
    SCOPED_TRACE(file);
    TriangleMesh mesh = load(file);
    Result<Bytes> bytes = write_obj(mesh);
    ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
    Result<TriangleMesh> back = parse_obj(bytes.value().data(), bytes.value().size(), nullptr);
    ASSERT_TRUE(back.is_ok()) << back.status().message();
    EXPECT_TRUE(back.value() == mesh) << "positions, triangles and attributes bit-identical";
    EXPECT_FALSE(drops_attributes("out.obj", mesh));
    Result<Bytes> again = write_obj(mesh);
    ASSERT_TRUE(again.is_ok());
    EXPECT_EQ(again.value(), bytes.value()) << "deterministic";
  }
}

TEST(MeshWriters, ObjKeepsPerCornerAttributes) {
  TriangleMesh mesh = corner_mesh();
  Result<Bytes> bytes = write_obj(mesh);
  ASSERT_TRUE(bytes.is_ok());
  const std::string text = as_text(bytes.value());
  EXPECT_NE(text.find("vn 0 1 0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("f 1/1/2 3/3/2 4/4/2\n"), std::string::npos) << text;
  Result<TriangleMesh> back = parse_obj(bytes.value().data(), bytes.value().size(), nullptr);
  ASSERT_TRUE(back.is_ok());
  EXPECT_TRUE(back.value() == mesh);
}

TEST(MeshWriters, FloatsRoundTripExactlyInText) {
  TriangleMesh mesh;
  const float awkward[] = {0.1f,        -0.0f,       1e-45f,
                           FLT_MIN,     FLT_MAX,     -FLT_MAX,
                           16777217.0f, 3.14159274f, std::nextafter(1.0f, 2.0f),
                           1e-7f,       123456.789f, -2.5e-38f};
  for (float f : awkward)
    mesh.positions.push_back({f, -f, f * 0.5f});
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}};
  Result<Bytes> obj = write_obj(mesh);
  Result<Bytes> off = write_off(mesh);
  ASSERT_TRUE(obj.is_ok() && off.is_ok());
  Result<TriangleMesh> from_obj = parse_obj(obj.value().data(), obj.value().size(), nullptr);
  Result<TriangleMesh> from_off = parse_off(off.value().data(), off.value().size(), nullptr);
  ASSERT_TRUE(from_obj.is_ok()) << from_obj.status().message();
  ASSERT_TRUE(from_off.is_ok()) << from_off.status().message();
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(std::memcmp(&from_obj.value().positions[i][k], &mesh.positions[i][k], 4), 0)
          << mesh.positions[i][k];
      EXPECT_EQ(std::memcmp(&from_off.value().positions[i][k], &mesh.positions[i][k], 4), 0);
    }
  }
}

TEST(MeshWriters, OffRoundTripKeepsPositionsTrianglesAndPerVertexAttributes) {
  for (const char* file :
       {"meshes/cgal_mpi.off", "meshes/npm_bunny.obj", "meshes/c3d_suzanne.obj"}) {
    SCOPED_TRACE(file);
    TriangleMesh mesh = load(file);
    Result<Bytes> bytes = write_off(mesh);
    ASSERT_TRUE(bytes.is_ok());
    Result<TriangleMesh> back = parse_off(bytes.value().data(), bytes.value().size(), nullptr);
    ASSERT_TRUE(back.is_ok()) << back.status().message();
    EXPECT_TRUE(back.value() == mesh);
    EXPECT_FALSE(drops_attributes("x.off", mesh));
  }
  // Suzanne's per-vertex normals make it an NOFF file.
  Result<Bytes> suzanne = write_off(load("meshes/c3d_suzanne.obj"));
  ASSERT_TRUE(suzanne.is_ok());
  EXPECT_EQ(as_text(suzanne.value()).substr(0, 19), "NOFF\n507 968 0\n-2.0");
}

TEST(MeshWriters, OffWritesStnoffAndLeavesOutPerCornerAttributes) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  mesh.normals = {AttributeBinding::kPerVertex, 3, {0, 0, 1, 0, 0, 1, 0, 0, 1}, {}};
  mesh.texcoords = {AttributeBinding::kPerVertex, 2, {0, 0, 1, 0, 0, 1}, {}};
  Result<Bytes> bytes = write_off(mesh);
  ASSERT_TRUE(bytes.is_ok());
  EXPECT_EQ(as_text(bytes.value()),
            "STNOFF\n3 1 0\n0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n0 1 0 0 0 1 0 1\n3 0 1 2\n");
  Result<TriangleMesh> back = parse_off(bytes.value().data(), bytes.value().size(), nullptr);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_TRUE(back.value() == mesh);

  TriangleMesh corners = corner_mesh();
  EXPECT_TRUE(drops_attributes("out.OFF", corners));
  EXPECT_FALSE(drops_attributes("out.ply", corners));
  EXPECT_FALSE(drops_attributes("out.obj", corners));
  Result<Bytes> plain = write_off(corners);
  ASSERT_TRUE(plain.is_ok());
  EXPECT_EQ(as_text(plain.value()).substr(0, 4), "OFF\n");
}

TEST(MeshWriters, CornerSplitDuplicatesOnlyDisagreeingVertices) {
  TriangleMesh split = split_corner_attributes(corner_mesh());
  // Vertices 0 and 2 are used with normal 0 by the first triangle and with
  // normal 1 by the second: each gets one duplicate, appended in order.
  ASSERT_EQ(split.positions.size(), 7u);
  EXPECT_EQ(split.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(split.triangles[1], (Triangle{5, 6, 3}));
  EXPECT_EQ(split.positions[5], (Vec3f{0, 0, 0}));
  EXPECT_EQ(split.positions[6], (Vec3f{1, 1, 0}));
  EXPECT_EQ(split.normals.binding, AttributeBinding::kPerVertex);
  EXPECT_EQ(split.normals.values,
            (std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0}));
  EXPECT_EQ(split.texcoords.values, (std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1, 0, 0, 0, 0, 1, 1}));
  EXPECT_EQ(split.positions[4], (Vec3f{9, 9, 9})) << "unreferenced vertex kept, zero attributes";
  // Every corner still sees the attribute values it had.
  const TriangleMesh original = corner_mesh();
  for (size_t t = 0; t < 2; ++t) {
    for (int k = 0; k < 3; ++k) {
      uint32_t v = split.triangles[t][k];
      uint32_t n = original.normals.corners[t][k];
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(split.normals.values[v * 3 + c], original.normals.values[n * 3 + c]);
      EXPECT_EQ(split.positions[v], original.positions[original.triangles[t][k]]);
    }
  }
  TriangleMesh plain;
  plain.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  plain.triangles = {{0, 1, 2}};
  EXPECT_TRUE(split_corner_attributes(plain) == plain);
}

uint32_t read_u32(const Bytes& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

float read_f32(const Bytes& b, size_t at) {
  float v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

TEST(MeshWriters, PlyLayoutIsBinaryLittleEndian) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5f}};
  mesh.triangles = {{0, 1, 2}};
  Result<Bytes> bytes = write_ply(mesh);
  ASSERT_TRUE(bytes.is_ok());
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment written by lodbake\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar uint vertex_indices\nend_header\n";
  const Bytes& b = bytes.value();
  ASSERT_EQ(b.size(), header.size() + 3 * 12 + 13);
  EXPECT_EQ(std::string(b.begin(), b.begin() + header.size()), header);
  EXPECT_EQ(read_f32(b, header.size() + 2 * 12 + 8), 0.5f);
  EXPECT_EQ(b[header.size() + 36], 3);
  EXPECT_EQ(read_u32(b, header.size() + 37 + 8), 2u);
}

TEST(MeshWriters, PlySplitsPerCornerAttributes) {
  Result<Bytes> bytes = write_ply(corner_mesh());
  ASSERT_TRUE(bytes.is_ok());
  const std::string text = as_text(bytes.value());
  EXPECT_NE(text.find("element vertex 7\n"), std::string::npos);
  EXPECT_NE(text.find("property float nx\nproperty float ny\nproperty float nz\n"
                      "property float s\nproperty float t\n"),
            std::string::npos);
  const size_t body = text.find("end_header\n") + 11;
  EXPECT_EQ(bytes.value().size(), body + 7 * 32 + 2 * 13);
  // Second vertex record: position (1,0,0), normal (0,0,1), texcoord (1,0).
  EXPECT_EQ(read_f32(bytes.value(), body + 32 + 0), 1.0f);
  EXPECT_EQ(read_f32(bytes.value(), body + 32 + 20), 1.0f);
  EXPECT_EQ(read_f32(bytes.value(), body + 32 + 24), 1.0f);
}

TEST(MeshWriters, InconsistentMeshesAreRefused) {
  TriangleMesh bad_index;
  bad_index.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  bad_index.triangles = {{0, 1, 3}};
  TriangleMesh bad_normals = corner_mesh();
  bad_normals.normals.corners[1][2] = 2;
  TriangleMesh short_values = corner_mesh();
  short_values.texcoords.binding = AttributeBinding::kPerVertex;
  short_values.texcoords.corners.clear();
  struct Case {
    const TriangleMesh* mesh;
    const char* message;
  } cases[] = {
      {&bad_index, "triangle 0 uses vertex 3 of 3"},
      {&bad_normals, "triangle 1 uses normals value 2 of 2"},
      {&short_values, "mesh has 5 vertices but 4 per-vertex texture coordinates"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    for (Result<Bytes> r : {write_obj(*c.mesh), write_off(*c.mesh), write_ply(*c.mesh)}) {
      ASSERT_FALSE(r.is_ok());
      EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
      EXPECT_EQ(r.status().message(), c.message);
    }
  }
}

}  // namespace
}  // namespace lodbake
