// Accessor values, primitive triangles, the welded topology of a scene mesh
// and the inspect summary, on hand-built scenes.
#include <gtest/gtest.h>

#include <cstring>

#include "formats/scene/accessor_values.h"
#include "lib/scene/scene_summary.h"
#include "lib/scene/scene_topology.h"
#include "tests/gltf/sample_scenes.h"

namespace lodbake {
namespace {

using sample_scenes::accessor;

TEST(AccessorValues, NormalizedIntegersFollowTheGltfRules) {
  const AccessorData u8 =
      accessor<uint8_t>(ComponentType::kUnsignedByte, ElementType::kVec2, {0, 255, 51, 102}, true);
  EXPECT_FLOAT_EQ(float_value(u8, 0, 1), 1.0f);
  EXPECT_FLOAT_EQ(float_value(u8, 1, 0), 0.2f);
  const AccessorData i16 =
      accessor<int16_t>(ComponentType::kShort, ElementType::kScalar, {-32768, 32767}, true);
  EXPECT_FLOAT_EQ(float_value(i16, 0, 0), -1.0f);  // clamped, not -1.00003
  EXPECT_FLOAT_EQ(float_value(i16, 1, 0), 1.0f);
  const AccessorData plain =
      accessor<uint16_t>(ComponentType::kUnsignedShort, ElementType::kScalar, {700});
  EXPECT_FLOAT_EQ(float_value(plain, 0, 0), 700.0f);
  EXPECT_EQ(float_values(u8).size(), 4u);
}

ScenePrimitive primitive(PrimitiveMode mode, std::vector<float> positions,
                         std::optional<std::vector<uint32_t>> indices) {
  ScenePrimitive p;
  p.mode = mode;
  p.indices = std::move(indices);
  p.attributes.push_back(
      {"POSITION", accessor<float>(ComponentType::kFloat, ElementType::kVec3, positions)});
  return p;
}

TEST(PrimitiveTriangles, StripsAndFansUnrollCounterClockwise) {
  const std::vector<float> square = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const auto strip = primitive_triangles(primitive(PrimitiveMode::kTriangleStrip, square, {}));
  ASSERT_EQ(strip.size(), 2u);
  EXPECT_EQ(strip[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(strip[1], (std::array<uint32_t, 3>{1, 3, 2}));
  const auto fan =
      primitive_triangles(primitive(PrimitiveMode::kTriangleFan, square, {{0, 1, 3, 2}}));
  ASSERT_EQ(fan.size(), 2u);
  EXPECT_EQ(fan[0], (std::array<uint32_t, 3>{1, 3, 0}));
  // A repeated index stitches strips: that zero-area triangle is dropped.
  const auto stitched =
      primitive_triangles(primitive(PrimitiveMode::kTriangleStrip, square, {{0, 1, 2, 2, 3}}));
  EXPECT_EQ(stitched.size(), 1u);
  EXPECT_TRUE(primitive_triangles(primitive(PrimitiveMode::kLines, square, {})).empty());
}

// Two primitives (two materials) sharing the edge x = 1; the second has a
// UV seam at one of its own points.
Scene two_material_scene() {
  Scene scene;
  SceneMesh mesh;
  ScenePrimitive left = primitive(PrimitiveMode::kTriangles, {0, 0, 0, 1, 0, 0, 1, 1, 0},
                                  std::vector<uint32_t>{0, 1, 2});
  left.material = 0;
  ScenePrimitive right =
      primitive(PrimitiveMode::kTriangles, {1, 0, 0, 2, 0, 0, 1, 1, 0, 2, 1, 0, 2, 1, 0},
                std::vector<uint32_t>{0, 1, 2, 2, 1, 4});
  right.material = 1;
  right.attributes.push_back(
      {"TEXCOORD_0", accessor<float>(ComponentType::kFloat, ElementType::kVec2,
                                     {0, 0, 1, 0, 0, 1, 1, 1, 0.5f, 1})});
  mesh.primitives = {left, right};
  // Points: left 0,1,2; right's vertices 0 and 2 are left's 1 and 2; its
  // vertices 3 and 4 are one point with two UVs.
  mesh.point_of_vertex = {{0, 1, 2}, {1, 3, 2, 4, 4}};
  mesh.point_count = 5;
  scene.meshes.push_back(mesh);
  scene.materials = SceneJson::array({{{"name", "red"}}, {{"name", "blue"}}});
  SceneNode a, b;
  a.mesh = 0;
  b.mesh = 0;
  b.translation = std::array<double, 3>{3, 0, 0};
  scene.nodes = {a, b};
  return scene;
}

TEST(MeshTopology, WeldsPrimitivesAlongTheirBorder) {
  const MeshTopology t = mesh_topology(two_material_scene().meshes[0]);
  EXPECT_EQ(t.mesh.positions.size(), 5u);
  ASSERT_EQ(t.mesh.triangles.size(), 3u);
  EXPECT_EQ(t.mesh.triangles[1], (Triangle{1, 3, 2}));
  EXPECT_EQ(t.mesh.triangles[2], (Triangle{2, 3, 4}));
  EXPECT_EQ(t.primitive_of_triangle, (std::vector<uint32_t>{0, 1, 1}));
  EXPECT_EQ(t.triangles_per_primitive, (std::vector<uint64_t>{1, 2}));
  EXPECT_EQ(t.mesh.positions[4], (Vec3f{2, 1, 0}));
}

TEST(SceneSummary, CountsInstancesMaterialsAndSeams) {
  const SceneSummary s = summarize_scene(two_material_scene());
  EXPECT_EQ(s.triangles, 3u);
  EXPECT_EQ(s.instanced_triangles, 6u);
  ASSERT_EQ(s.meshes.size(), 1u);
  const MeshSummary& m = s.meshes[0];
  EXPECT_EQ(m.nodes, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(m.points, 5u);
  // Points 1 and 2 border the materials (and differ in attributes); point 4
  // carries two UVs.
  EXPECT_EQ(m.border_points, 2u);
  EXPECT_EQ(m.seam_points, 3u);
  ASSERT_EQ(m.primitives.size(), 2u);
  EXPECT_EQ(m.primitives[0].seam_points, 2u);
  EXPECT_EQ(m.primitives[1].seam_points, 3u);
  EXPECT_EQ(m.primitives[1].material_name, "blue");
  EXPECT_EQ(m.primitives[1].attributes[1], "TEXCOORD_0 VEC2 float");
  EXPECT_EQ(to_json(s)["meshes"][0]["instances"], 2);
}

}  // namespace
}  // namespace lodbake
