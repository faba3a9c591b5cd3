// parse_gltf() against the scene model: for every real asset, the merged
// mesh must be the default scene of read_gltf_scene()'s scene, flattened
// here independently (corner by corner: positions in world space, texture
// coordinates with v flipped), so that the merged-mesh reader and the scene
// reader cannot drift apart.
#include <gtest/gtest.h>

#include <dirent.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "formats/scene/accessor_values.h"
#include "formats/scene/node_matrix.h"
#include "formats/support/file_io.h"
#include "lib/dracoio/draco_io.h"
#include "tests/unit/asset_test_support.h"

namespace lodbake {
namespace {

using test::kAssets;
using test::read_asset;

// Every .gltf and .glb one folder below `root`, sorted.
std::vector<std::string> asset_files(const std::string& root) {
  std::vector<std::string> out;
  auto list = [](const std::string& dir) {
    std::vector<std::string> names;
    if (DIR* d = opendir(dir.c_str())) {
      while (const dirent* e = readdir(d))
        if (e->d_name[0] != '.') names.push_back(e->d_name);
      closedir(d);
    }
    std::sort(names.begin(), names.end());
    return names;
  };
  for (const std::string& folder : list(root)) {
    for (const std::string& name : list(root + folder)) {
      const size_t dot = name.rfind('.');
      const std::string ext = dot == std::string::npos ? "" : name.substr(dot);
      if (ext == ".gltf" || ext == ".glb") out.push_back(root + folder + "/" + name);
    }
  }
  return out;
}

struct Corner {
  Vec3f position;
  std::array<float, 2> uv;  // (u, 1 - v)
};

struct Flat {
  std::vector<Corner> corners;  // three per triangle
  bool all_have_uv = true;
  size_t transformed_instances = 0;
};

// The default scene's triangle primitives as corners, straight from the model.
Flat flatten_in_test(const Scene& scene) {
  Flat flat;
  std::vector<uint32_t> roots;
  if (scene.scenes.empty()) {
    std::vector<bool> child(scene.nodes.size(), false);
    for (const SceneNode& n : scene.nodes)
      for (uint32_t c : n.children)
        child[c] = true;
    for (uint32_t i = 0; i < scene.nodes.size(); ++i)
      if (!child[i]) roots.push_back(i);
  } else {
    roots = scene.scenes[scene.default_scene < 0 ? 0 : scene.default_scene].nodes;
  }
  std::vector<std::pair<uint32_t, Mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it)
    stack.emplace_back(*it, identity_matrix());
  while (!stack.empty()) {
    const auto [index, parent] = stack.back();
    stack.pop_back();
    const SceneNode& node = scene.nodes[index];
    const Mat4 m = multiply(parent, local_matrix(node));
    if (node.mesh >= 0) {
      const bool identity = m == identity_matrix();
      if (!identity) ++flat.transformed_instances;
      const bool mirrored = linear_determinant(m) < 0;
      for (const ScenePrimitive& p : scene.meshes[node.mesh].primitives) {
        const SceneAttribute* position = p.find("POSITION");
        if (p.mode < PrimitiveMode::kTriangles || position == nullptr) continue;
        const SceneAttribute* uv = p.find("TEXCOORD_0");
        if (uv == nullptr) flat.all_have_uv = false;
        for (const auto& t : primitive_triangles(p)) {
          const std::array<uint32_t, 3> order =
              mirrored ? std::array<uint32_t, 3>{t[0], t[2], t[1]} : t;
          for (uint32_t v : order) {
            Corner c;
            const float x = float_value(position->data, v, 0);
            const float y = float_value(position->data, v, 1);
            const float z = float_value(position->data, v, 2);
            c.position = {x, y, z};
            if (!identity) {
              for (int r = 0; r < 3; ++r)
                c.position[r] = static_cast<float>(double{m[r]} * x + m[4 + r] * double{y} +
                                                   m[8 + r] * double{z} + m[12 + r]);
            }
            c.uv = {0, 0};
            if (uv != nullptr)
              c.uv = {float_value(uv->data, v, 0), 1.0f - float_value(uv->data, v, 1)};
            flat.corners.push_back(c);
          }
        }
      }
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
      stack.emplace_back(*it, m);
  }
  return flat;
}

std::array<float, 2> corner_uv(const TriangleMesh& mesh, size_t t, int k) {
  const MeshAttribute& a = mesh.texcoords;
  const uint32_t value =
      a.binding == AttributeBinding::kPerCorner ? a.corners[t][k] : mesh.triangles[t][k];
  return {a.values[2 * size_t{value}], a.values[2 * size_t{value} + 1]};
}

TEST(GltfFlatten, MergedMeshIsTheFlattenedSceneOfEveryAsset) {
  const std::vector<std::string> files = asset_files(kAssets);
  ASSERT_GE(files.size(), 11u) << kAssets;
  size_t transformed = 0, textured = 0;
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    Result<Bytes> bytes = read_file(path);
    ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
    SceneResources resources;
    resources.folder = path.substr(0, path.rfind('/'));
    ImportReport report;
    Result<TriangleMesh> merged =
        parse_gltf(bytes.value().data(), bytes.value().size(), &report, resources);
    ASSERT_TRUE(merged.is_ok()) << merged.status().message();
    const TriangleMesh& mesh = merged.value();
    const Flat flat = flatten_in_test(read_asset(path));
    ASSERT_EQ(mesh.triangles.size() * 3, flat.corners.size());
    ASSERT_GT(flat.corners.size(), 0u);
    EXPECT_EQ(mesh.texcoords.present(), flat.all_have_uv);
    transformed += flat.transformed_instances > 0;
    textured += mesh.texcoords.present();
    size_t position_mismatches = 0, uv_mismatches = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const Corner& want = flat.corners[3 * t + k];
        if (mesh.positions[mesh.triangles[t][k]] != want.position) ++position_mismatches;
        if (mesh.texcoords.present() && corner_uv(mesh, t, k) != want.uv) ++uv_mismatches;
      }
    }
    EXPECT_EQ(position_mismatches, 0u);
    EXPECT_EQ(uv_mismatches, 0u);
  }
  // The assets exercise node transforms and texture coordinates.
  EXPECT_GE(transformed, 3u);
  EXPECT_GE(textured, 5u);
}

}  // namespace
}  // namespace lodbake
