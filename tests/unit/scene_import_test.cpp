// Tests of lib/scene's mesh files as scenes: every shared mesh reads as a
// scene with the triangles and positions import_mesh() gives, OBJ corners
// become one vertex per (v, vt, vn) triple, OBJ + MTL give primitives,
// materials, textures and images, PLY colours give COLOR_0.
#include <gtest/gtest.h>

#include <dirent.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "lib/meshio/mesh_import.h"
#include "lib/scene/scene_from_mesh.h"
#include "lib/scene/scene_io.h"

namespace lodbake {
namespace {

std::string shared_meshes() {
  return std::string(LODBAKE_TEST_SHARED_DATA) + "/meshes";
}

using Bits = std::array<uint32_t, 3>;  // a position by its bit pattern

Bits bits_of(const float* p) {
  Bits b;
  std::memcpy(b.data(), p, sizeof(b));
  return b;
}

const float* floats(const SceneAttribute& a) {
  return reinterpret_cast<const float*>(a.data.bytes.data());
}

// A fresh folder under the test temp dir.
std::string temp_folder() {
  std::string folder = ::testing::TempDir() + "lodbake_scene_XXXXXX";
  EXPECT_NE(::mkdtemp(folder.data()), nullptr);
  return folder;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

Scene read_ok(const std::string& path, ImportReport* report) {
  Result<Scene> scene = read_scene_file(path, SceneResources(), report);
  EXPECT_TRUE(scene.is_ok()) << path << ": " << scene.status().message();
  return scene.is_ok() ? std::move(scene).value() : Scene();
}

// The triangles of every primitive, each as the bit patterns of its corners.
std::vector<std::array<Bits, 3>> position_triangles(const SceneMesh& mesh) {
  std::vector<std::array<Bits, 3>> out;
  for (const ScenePrimitive& p : mesh.primitives) {
    const SceneAttribute* pos = p.find("POSITION");
    EXPECT_NE(pos, nullptr);
    if (pos == nullptr || !p.indices) continue;
    const std::vector<uint32_t>& idx = *p.indices;
    for (size_t i = 0; i + 2 < idx.size(); i += 3) {
      std::array<Bits, 3> t;
      for (int k = 0; k < 3; ++k) {
        EXPECT_LT(idx[i + k], pos->data.count);
        t[k] = bits_of(floats(*pos) + 3 * size_t{idx[i + k]});
      }
      out.push_back(t);
    }
  }
  return out;
}

std::vector<std::array<Bits, 3>> position_triangles(const TriangleMesh& mesh) {
  std::vector<std::array<Bits, 3>> out;
  for (const Triangle& t : mesh.triangles)
    out.push_back({bits_of(mesh.positions[t[0]].data()), bits_of(mesh.positions[t[1]].data()),
                   bits_of(mesh.positions[t[2]].data())});
  return out;
}

TEST(SceneImport, EverySharedMeshAgreesWithImportMesh) {
  DIR* dir = ::opendir(shared_meshes().c_str());
  ASSERT_NE(dir, nullptr);
  std::vector<std::string> names;
  while (dirent* e = ::readdir(dir)) {
    const std::string name = e->d_name;
    if (name[0] == '.' || name == "MANIFEST.md" || name.find(".xz") != std::string::npos) continue;
    names.push_back(name);
  }
  ::closedir(dir);
  std::sort(names.begin(), names.end());
  ASSERT_GE(names.size(), 37u);  // MANIFEST.md: 38 meshes, the full dragon as .xz parts
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const std::string path = shared_meshes() + "/" + name;
    ImportReport mesh_report, scene_report;
    Result<TriangleMesh> mesh = import_mesh_file(path, &mesh_report);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    Scene scene = read_ok(path, &scene_report);
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.nodes.size(), 1u);
    EXPECT_EQ(scene.nodes[0].mesh, 0);
    ASSERT_EQ(scene.scenes.size(), 1u);
    EXPECT_EQ(scene.scenes[0].nodes, std::vector<uint32_t>{0});
    EXPECT_EQ(scene.default_scene, 0);
    EXPECT_EQ(scene.meshes[0].name, name.substr(0, name.find('.')));
    EXPECT_EQ(scene_report.format, mesh_report.format);

    const SceneMesh& m = scene.meshes[0];
    size_t vertices = 0;
    std::set<Bits> scene_positions;
    for (const ScenePrimitive& p : m.primitives) {
      EXPECT_EQ(p.mode, PrimitiveMode::kTriangles);
      vertices += p.vertex_count();
      const SceneAttribute* pos = p.find("POSITION");
      ASSERT_NE(pos, nullptr);
      for (uint32_t v = 0; v < pos->data.count; ++v)
        scene_positions.insert(bits_of(floats(*pos) + 3 * size_t{v}));
      for (const SceneAttribute& a : p.attributes)
        EXPECT_EQ(a.data.count, pos->data.count) << a.semantic;
    }
    std::set<Bits> mesh_positions;
    for (const Vec3f& p : mesh.value().positions)
      mesh_positions.insert(bits_of(p.data()));
    EXPECT_EQ(scene_positions, mesh_positions);
    // Splitting only adds vertices: every mesh vertex is there at least once.
    EXPECT_GE(vertices, mesh.value().positions.size());
    if (!mesh.value().normals.present() && !mesh.value().texcoords.present()) {
      EXPECT_EQ(vertices, mesh.value().positions.size());
    }

    std::vector<std::array<Bits, 3>> from_scene = position_triangles(m);
    std::vector<std::array<Bits, 3>> from_mesh = position_triangles(mesh.value());
    ASSERT_EQ(from_scene.size(), mesh.value().triangles.size());
    if (m.primitives.size() != 1) {
      std::sort(from_scene.begin(), from_scene.end());
      std::sort(from_mesh.begin(), from_mesh.end());
    }
    EXPECT_TRUE(from_scene == from_mesh);
  }
}

// The distinct "v/vt" corners of a triangle-only OBJ with per-corner UVs.
TEST(SceneImport, SpotGetsOneVertexPerDistinctCorner) {
  const std::string path = shared_meshes() + "/c3d_spot.obj";
  std::ifstream in(path);
  std::vector<std::array<float, 3>> v;
  std::vector<std::array<float, 2>> vt;
  std::vector<std::pair<uint32_t, uint32_t>> corners;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string k;
    s >> k;
    if (k == "v") {
      std::array<float, 3> p;
      s >> p[0] >> p[1] >> p[2];
      v.push_back(p);
    } else if (k == "vt") {
      std::array<float, 2> t;
      s >> t[0] >> t[1];
      vt.push_back(t);
    } else if (k == "f") {
      std::string c;
      while (s >> c) {
        const size_t slash = c.find('/');
        corners.emplace_back(std::stoul(c.substr(0, slash)) - 1,
                             std::stoul(c.substr(slash + 1)) - 1);
      }
    }
  }
  ASSERT_EQ(corners.size(), 5856u * 3);
  std::set<std::pair<uint32_t, uint32_t>> distinct(corners.begin(), corners.end());
  ASSERT_GT(distinct.size(), v.size());  // spot has UV seams

