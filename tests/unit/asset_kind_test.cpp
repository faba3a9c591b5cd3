// Tests of which inputs the tools take as assets (is_asset(),
// is_scene_source(); docs/import.md "Meshes as scenes"): an OBJ with
// materials or a PLY with colours is an asset, an OBJ with texture
// coordinates only is a mesh that simplify -o OUT.glb reads as a scene, and
// every shared mesh stays a mesh. Also: an OBJ's library or image outside
// its folder is refused (kUnsupported), a missing one is a warning.
#include <gtest/gtest.h>

#include <dirent.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <fstream>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "lib/scene/asset_build.h"
#include "lib/scene/scene_io.h"

namespace lodbake {
namespace {

constexpr char kTriangles[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n";

class AssetKind : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = ::testing::TempDir() + "lodbake_asset_kind_XXXXXX";
    ASSERT_NE(::mkdtemp(root_.data()), nullptr);
    ASSERT_EQ(::mkdir((root_ + "/in").c_str(), 0755), 0);
  }

  // Writes `text` to root/in/<name> and returns its path.
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = root_ + "/in/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  static Bytes bytes_of(const std::string& path) {
    Result<Bytes> bytes = read_file(path);
    EXPECT_TRUE(bytes.is_ok()) << path;
    return bytes.is_ok() ? std::move(bytes).value() : Bytes();
  }
  static bool asset(const std::string& path) { return is_asset(path, bytes_of(path)); }
  static bool scene_source(const std::string& path) {
    return is_scene_source(path, bytes_of(path));
  }

  std::string root_;
};

TEST_F(AssetKind, ObjWithoutMaterialsOrTextureCoordinatesIsAMesh) {
  const std::string path = write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_FALSE(asset(path));
  EXPECT_FALSE(scene_source(path));
  // A library that exists but no material in use: still a mesh.
  write("m.mtl", "newmtl paint\nKd 1 0 0\n");
  const std::string unused =
      write("unused.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_FALSE(asset(unused));
}

TEST_F(AssetKind, TextureCoordinatesAloneMakeASceneSourceNotAnAsset) {
  const std::string path = write("uv.obj", std::string(kTriangles) + "f 1/1 2/2 3/3\n");
  EXPECT_FALSE(asset(path));
  EXPECT_TRUE(scene_source(path));
  // Texture coordinates on only some faces count too.
  const std::string partial =
      write("partial.obj", std::string(kTriangles) + "f 1/1 2/2 3/3\nf 1 3 4\n");
  EXPECT_TRUE(scene_source(partial));
}

TEST_F(AssetKind, MaterialFromALibraryThatExistsMakesAnAsset) {
  write("m.mtl", "newmtl paint\nKd 1 0 0\n");
  const std::string path =
      write("one.obj", std::string("mtllib m.mtl\n") + kTriangles + "usemtl paint\nf 1 2 3\n");
  EXPECT_TRUE(asset(path));
  EXPECT_TRUE(scene_source(path));
  // The same file whose library is missing: one material group, a mesh.
  const std::string missing = write(
      "missing.obj", std::string("mtllib gone.mtl\n") + kTriangles + "usemtl paint\nf 1 2 3\n");
  EXPECT_FALSE(asset(missing));
}

TEST_F(AssetKind, TwoMaterialGroupsMakeAnAssetWithoutALibrary) {
  const std::string two = write("two.obj", std::string("mtllib gone.mtl\n") + kTriangles +
                                               "usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\n");
  EXPECT_TRUE(asset(two));
  // Faces before any usemtl form a group of their own.
  const std::string before =
      write("before.obj", std::string(kTriangles) + "f 1 2 3\nusemtl b\nf 1 3 4\n");
  EXPECT_TRUE(asset(before));
  // One name used twice is one group.
  const std::string same =
      write("same.obj", std::string(kTriangles) + "usemtl a\nf 1 2 3\ng x\nusemtl a\nf 1 3 4\n");
  EXPECT_FALSE(asset(same));

  // Read as an asset: the missing library is one warning, the file reads.
  ImportReport report;
  Result<Scene> scene = read_scene_file(two, SceneResources(), &report);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("gone.mtl"), std::string::npos);
  EXPECT_EQ(scene.value().meshes[0].primitives.size(), 2u);
}

