// Every mesh writer's file read back by lodbake's readers is the mesh that
// was written: the same vertex count, the same triangles, positions bit for
// bit. Over a plain mesh, a mesh with per-corner attributes and meshes that
// repair split apart (non-manifold vertices and edges become several
// vertices at one position), which the glTF reader must not weld together
// again. The OBJ, PLY and OFF readers keep vertices as written; PLY stores
// per-corner attributes by splitting vertices first (corner_split.h), so
// its file reads back as that split mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "lib/ingest/load_mesh.h"
#include "lib/meshio/corner_split.h"
#include "lib/meshio/mesh_import.h"
#include "lib/meshio/mesh_writers.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::env_or_fail;

struct Source {
  std::string path;  // under LODBAKE_SHARED_DATA, or "src:" + a path in the source tree
  bool repair;
};

std::string full_path(const std::string& path) {
  if (path.rfind("src:", 0) == 0) return env_or_fail("LODBAKE_SOURCE_DIR") + "/" + path.substr(4);
  return env_or_fail("LODBAKE_SHARED_DATA") + "/" + path;
}

// The mesh as a tool stores it: loaded, repaired when asked, unreferenced
// vertices dropped, accepted by the default policy.
TriangleMesh load(const Source& source) {
  LoadOptions options;
  options.repair = source.repair;
  options.drop_unreferenced = true;
  LoadedMesh loaded;
  const Status status = load_mesh(full_path(source.path), options, &loaded);
  EXPECT_TRUE(status.is_ok()) << source.path << ": " << status.message();
  return loaded.mesh;
}

const std::vector<Source>& sources() {
  static const std::vector<Source> list = {
      {"meshes/cgal_elephant.off", false},
      {"src:tests/golden/inputs/cube_attributes.obj", false},  // per-corner attributes
      {"bad/hw_nonmanifold_vertex_bowtie.off", true},
      {"bad/hw_nonmanifold_vertex_two_cones.off", true},
      {"bad/hw_nonmanifold_edge_3tris.off", true},
      {"bad/draco_non_manifold_wrap.obj", true},
  };
  return list;
}

// Writes `mesh` as `name`'s format, reads the bytes back through the same
// import path as every tool (format detection included) and compares with
// `expected`; then checks that a tool would take the file (no
// non-manifold edge appeared that `mesh` did not have).
void expect_round_trip(const std::string& name, const TriangleMesh& mesh,
                       const TriangleMesh& expected) {
  SCOPED_TRACE(name);
  Result<Bytes> bytes = write_mesh_for_path(name, mesh);
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  ImportReport report;
  Result<TriangleMesh> back = import_mesh(name, bytes.value(), &report);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(back.value().vertex_count(), expected.vertex_count());
  EXPECT_EQ(back.value().triangles, expected.triangles);
  EXPECT_EQ(back.value().positions, expected.positions);  // float ==: bit-exact but ±0
  for (size_t v = 0; v < expected.positions.size() && v < back.value().positions.size(); ++v) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(std::signbit(back.value().positions[v][k]), std::signbit(expected.positions[v][k]))
          << "vertex " << v;
    }
  }
  // The OBJ, PLY and OFF readers keep every vertex as written; GLB merges
  // the glTF vertices its writer made per distinct corner back.
  if (name.substr(name.size() - 4) != ".glb") {
    EXPECT_EQ(report.welded_vertices, 0u);
  }
  LoadedMesh reloaded;
  const Status accepted = load_mesh_bytes(name, bytes.value(), LoadOptions(), &reloaded);
  EXPECT_TRUE(accepted.is_ok()) << accepted.message();
}

bool has_per_corner(const TriangleMesh& mesh) {
  return mesh.normals.binding == AttributeBinding::kPerCorner ||
         mesh.texcoords.binding == AttributeBinding::kPerCorner;
}

TEST(WriterRoundTrip, Obj) {
  for (const Source& source : sources()) {
    SCOPED_TRACE(source.path);
    const TriangleMesh mesh = load(source);
    expect_round_trip("mesh.obj", mesh, mesh);
  }
}

TEST(WriterRoundTrip, Off) {
  for (const Source& source : sources()) {
    SCOPED_TRACE(source.path);
    const TriangleMesh mesh = load(source);
    expect_round_trip("mesh.off", mesh, mesh);
  }
}

TEST(WriterRoundTrip, Ply) {
  for (const Source& source : sources()) {
    SCOPED_TRACE(source.path);
    const TriangleMesh mesh = load(source);
    const TriangleMesh split = split_corner_attributes(mesh);
    if (has_per_corner(mesh)) {
      EXPECT_GT(split.vertex_count(), mesh.vertex_count());
    }
    expect_round_trip("mesh.ply", mesh, split);
  }
}

TEST(WriterRoundTrip, Glb) {
  for (const Source& source : sources()) {
    SCOPED_TRACE(source.path);
    const TriangleMesh mesh = load(source);
    expect_round_trip("mesh.glb", mesh, mesh);
  }
}

TEST(WriterRoundTrip, RepairedMeshesHaveVerticesAtOnePosition) {
  // What makes the repaired sources a test of welding: repair left two or
  // more vertices at one position.
  for (const Source& source : sources()) {
    if (!source.repair) continue;
    SCOPED_TRACE(source.path);
    const TriangleMesh mesh = load(source);
    size_t coincident = 0;
    for (size_t a = 0; a < mesh.positions.size(); ++a) {
      for (size_t b = a + 1; b < mesh.positions.size(); ++b)
        coincident += mesh.positions[a] == mesh.positions[b] ? 1 : 0;
    }
    EXPECT_GT(coincident, 0u);
  }
}

}  // namespace
}  // namespace lodbake