  ImportReport report;
  Scene scene = read_ok(path, &report);
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.meshes[0].primitives.size(), 1u);
  const ScenePrimitive& p = scene.meshes[0].primitives[0];
  const SceneAttribute* pos = p.find("POSITION");
  const SceneAttribute* uv = p.find("TEXCOORD_0");
  ASSERT_NE(pos, nullptr);
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(uv->data.component_type, ComponentType::kFloat);
  EXPECT_EQ(uv->data.type, ElementType::kVec2);
  EXPECT_EQ(p.find("NORMAL"), nullptr);
  EXPECT_EQ(p.vertex_count(), distinct.size());
  ASSERT_EQ(p.indices->size(), corners.size());
  // Every corner's vertex has the file's position and its (u, 1 - v), and
  // distinct vertices are distinct triples.
  std::map<uint32_t, std::pair<uint32_t, uint32_t>> triple_of_vertex;
  for (size_t c = 0; c < corners.size(); ++c) {
    const uint32_t vertex = (*p.indices)[c];
    const auto [vi, ti] = corners[c];
    const float* xyz = floats(*pos) + 3 * size_t{vertex};
    const float* st = floats(*uv) + 2 * size_t{vertex};
    EXPECT_EQ(xyz[0], v[vi][0]);
    EXPECT_EQ(xyz[1], v[vi][1]);
    EXPECT_EQ(xyz[2], v[vi][2]);
    EXPECT_EQ(st[0], vt[ti][0]);
    EXPECT_EQ(st[1], 1.0f - vt[ti][1]);
    auto [it, inserted] = triple_of_vertex.emplace(vertex, corners[c]);
    if (!inserted) {
      EXPECT_EQ(it->second, corners[c]);
    }
  }
  EXPECT_EQ(triple_of_vertex.size(), distinct.size());
}