TEST_F(AssetKind, LibraryOutsideTheFolderIsAnAssetThatReadsOnlyWhenAllowed) {
  std::ofstream(root_ + "/outside.mtl") << "newmtl paint\nKd 1 0 0\n";
  const std::string path = write(
      "out.obj", std::string("mtllib ../outside.mtl\n") + kTriangles + "usemtl paint\nf 1 2 3\n");
  EXPECT_TRUE(asset(path));
  ImportReport report;
  Result<Scene> refused = read_scene_file(path, SceneResources(), &report);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kUnsupported);
  EXPECT_NE(refused.status().message().find("../outside.mtl"), std::string::npos);

  SceneResources allowed;
  allowed.allow_outside = true;
  ImportReport allowed_report;
  Result<Scene> read = read_scene_file(path, allowed, &allowed_report);
  ASSERT_TRUE(read.is_ok()) << read.status().message();
  EXPECT_TRUE(allowed_report.warnings.empty());
  ASSERT_EQ(read.value().materials.size(), 1u);
  EXPECT_EQ(read.value().materials[0]["pbrMetallicRoughness"]["baseColorFactor"],
            SceneJson({1.0, 0.0, 0.0, 1.0}));
}

TEST_F(AssetKind, ImageOutsideTheFolderIsRefusedAMissingOneWarned) {
  std::ofstream(root_ + "/outside.png") << "\x89PNG\r\n";
  write("m.mtl", "newmtl paint\nmap_Kd ../outside.png\nnewmtl other\nmap_Kd absent.png\n");
  const std::string outside = write(
      "img.obj", std::string("mtllib m.mtl\n") + kTriangles + "usemtl paint\nf 1/1 2/2 3/3\n");
  ImportReport report;
  Result<Scene> refused = read_scene_file(outside, SceneResources(), &report);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kUnsupported);
  EXPECT_NE(refused.status().message().find("outside.png"), std::string::npos);

  const std::string absent = write(
      "absent.obj", std::string("mtllib m.mtl\n") + kTriangles + "usemtl other\nf 1/1 2/2 3/3\n");
  ImportReport absent_report;
  Result<Scene> read = read_scene_file(absent, SceneResources(), &absent_report);
  ASSERT_TRUE(read.is_ok()) << read.status().message();
  ASSERT_EQ(absent_report.warnings.size(), 1u);
  EXPECT_NE(absent_report.warnings[0].find("absent.png"), std::string::npos);
  ASSERT_EQ(read.value().images.size(), 1u);
  EXPECT_TRUE(read.value().images[0].missing);
}

TEST_F(AssetKind, PlyWithColoursIsAnAssetWithoutIsAMesh) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string coloured =
      write("c.ply", header + "property uchar red\nproperty uchar green\nproperty uchar blue\n" +
                         faces + "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n");
  EXPECT_TRUE(asset(coloured));
  EXPECT_TRUE(scene_source(coloured));
  const std::string plain = write("p.ply", header + "property float u\nproperty float v\n" + faces +
                                               "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n");
  EXPECT_FALSE(asset(plain));
  EXPECT_FALSE(scene_source(plain));
}

// The guarantee that plain meshes keep their behaviour: no shared mesh
// file is an asset, and only the one with texture coordinates is a scene
// source (for simplify -o OUT.glb). c3d_beetle.obj names a library that is
// not there and uses one material: a mesh.
TEST(AssetKindShared, EverySharedMeshIsAMesh) {
  const std::string folder = std::string(LODBAKE_TEST_SHARED_DATA) + "/meshes";
  DIR* dir = ::opendir(folder.c_str());
  ASSERT_NE(dir, nullptr) << folder;
  std::vector<std::string> names;
  while (dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (name.find(".part") != std::string::npos || name.rfind(".md") == name.size() - 3 ||
        name[0] == '.')
      continue;
    names.push_back(name);
  }
  ::closedir(dir);
  ASSERT_GE(names.size(), 30u);
  for (const std::string& name : names) {
    const std::string path = folder + "/" + name;
    Result<Bytes> bytes = read_file(path);
    ASSERT_TRUE(bytes.is_ok()) << path;
    EXPECT_FALSE(is_asset(path, bytes.value())) << name;
    EXPECT_EQ(is_scene_source(path, bytes.value()), name == "c3d_spot.obj") << name;
  }
}

TEST(AssetKindShared, GltfIsAnAsset) {
  const std::string duck = std::string(LODBAKE_TEST_SHARED_DATA) + "/assets/Duck/Duck.glb";
  Result<Bytes> bytes = read_file(duck);
  ASSERT_TRUE(bytes.is_ok()) << duck;
  EXPECT_TRUE(is_asset(duck, bytes.value()));
  EXPECT_TRUE(is_scene_source(duck, bytes.value()));
}

}  // namespace
}  // namespace lodbake
