// write_ply -> parse_ply round trips: positions, triangles and per-vertex
// attributes come back bit-identical; per-corner attributes come back as the
// per-vertex split that split_corner_attributes() defines.
#include <gtest/gtest.h>

#include <string>

#include "lib/meshio/corner_split.h"
#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/mesh_writers.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::shared_file;

TriangleMesh load_obj(const std::string& relative) {
  Bytes bytes = shared_file(relative);
  Result<TriangleMesh> mesh = parse_obj(bytes.data(), bytes.size(), nullptr);
  EXPECT_TRUE(mesh.is_ok()) << relative << ": " << mesh.status().message();
  return mesh.is_ok() ? std::move(mesh).value() : TriangleMesh{};
}

TriangleMesh ply_round_trip(const TriangleMesh& mesh) {
  Result<Bytes> bytes = write_ply(mesh);
  EXPECT_TRUE(bytes.is_ok()) << bytes.status().message();
  if (!bytes.is_ok()) return {};
  ImportReport report;
  Result<TriangleMesh> back = parse_ply(bytes.value().data(), bytes.value().size(), &report);
  EXPECT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(report.format, "ply-binary-le");
  return back.is_ok() ? std::move(back).value() : TriangleMesh{};
}

TEST(PlyWriter, RoundTripWithoutAttributesIsExact) {
  TriangleMesh mesh = load_obj("meshes/npm_bunny.obj");
  EXPECT_TRUE(ply_round_trip(mesh) == mesh);
}

TEST(PlyWriter, RoundTripWithPerVertexNormalsIsExact) {
  TriangleMesh mesh = load_obj("meshes/c3d_suzanne.obj");
  ASSERT_EQ(mesh.normals.binding, AttributeBinding::kPerVertex);
  EXPECT_TRUE(ply_round_trip(mesh) == mesh);
}

TEST(PlyWriter, PerCornerAttributesComeBackSplit) {
  for (const char* file : {"meshes/c3d_beetle.obj", "meshes/c3d_spot.obj"}) {
    SCOPED_TRACE(file);
    TriangleMesh mesh = load_obj(file);
    TriangleMesh split = split_corner_attributes(mesh);
    EXPECT_GT(split.vertex_count(), mesh.vertex_count()) << "seams duplicate vertices";
    EXPECT_EQ(split.triangle_count(), mesh.triangle_count());
    EXPECT_TRUE(ply_round_trip(mesh) == split);
  }
}

}  // namespace
}  // namespace lodbake