TEST(SceneImport, SharedCornersAndSplitCorners) {
  const std::string folder = temp_folder();
  write_text(folder + "/quad.obj",
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
             "vn 0 0 1\n"
             // v3 is used with vt3 twice (one vertex) and with vt5 once (a second vertex).
             "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\nf 3/5/1 2/2/1 4/4/1\n");
  ImportReport report;
  Scene scene = read_ok(folder + "/quad.obj", &report);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const ScenePrimitive& p = scene.meshes[0].primitives[0];
  EXPECT_EQ(p.vertex_count(), 5u);
  EXPECT_EQ(*p.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 4, 1, 3}));
  const SceneAttribute* uv = p.find("TEXCOORD_0");
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(floats(*uv)[2 * 4], 0.5f);
  EXPECT_EQ(floats(*uv)[2 * 2 + 1], 0.0f);  // vt 1 1 flipped
  const SceneAttribute* n = p.find("NORMAL");
  ASSERT_NE(n, nullptr);
  EXPECT_EQ(floats(*n)[3 * 4 + 2], 1.0f);
  ASSERT_EQ(p.attributes.size(), 3u);
  EXPECT_EQ(p.attributes[0].semantic, "NORMAL");
  EXPECT_EQ(p.attributes[1].semantic, "POSITION");
  EXPECT_EQ(p.attributes[2].semantic, "TEXCOORD_0");
  EXPECT_TRUE(scene.materials.is_null());
}

const char kTwoMaterialObj[] =
    "mtllib lib/two.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\n"
    "f 5 2 3\n"  // before any usemtl: a primitive without material
    "usemtl red\nf 1/1 2/2 3/3\n"
    "usemtl glass blue\nf 1 3 4\n"
    "usemtl red\nf 2/2 5/1 3/3\n";

const char kTwoMaterialMtl[] =
    "# two materials\n"
    "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 98\nillum 2\nmap_Kd -s 1 1 1 tex\\red.png\n"
    "newmtl glass blue\nKd 0 0 1\nd 0.25\nKe 0 0.5 0\n";

TEST(SceneImport, ObjMaterialsBecomePrimitivesMaterialsAndTextures) {
  const std::string folder = temp_folder();
  ASSERT_EQ(::mkdir((folder + "/lib").c_str(), 0755), 0);
  ASSERT_EQ(::mkdir((folder + "/lib/tex").c_str(), 0755), 0);
  write_text(folder + "/two.obj", kTwoMaterialObj);
  write_text(folder + "/lib/two.mtl", kTwoMaterialMtl);
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + "not really an image";
  write_text(folder + "/lib/tex/red.png", png);

  ImportReport report;
  Scene scene = read_ok(folder + "/two.obj", &report);
  EXPECT_TRUE(report.warnings.empty()) << report.warnings[0];
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].name, "two");
  const std::vector<ScenePrimitive>& prims = scene.meshes[0].primitives;
  ASSERT_EQ(prims.size(), 3u);
  EXPECT_EQ(prims[0].material, -1);
  EXPECT_EQ(prims[1].material, 0);
  EXPECT_EQ(prims[2].material, 1);
  // Each primitive holds only the vertices its faces use.
  EXPECT_EQ(prims[0].vertex_count(), 3u);
  EXPECT_EQ(prims[1].vertex_count(), 4u);  // 1/1 2/2 3/3 5/1
  EXPECT_EQ(prims[2].vertex_count(), 3u);
  EXPECT_EQ(prims[1].indices->size(), 6u);
  // Texture coordinates only where every face of the group has them.
  EXPECT_NE(prims[1].find("TEXCOORD_0"), nullptr);
  EXPECT_EQ(prims[0].find("TEXCOORD_0"), nullptr);
  EXPECT_EQ(prims[2].find("TEXCOORD_0"), nullptr);

  ASSERT_TRUE(scene.materials.is_array());
  ASSERT_EQ(scene.materials.size(), 2u);
  const SceneJson& red = scene.materials[0];
  EXPECT_EQ(red["name"], "red");
  EXPECT_EQ(red["pbrMetallicRoughness"]["baseColorFactor"], SceneJson({1.0, 0.0, 0.0, 1.0}));
  EXPECT_EQ(red["pbrMetallicRoughness"]["metallicFactor"], 0.0);
  const double roughness = red["pbrMetallicRoughness"]["roughnessFactor"].get<double>();
  EXPECT_NEAR(roughness, std::pow(2.0 / 100.0, 0.25), 1e-6);
  EXPECT_EQ(red["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
  EXPECT_FALSE(red.contains("alphaMode"));
  const SceneJson& blue = scene.materials[1];
  EXPECT_EQ(blue["name"], "glass blue");
  EXPECT_EQ(blue["pbrMetallicRoughness"]["baseColorFactor"], SceneJson({0.0, 0.0, 1.0, 0.25}));
  EXPECT_EQ(blue["alphaMode"], "BLEND");
  EXPECT_EQ(blue["emissiveFactor"], SceneJson({0.0, 0.5, 0.0}));
  EXPECT_FALSE(blue["pbrMetallicRoughness"].contains("baseColorTexture"));

  ASSERT_TRUE(scene.textures.is_array());
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0], SceneJson({{"source", 0}}));
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].uri, "lib/tex/red.png");
  EXPECT_EQ(scene.images[0].mime_type, "image/png");
  EXPECT_FALSE(scene.images[0].missing);
  EXPECT_EQ(scene.images[0].bytes, Bytes(png.begin(), png.end()));
}

