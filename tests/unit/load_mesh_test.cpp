// The default repair of the import path (lib/ingest): with the tools'
// two-manifold policy, every kind of defect check_mesh() finds and
// repair_mesh() fixes is repaired without being asked, positions stay
// exactly the file's, the report counts what changed, the same bytes give
// the same mesh, the result is taken by the algorithms that need a
// 2-manifold, a clean mesh is left exactly as read, and --strict refuses
// instead.
#include "lib/ingest/load_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "lib/fanmerge/fan_build.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/meshio/mesh_writers.h"
#include "lib/simplify/simplify.h"
#include "lib/strips/stripify.h"
#include "tests/unit/test_meshes.h"

namespace lodbake {
namespace {

using namespace test_meshes;  // NOLINT: test shapes only

// `mesh` as the bytes of an OFF file, the way a tool reads it.
Bytes off_bytes(const TriangleMesh& mesh) {
  Result<Bytes> bytes = write_off(mesh);
  EXPECT_TRUE(bytes.is_ok()) << bytes.status().message();
  return bytes.is_ok() ? bytes.value() : Bytes();
}

Status load(const TriangleMesh& mesh, const LoadOptions& options, LoadedMesh* loaded) {
  return load_mesh_bytes("input.off", off_bytes(mesh), options, loaded);
}

// The tools' options: the default policy and unreferenced vertices dropped.
LoadOptions tool_options() {
  LoadOptions options;
  options.drop_unreferenced = true;
  return options;
}

// Every output position is an input position, bit for bit, and every input
// position that a triangle used is still there.
void expect_positions_kept(const TriangleMesh& input, const TriangleMesh& output) {
  const std::set<Vec3f> before(input.positions.begin(), input.positions.end());
  for (const Vec3f& p : output.positions)
    EXPECT_EQ(before.count(p), 1u) << p[0] << " " << p[1] << " " << p[2];
  std::set<Vec3f> used;
  for (const Triangle& t : output.triangles) {
    for (uint32_t v : t)
      used.insert(output.positions[v]);
  }
  EXPECT_FALSE(used.empty());
}

// The repaired mesh goes through every algorithm the tools run on it.
void expect_taken_by_algorithms(const TriangleMesh& mesh) {
  SimplifyOptions simplify_options;
  simplify_options.record_pm = true;
  Result<SimplifyResult> simplified = simplify(mesh, simplify_options);
  EXPECT_TRUE(simplified.is_ok()) << simplified.status().message();
  Result<BalancedHierarchy> hierarchy = build_balanced_hierarchy(mesh, BalancedBuildOptions());
  EXPECT_TRUE(hierarchy.is_ok()) << hierarchy.status().message();
  Result<FanBuildResult> fans = build_fan_hierarchy(mesh, FanBuildOptions());
  EXPECT_TRUE(fans.is_ok()) << fans.status().message();
  Result<TriangleStrips> strips = stripify(mesh);
  EXPECT_TRUE(strips.is_ok()) << strips.status().message();
}

struct Defect {
  const char* name;
  TriangleMesh mesh;
  uint64_t RepairReport::*count;  // the count that must be non-zero
  uint64_t expected;
  const char* strict_message;  // the start of --strict's refusal
};

std::vector<Defect> defects() {
  return {
      {"bowtie", bowtie(), &RepairReport::split_non_manifold_vertices, 1,
       "--strict: 1 non-manifold vertex (faces around it form separate fans): vertex 0"},
      {"two cones", two_cones(), &RepairReport::split_non_manifold_vertices, 1,
       "--strict: 1 non-manifold vertex"},
      {"three on an edge", three_on_an_edge(), &RepairReport::split_non_manifold_edges, 1,
       "--strict: 1 non-manifold edge (more than two faces): edge 0-1"},
      {"four on an edge", four_on_an_edge(), &RepairReport::split_non_manifold_edges, 1,
       "--strict: 1 non-manifold edge (more than two faces): edge 0-1"},
      {"duplicates", tetrahedron_with_duplicates(), &RepairReport::removed_duplicate_triangles, 2,
       "--strict: 3 non-manifold edges"},
      {"one flipped", tetrahedron_one_flipped(), &RepairReport::flipped_triangles, 1,
       "--strict: 3 edges with inconsistent orientation"},
      {"degenerates", square_with_degenerates(), &RepairReport::removed_degenerate_triangles, 4,
       "--strict: 2 degenerate triangles with a repeated vertex index"},
  };
}

TEST(LoadMeshDefaultRepair, EveryKindOfDefectIsRepairedWithoutBeingAsked) {
  for (const Defect& d : defects()) {
    SCOPED_TRACE(d.name);
    LoadedMesh loaded;
    Status status = load(d.mesh, tool_options(), &loaded);
    ASSERT_TRUE(status.is_ok()) << status.message();
    ASSERT_TRUE(loaded.repair.has_value());
    EXPECT_TRUE(loaded.repaired_by_default);
    EXPECT_TRUE(loaded.check.has_problems());
    EXPECT_EQ((*loaded.repair).*d.count, d.expected);
    EXPECT_TRUE(loaded.repair->changed());
    EXPECT_FALSE(loaded.repair->actions().empty());
    ASSERT_TRUE(loaded.check_after_repair.has_value());
    EXPECT_FALSE(loaded.check_after_repair->has_problems())
        << loaded.check_after_repair->problems().front();
    EXPECT_TRUE(loaded.check_after_repair->manifold());
    expect_positions_kept(d.mesh, loaded.mesh);
    expect_taken_by_algorithms(loaded.mesh);
  }
}

TEST(LoadMeshDefaultRepair, SplitsCopyPositionsAndCountTheCopies) {
  LoadedMesh loaded;
  ASSERT_TRUE(load(two_cones(), tool_options(), &loaded).is_ok());
  const TriangleMesh input = two_cones();
  EXPECT_EQ(loaded.repair->added_vertices, 1u);
  EXPECT_EQ(loaded.mesh.positions.size(), input.positions.size() + 1);
  // Input vertices keep their index; the copy of the apex comes last.
  for (size_t v = 0; v < input.positions.size(); ++v)
    EXPECT_EQ(loaded.mesh.positions[v], input.positions[v]);
  EXPECT_EQ(loaded.mesh.positions.back(), input.positions[0]);
  EXPECT_EQ(loaded.mesh.triangles.size(), input.triangles.size());
  EXPECT_EQ(loaded.check_after_repair->components, 2u);
  EXPECT_TRUE(loaded.check_after_repair->closed());
}

TEST(LoadMeshDefaultRepair, SameBytesGiveTheSameMesh) {
  for (const Defect& d : defects()) {
    SCOPED_TRACE(d.name);
    LoadedMesh a, b;
    ASSERT_TRUE(load(d.mesh, tool_options(), &a).is_ok());
    ASSERT_TRUE(load(d.mesh, tool_options(), &b).is_ok());
    EXPECT_EQ(a.mesh, b.mesh);
    EXPECT_EQ(a.repair->actions(), b.repair->actions());
  }
}

TEST(LoadMeshDefaultRepair, ItIsTheSameRepairAsRequested) {
  // The default repair is repair_mesh(): asking for it changes nothing but
  // who asked.
  for (const Defect& d : defects()) {
    SCOPED_TRACE(d.name);
    LoadedMesh by_default, asked;
    LoadOptions repair = tool_options();
    repair.repair = true;
    ASSERT_TRUE(load(d.mesh, tool_options(), &by_default).is_ok());
    ASSERT_TRUE(load(d.mesh, repair, &asked).is_ok());
    EXPECT_FALSE(asked.repaired_by_default);
    EXPECT_EQ(by_default.mesh, asked.mesh);
  }
}

TEST(LoadMeshDefaultRepair, CleanMeshIsLeftExactlyAsRead) {
  for (const TriangleMesh& mesh : {tetrahedron(), open_square(), torus(8, 6)}) {
    LoadedMesh plain, strict, linted;
    LoadOptions strict_options = tool_options();
    strict_options.strict = true;
    LoadOptions lint_options;
    lint_options.policy = std::nullopt;
    ASSERT_TRUE(load(mesh, tool_options(), &plain).is_ok());
    ASSERT_TRUE(load(mesh, strict_options, &strict).is_ok());
    ASSERT_TRUE(load(mesh, lint_options, &linted).is_ok());
    EXPECT_FALSE(plain.repair.has_value());
    EXPECT_FALSE(plain.repaired_by_default);
    EXPECT_EQ(plain.mesh, mesh);
    EXPECT_EQ(strict.mesh, mesh);
    EXPECT_EQ(linted.mesh, mesh);
  }
}

TEST(LoadMeshDefaultRepair, UnreferencedVerticesAloneAreDroppedNotRepaired) {
  LoadedMesh loaded;
  LoadOptions strict = tool_options();
  strict.strict = true;  // dropping them is no repair: --strict takes the mesh
  ASSERT_TRUE(load(tetrahedron_with_unreferenced(), strict, &loaded).is_ok());
  EXPECT_FALSE(loaded.repair.has_value());
  EXPECT_EQ(loaded.dropped_unreferenced, 3u);
  EXPECT_EQ(loaded.mesh.positions.size(), 4u);
}

TEST(LoadMeshDefaultRepair, StrictRefusesNamingTheFirstProblem) {
  for (const Defect& d : defects()) {
    SCOPED_TRACE(d.name);
    LoadedMesh loaded;
    LoadOptions strict = tool_options();
    strict.strict = true;
    Status status = load(d.mesh, strict, &loaded);
    EXPECT_EQ(status.kind(), ErrorKind::kInvalidInput);
    EXPECT_EQ(status.message().rfind(d.strict_message, 0), 0u) << status.message();
    EXPECT_EQ(status.message().find('\n'), std::string::npos);
    EXPECT_FALSE(loaded.repair.has_value());
  }
}

TEST(LoadMeshDefaultRepair, TheLinterTakesEveryMeshAsItIs) {
  for (const Defect& d : defects()) {
    SCOPED_TRACE(d.name);
    LoadedMesh loaded;
    LoadOptions lint;
    lint.policy = std::nullopt;
    ASSERT_TRUE(load(d.mesh, lint, &loaded).is_ok());
    EXPECT_FALSE(loaded.repair.has_value());
    EXPECT_TRUE(loaded.check.has_problems());
  }
}

TEST(LoadMeshDefaultRepair, NothingLeftIsOneError) {
  LoadedMesh loaded;
  Status status =
      load(make({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}), tool_options(), &loaded);
  EXPECT_EQ(status.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(status.message(), "no triangle is left after repair: removed 1 degenerate triangle");
  EXPECT_FALSE(loaded.repair.has_value());
}

TEST(LoadMeshDefaultRepair, PerCornerAttributesAreSplitOnSeamsWhenAsked) {
  // Two triangles sharing edge 1-2 whose corners at 1 and 2 disagree on
  // their texture coordinates: a seam along the shared edge.
  const char* obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 0.5 0\nvt 0.5 1\n"
      "f 1/1 2/2 3/3\nf 2/5 4/4 3/6\n";
  const Bytes bytes(obj, obj + std::string(obj).size());
  LoadedMesh kept, split;
  ASSERT_TRUE(load_mesh_bytes("seam.obj", bytes, tool_options(), &kept).is_ok());
  EXPECT_EQ(kept.mesh.texcoords.binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(kept.seam_vertices, 0u);
  LoadOptions options = tool_options();
  options.per_vertex_attributes = true;
  ASSERT_TRUE(load_mesh_bytes("seam.obj", bytes, options, &split).is_ok());
  EXPECT_EQ(split.mesh.texcoords.binding, AttributeBinding::kPerVertex);
  EXPECT_EQ(split.seam_vertices, 2u);
  EXPECT_EQ(split.mesh.positions.size(), 6u);
  expect_positions_kept(kept.mesh, split.mesh);
  SimplifyOptions record;
  record.record_pm = true;
  EXPECT_TRUE(simplify(split.mesh, record).is_ok());
}

}  // namespace
}  // namespace lodbake
