// Whole assets in lodbake: the asset container (SCNE + a BASE per mesh)
// gives the scene back, and simplify_scene keeps materials, shares border
// points between primitives and carries each corner's attributes.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "formats/container/section_registry.h"
#include "formats/scene/accessor_values.h"
#include "formats/sections/base.h"
#include "formats/sections/open_container.h"
#include "formats/sections/scne.h"
#include "lib/meshio/mesh_import.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_compare.h"
#include "lib/scene/scene_container.h"
#include "lib/scene/scene_from_mesh.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_lods.h"
#include "lib/scene/scene_pack.h"
#include "lib/scene/scene_points.h"
#include "lib/scene/scene_topology.h"
#include "tests/unit/asset_test_support.h"

namespace lodbake {
namespace {

using test::kAssets;
using test::read_asset;

TEST(AssetContainer, GivesTheSceneBackWithAGroupPerMesh) {
  const Scene truck = read_asset(kAssets + "CesiumMilkTruck/CesiumMilkTruck.gltf");
  MetaSection meta = make_meta("test");
  Result<ScenePackResult> packed = pack_scene(truck, meta, BaseEncodeOptions{});
  ASSERT_TRUE(packed.is_ok()) << packed.status().message();
  Result<OpenedContainer> opened = open_container(packed.value().file);
  ASSERT_TRUE(opened.is_ok()) << opened.status().message();
  SceneSection map;
  Result<Scene> back = scene_of_container(opened.value().decoded(), &map);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  // The image's file name comes back too (the map keeps it).
  EXPECT_EQ(first_scene_difference(truck, back.value()), "");
  ASSERT_EQ(map.meshes.size(), 2u);
  for (const SceneMeshGroup& m : map.meshes) {
    const MeshTopology topology = mesh_topology(truck.meshes[m.mesh]);
    EXPECT_EQ(m.triangles, topology.triangles_per_primitive);
    const Section* base = opened.value().find(kBaseTag, m.group);
    ASSERT_NE(base, nullptr);
    Result<TriangleMesh> mesh = decode_base(base->data, base->size);
    ASSERT_TRUE(mesh.is_ok());
    EXPECT_EQ(mesh.value().positions, topology.mesh.positions);
    EXPECT_EQ(mesh.value().triangles, topology.mesh.triangles);
  }
  // Same scene, same bytes.
  EXPECT_EQ(pack_scene(truck, meta, BaseEncodeOptions{}).value().file, packed.value().file);
}

// The elephant cut in two materials by x, each primitive with its own copy
// of the border vertices (as glTF stores them) and UVs that are a function
// of the position, so a corner's UV says which point it came from.
Scene two_material_elephant() {
  ImportReport report;
  Result<TriangleMesh> mesh =
      import_mesh_file(std::string(LODBAKE_TEST_SOURCE_DIR) + "/samples/elephant.off", &report);
  EXPECT_TRUE(mesh.is_ok());
  const TriangleMesh& m = mesh.value();
  std::vector<ScenePrimitive> primitives(2);
  for (int p = 0; p < 2; ++p) {
    std::map<uint32_t, uint32_t> local;
    std::vector<float> positions, uvs;
    std::vector<uint32_t> indices;
    for (const Triangle& t : m.triangles) {
      const float x = m.positions[t[0]][0] + m.positions[t[1]][0] + m.positions[t[2]][0];
      if ((x < 0) != (p == 0)) continue;
      for (uint32_t v : t) {
        auto [it, added] = local.emplace(v, static_cast<uint32_t>(local.size()));
        if (added) {
          const Vec3f& q = m.positions[v];
          positions.insert(positions.end(), q.begin(), q.end());
          uvs.push_back(q[0] * 0.5f + q[2]);
          uvs.push_back(q[1] - q[2] * 0.25f);
        }
        indices.push_back(it->second);
      }
    }
    ScenePrimitive& prim = primitives[p];
    prim.material = p;
    prim.indices = indices;
    const uint32_t n = static_cast<uint32_t>(local.size());
    prim.attributes.push_back({"POSITION", float_accessor(positions.data(), n, 3)});
    prim.attributes.push_back({"TEXCOORD_0", float_accessor(uvs.data(), n, 2)});
  }
  Scene scene = scene_of_mesh("elephant", std::move(primitives));
  scene.materials = SceneJson::array({{{"name", "left"}}, {{"name", "right"}}});
  weld_mesh_points(&scene.meshes[0]);
  return scene;
}

// Edges used by one triangle only, over points welded by position.
size_t open_edges(const SceneMesh& mesh) {
  std::map<std::pair<Vec3f, Vec3f>, int> edges;
  for (const ScenePrimitive& prim : mesh.primitives) {
    const AccessorData& pos = prim.find("POSITION")->data;
    auto at = [&](uint32_t v) {
      return Vec3f{float_value(pos, v, 0), float_value(pos, v, 1), float_value(pos, v, 2)};
    };
    for (const std::array<uint32_t, 3>& t : primitive_triangles(prim))
      for (int k = 0; k < 3; ++k) {
        Vec3f a = at(t[k]), b = at(t[(k + 1) % 3]);
        if (b < a) std::swap(a, b);
        ++edges[{a, b}];
      }
  }
  size_t open = 0;
  for (const auto& [edge, count] : edges)
    open += count == 1 ? 1 : 0;
  return open;
}

TEST(SimplifyScene, KeepsMaterialsBordersAndEachCornersAttributes) {
  const Scene scene = two_material_elephant();
  ASSERT_EQ(open_edges(scene.meshes[0]), 0u);  // closed, the border shared by position
  SceneLodOptions options;
  options.ratios = {0.5, 0.2};
  Result<SceneLods> lods = simplify_scene(scene, options);
  ASSERT_TRUE(lods.is_ok()) << lods.status().message();
  ASSERT_EQ(lods.value().levels.size(), 2u);
  const MeshLodReport& report = lods.value().meshes.at(0);
  for (size_t level = 0; level < 2; ++level) {
    const SceneMesh& mesh = lods.value().levels[level].meshes[0];
    ASSERT_EQ(mesh.primitives.size(), 2u);
    EXPECT_EQ(mesh.primitives[0].material, 0);
    EXPECT_EQ(mesh.primitives[1].material, 1);
    // No crack between the materials: still closed.
    EXPECT_EQ(open_edges(mesh), 0u) << "level " << level;
    uint64_t triangles = 0;
    size_t off_uv = 0;
    for (const ScenePrimitive& prim : mesh.primitives) {
      triangles += primitive_triangles(prim).size();
      const AccessorData& pos = prim.find("POSITION")->data;
      const AccessorData& uv = prim.find("TEXCOORD_0")->data;
      for (uint32_t v = 0; v < pos.count; ++v) {
        const float x = float_value(pos, v, 0), y = float_value(pos, v, 1),
                    z = float_value(pos, v, 2);
        if (float_value(uv, v, 0) != x * 0.5f + z || float_value(uv, v, 1) != y - z * 0.25f)
          ++off_uv;
      }
    }
    EXPECT_EQ(triangles, report.lod_triangles[level]);
    EXPECT_EQ(off_uv, 0u) << "level " << level;  // no wedge moved without --permissive
  }
  EXPECT_LE(report.lod_triangles[0], report.input_triangles / 2);
  EXPECT_LT(report.lod_triangles[1], report.lod_triangles[0]);
  // Deterministic.
  Result<SceneLods> again = simplify_scene(scene, options);
  ASSERT_TRUE(again.is_ok());
  EXPECT_EQ(first_scene_difference(again.value().levels[1], lods.value().levels[1]), "");
}

TEST(SimplifyScene, EachMeshOnceAndTheSceneAroundItKept) {
  const Scene spheres =
      read_asset(kAssets + "SpheresScaledInstances/spheres_scaled_instances.gltf");
  SceneLodOptions options;
  options.ratios = {0.5};
  Result<SceneLods> lods = simplify_scene(spheres, options);
  ASSERT_TRUE(lods.is_ok()) << lods.status().message();
  ASSERT_EQ(lods.value().meshes.size(), spheres.meshes.size());
  Scene level = lods.value().levels[0];
  EXPECT_EQ(level.nodes, spheres.nodes);
  EXPECT_EQ(level.materials, spheres.materials);
  // Only the meshes' primitives changed.
  level.meshes = spheres.meshes;
  EXPECT_EQ(first_scene_difference(level, spheres), "");
}

TEST(SimplifyScene, RefusesOptimalPlacement) {
  SceneLodOptions options;
  options.simplify.placement = Placement::kOptimal;
  Result<SceneLods> lods = simplify_scene(two_material_elephant(), options);
  ASSERT_FALSE(lods.is_ok());
  EXPECT_EQ(lods.status().kind(), ErrorKind::kUsage);
}

TEST(AssetBuild, OneGroupPerMeshBesideTheScene) {
  const Scene truck = read_asset(kAssets + "CesiumMilkTruck/CesiumMilkTruck.gltf");
  std::vector<uint32_t> meshes_built;
  const MeshBuilder base_only = [&](uint32_t mesh, const TriangleMesh& m) -> Result<MeshSections> {
    meshes_built.push_back(mesh);
    MeshSections out;
    LODBAKE_ASSIGN_OR_RETURN(Bytes base, encode_base(m, BaseEncodeOptions{}));
    out.sections.emplace_back(kBaseTag, std::move(base));
    out.counts = {{"vertices", m.vertex_count()}, {"triangles", m.triangle_count()}};
    return out;
  };
  Result<AssetBuild> built = build_asset(truck, make_meta("test"), LoadOptions{}, base_only);
  ASSERT_TRUE(built.is_ok()) << built.status().message();
  // The wheels' mesh is used by two nodes and built once.
  EXPECT_EQ(meshes_built, (std::vector<uint32_t>{0, 1}));
  ASSERT_EQ(built.value().groups.size(), 2u);
  EXPECT_TRUE(built.value().groups[0]["repaired"].get<bool>());  // two split fans
  Result<OpenedContainer> opened = open_container(built.value().file);
  ASSERT_TRUE(opened.is_ok()) << opened.status().message();
  EXPECT_EQ(opened.value().group_count(), 2u);
  Result<Scene> back = scene_of_container(opened.value().decoded());
  ASSERT_TRUE(back.is_ok());
  EXPECT_EQ(first_scene_difference(truck, back.value()), "");
  // A builder's failure names the mesh.
  const MeshBuilder failing = [](uint32_t, const TriangleMesh&) -> Result<MeshSections> {
    return runtime_error("no memory left");
  };
  Result<AssetBuild> failed = build_asset(truck, make_meta("test"), LoadOptions{}, failing);
  ASSERT_FALSE(failed.is_ok());
  EXPECT_EQ(failed.status().message(), "mesh 0: no memory left");
  // --strict refuses the mesh the default repair would have fixed.
  LoadOptions strict;
  strict.strict = true;
  Result<AssetBuild> refused = build_asset(truck, make_meta("test"), strict, base_only);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_NE(refused.status().message().find("mesh 0: --strict"), std::string::npos)
      << refused.status().message();
}

}  // namespace
}  // namespace lodbake