TEST(SceneImport, MissingMaterialLibraryIsOneWarning) {
  const std::string folder = temp_folder();
  write_text(folder + "/a.obj",
             "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n");
  ImportReport report;
  Scene scene = read_ok(folder + "/a.obj", &report);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("nowhere.mtl"), std::string::npos);
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0]["name"], "paint");
  EXPECT_EQ(scene.meshes[0].primitives[0].material, 0);
}

TEST(SceneImport, MissingTextureIsOneWarning) {
  const std::string folder = temp_folder();
  write_text(folder + "/a.obj",
             "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl paint\nf 1/1 2/1 3/1\n");
  write_text(folder + "/a.mtl", "newmtl paint\nKd 0.5 0.5 0.5\nmap_Kd gone.jpg\n");
  ImportReport report;
  Scene scene = read_ok(folder + "/a.obj", &report);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("gone.jpg"), std::string::npos);
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_TRUE(scene.images[0].missing);
  EXPECT_TRUE(scene.images[0].bytes.empty());
  EXPECT_EQ(scene.images[0].uri, "gone.jpg");
  EXPECT_EQ(scene.images[0].mime_type, "image/jpeg");
  EXPECT_EQ(scene.materials[0]["pbrMetallicRoughness"]["baseColorFactor"],
            SceneJson({0.5, 0.5, 0.5, 1.0}));
}

TEST(SceneImport, GroupMixingTextureCoordinatesDropsThemWithANote) {
  const std::string folder = temp_folder();
  write_text(folder + "/m.obj",
             "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
             "usemtl a\nf 1/1 2/1 3/1\nf 1 3 2\nusemtl b\nf 1/1 3/1 2/1\n");
  write_text(folder + "/m.mtl",
             "newmtl a\nTr 0.75\nPm 0.5\nPr 0.25\nKa 1 1 1\nnewmtl b\nmap_Ke -o 0 0 e.png\n");
  write_text(folder + "/e.png", "E");
  ImportReport report;
  Scene scene = read_ok(folder + "/m.obj", &report);
  EXPECT_TRUE(report.warnings.empty());
  const std::vector<ScenePrimitive>& prims = scene.meshes.at(0).primitives;
  ASSERT_EQ(prims.size(), 2u);
  EXPECT_EQ(prims[0].find("TEXCOORD_0"), nullptr);
  EXPECT_NE(prims[1].find("TEXCOORD_0"), nullptr);
  bool noted = false;
  for (const std::string& note : report.notes)
    noted =
        noted || note == "dropped texture coordinates of material 'a': 1 of 2 triangles have none";
  EXPECT_TRUE(noted);
  const SceneJson& a = scene.materials.at(0);
  EXPECT_EQ(a["pbrMetallicRoughness"]["baseColorFactor"], SceneJson({1.0, 1.0, 1.0, 0.25}));
  EXPECT_EQ(a["pbrMetallicRoughness"]["metallicFactor"], 0.5);
  EXPECT_EQ(a["pbrMetallicRoughness"]["roughnessFactor"], 0.25);
  const SceneJson& b = scene.materials.at(1);
  EXPECT_EQ(b["emissiveTexture"]["index"], 0);
  EXPECT_EQ(b["emissiveFactor"], SceneJson({1.0, 1.0, 1.0}));
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].uri, "e.png");
  EXPECT_EQ(scene.images[0].bytes, Bytes{'E'});
}

TEST(SceneImport, PlyUcharColoursBecomeNormalizedUnsignedBytes) {
  const std::string folder = temp_folder();
  write_text(folder + "/c.ply",
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
             "property float s\nproperty float t\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "0 0 0 255 0 0 0 0.25\n1 0 0 0 128 0 1 0\n0 1 0 1 2 3 0 1\n3 0 1 2\n");
  ImportReport report;
  Scene scene = read_ok(folder + "/c.ply", &report);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const ScenePrimitive& p = scene.meshes[0].primitives[0];
  const SceneAttribute* colour = p.find("COLOR_0");
  ASSERT_NE(colour, nullptr);
  EXPECT_EQ(colour->data.component_type, ComponentType::kUnsignedByte);
  EXPECT_EQ(colour->data.type, ElementType::kVec3);
  EXPECT_TRUE(colour->data.normalized);
  EXPECT_EQ(colour->data.bytes, (Bytes{255, 0, 0, 0, 128, 0, 1, 2, 3}));
  const SceneAttribute* uv = p.find("TEXCOORD_0");
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(floats(*uv)[1], 0.75f);
  EXPECT_EQ(floats(*uv)[5], 0.0f);
  for (const std::string& note : report.notes)
    EXPECT_EQ(note.find("red"), std::string::npos) << note;
}

TEST(SceneImport, PlyColourTypes) {
  const std::string folder = temp_folder();
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  write_text(folder + "/rgba.ply", head +
                                       "property uchar red\nproperty uchar green\n"
                                       "property uchar blue\nproperty uchar alpha\n" +
                                       faces +
                                       "0 0 0 1 2 3 4\n1 0 0 5 6 7 8\n0 1 0 9 10 11 12\n3 0 1 2\n");
  write_text(folder + "/float.ply",
             head + "property float red\nproperty float green\nproperty float blue\n" + faces +
                 "0 0 0 0.5 0.25 1\n1 0 0 0 0 0\n0 1 0 1 1 1\n3 0 1 2\n");
  ImportReport report;
  Scene rgba = read_ok(folder + "/rgba.ply", &report);
  const SceneAttribute* c = rgba.meshes.at(0).primitives.at(0).find("COLOR_0");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->data.type, ElementType::kVec4);
  EXPECT_EQ(c->data.bytes, (Bytes{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
  Scene f = read_ok(folder + "/float.ply", &report);
  c = f.meshes.at(0).primitives.at(0).find("COLOR_0");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->data.component_type, ComponentType::kFloat);
  EXPECT_FALSE(c->data.normalized);
  EXPECT_EQ(floats(*c)[0], 0.5f);
  EXPECT_EQ(floats(*c)[1], 0.25f);
}

TEST(SceneImport, SceneFromMeshRejectsInconsistentMeshes) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 3}};
  EXPECT_FALSE(scene_from_mesh(mesh, "bad").is_ok());
  mesh.triangles = {{0, 1, 2}};
  mesh.normals.binding = AttributeBinding::kPerVertex;
  mesh.normals.components = 3;
  mesh.normals.values = {0, 0, 1};
  EXPECT_FALSE(scene_from_mesh(mesh, "bad").is_ok());
  mesh.normals = MeshAttribute();
  Result<Scene> scene = scene_from_mesh(mesh, "ok");
  ASSERT_TRUE(scene.is_ok());
  EXPECT_EQ(scene.value().meshes[0].name, "ok");
  EXPECT_EQ(*scene.value().meshes[0].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(SceneImport, SameFileGivesEqualScenes) {
  const std::string path = shared_meshes() + "/stanford_dragon_vrip_res4.ply.gz";
  ImportReport r1, r2;
  Scene a = read_ok(path, &r1);
  Scene b = read_ok(path, &r2);
  EXPECT_TRUE(a == b);
  EXPECT_EQ(a.meshes.at(0).name, "stanford_dragon_vrip_res4");
}

}  // namespace
}  // namespace lodbake
