// read_gltf_scene(), read_resource() and weld_mesh_points(): the real assets
// of shared/data/assets against their MANIFEST.md, hand-made files for
// sparse accessors, KHR_mesh_quantization and EXT_meshopt_compression (built
// here with meshoptimizer's encoder), and URI confinement.
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "formats/support/file_io.h"
#include "lib/dracoio/draco_io.h"
#include "lib/meshio/mesh_import.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_points.h"

namespace lodbake {
namespace {

using Json = nlohmann::json;

const std::string kAssets = std::string(LODBAKE_TEST_SHARED_DATA) + "/assets";

std::string folder_of(const std::string& path) {
  return path.substr(0, path.find_last_of('/'));
}

Result<Scene> read_path(const std::string& path, ImportReport* report) {
  Result<Bytes> bytes = read_file(path);
  if (!bytes.is_ok()) return bytes.status();
  SceneResources resources;
  resources.folder = folder_of(path);
  return read_gltf_scene(bytes.value().data(), bytes.value().size(), resources, report);
}

Result<Scene> read_text(const std::string& text, ImportReport* report = nullptr,
                        const SceneResources& resources = SceneResources()) {
  ImportReport local;
  return read_gltf_scene(reinterpret_cast<const uint8_t*>(text.data()), text.size(), resources,
                         report != nullptr ? report : &local);
}

// With LODBAKE_REGENERATE_GOLDEN=1, a hand-made file becomes a seed of the
// fuzz_gltf_scene corpus (in LODBAKE_SOURCE_DIR, or this source tree).
void maybe_write_seed(const std::string& name, const std::string& text) {
  const char* regenerate = std::getenv("LODBAKE_REGENERATE_GOLDEN");
  if (regenerate == nullptr || std::string(regenerate) != "1") return;
  const char* source = std::getenv("LODBAKE_SOURCE_DIR");
  const std::string dir = std::string(source != nullptr ? source : LODBAKE_TEST_SOURCE_DIR) +
                          "/tests/fuzz/corpus/gltf_scene/";
  ASSERT_TRUE(write_file_atomic(dir + name, text).is_ok()) << dir + name;
}

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (uint32_t{bytes[i]} << 16) | (uint32_t{bytes[i + 1]} << 8) | bytes[i + 2];
    for (int s = 18; s >= 0; s -= 6)
      out.push_back(kTable[(v >> s) & 63]);
  }
  if (i < bytes.size()) {
    uint32_t v = uint32_t{bytes[i]} << 16;
    if (i + 1 < bytes.size()) v |= uint32_t{bytes[i + 1]} << 8;
    out.push_back(kTable[(v >> 18) & 63]);
    out.push_back(kTable[(v >> 12) & 63]);
    out.push_back(i + 1 < bytes.size() ? kTable[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

std::string data_uri(const std::vector<uint8_t>& bytes) {
  return "data:application/octet-stream;base64," + base64(bytes);
}

template <typename T>
void append(std::vector<uint8_t>* out, const std::vector<T>& values) {
  const size_t at = out->size();
  out->resize(at + values.size() * sizeof(T));
  std::memcpy(out->data() + at, values.data(), values.size() * sizeof(T));
}

template <typename T>
std::vector<T> values_of(const AccessorData& a) {
  std::vector<T> out(a.bytes.size() / sizeof(T));
  std::memcpy(out.data(), a.bytes.data(), out.size() * sizeof(T));
  return out;
}

// One row of shared/data/assets/MANIFEST.md.
struct ManifestRow {
  std::string file;
  uint64_t triangles = 0;
  size_t primitives = 0, materials = 0, nodes = 0;
  std::string attributes;
};

std::vector<ManifestRow> manifest() {
  std::ifstream in(kAssets + "/MANIFEST.md");
  std::vector<ManifestRow> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, 10, "| `assets/") != 0) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) {
      const size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    ManifestRow row;
    row.file = cells[0].substr(8, cells[0].size() - 9);  // `assets/X` -> X
    row.triangles = std::stoull(cells[1]);
    row.primitives = std::stoul(cells[2]);
    row.materials = std::stoul(cells[3]);
    row.nodes = std::stoul(cells[4]);
    row.attributes = cells[5];
    rows.push_back(row);
  }
  return rows;
}

TEST(GltfSceneReader, EveryAssetMatchesItsManifestRow) {
  const std::vector<ManifestRow> rows = manifest();
  ASSERT_EQ(rows.size(), 11u);
  for (const ManifestRow& row : rows) {
    SCOPED_TRACE(row.file);
    ImportReport report;
    Result<Scene> scene = read_path(kAssets + "/" + row.file, &report);
    ASSERT_TRUE(scene.is_ok()) << scene.status().message();
    const Scene& s = scene.value();
    uint64_t triangles = 0;
    size_t primitives = 0;
    std::set<std::string> semantics;
    for (const SceneMesh& m : s.meshes) {
      ASSERT_EQ(m.point_of_vertex.size(), m.primitives.size());
      for (const ScenePrimitive& p : m.primitives) {
        ++primitives;
        for (const SceneAttribute& a : p.attributes) {
          semantics.insert(a.semantic);
          EXPECT_EQ(a.data.bytes.size(), uint64_t{a.data.count} * a.data.element_size());
        }
        if (p.mode == PrimitiveMode::kTriangles) {
          triangles += p.indices ? p.indices->size() / 3 : p.vertex_count() / 3;
        }
      }
    }
    std::string attributes;
    for (const std::string& a : semantics)
      attributes += (attributes.empty() ? "" : ", ") + a;
    EXPECT_EQ(triangles, row.triangles);
    EXPECT_EQ(primitives, row.primitives);
    EXPECT_EQ(s.materials.is_array() ? s.materials.size() : 0u, row.materials);
    EXPECT_EQ(s.nodes.size(), row.nodes);
    EXPECT_EQ(attributes, row.attributes);
    // Decoded compression leaves no trace.
    for (const auto* list : {&s.extensions_used, &s.extensions_required}) {
      EXPECT_EQ(std::count(list->begin(), list->end(), "KHR_draco_mesh_compression"), 0);
    }
    EXPECT_EQ(report.format, row.file.substr(row.file.size() - 3) == "glb" ? "glb" : "gltf");
  }
}

TEST(GltfSceneReader, DuckGltfAndGlbAreTheSameScene) {
  ImportReport r1, r2;
  Result<Scene> gltf = read_path(kAssets + "/Duck/Duck.gltf", &r1);
  Result<Scene> glb = read_path(kAssets + "/Duck/Duck.glb", &r2);
  ASSERT_TRUE(gltf.is_ok()) << gltf.status().message();
  ASSERT_TRUE(glb.is_ok()) << glb.status().message();
  Scene a = std::move(gltf).value();
  Scene b = std::move(glb).value();
  ASSERT_EQ(a.images.size(), 1u);
  ASSERT_EQ(b.images.size(), 1u);
  // The .gltf keeps the image beside it, the .glb inside: only where it
  // lives differs, its bytes and type do not.
  EXPECT_EQ(a.images[0].uri, "DuckCM.png");
  EXPECT_EQ(b.images[0].uri, "");
  EXPECT_EQ(a.images[0].mime_type, "image/png");  // not in the .gltf: from the signature
  EXPECT_FALSE(a.images[0].bytes.empty());
  a.images[0].uri.clear();
  EXPECT_TRUE(a == b);
  EXPECT_TRUE(a.images == b.images);
  EXPECT_TRUE(a.nodes == b.nodes);
  EXPECT_TRUE(a.meshes == b.meshes);
  EXPECT_TRUE(r1.warnings.empty());
  // Camera, material and mesh carried; the camera node keeps its matrix.
  ASSERT_TRUE(a.cameras.is_array());
  EXPECT_EQ(a.cameras.size(), 1u);
  ASSERT_EQ(a.nodes.size(), 3u);
  EXPECT_EQ(a.nodes[1].camera, 0);
  EXPECT_TRUE(a.nodes[1].matrix.has_value());
  EXPECT_FALSE(a.nodes[1].translation.has_value());
  EXPECT_EQ(a.nodes[0].children, (std::vector<uint32_t>{2, 1}));
}

TEST(GltfSceneReader, LanternWarnsOnceAboutItsMissingImage) {
  ImportReport report;
  Result<Scene> scene = read_path(kAssets + "/Lantern/Lantern.gltf", &report);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("'Lantern_baseColor.png' is missing"), std::string::npos)
      << report.warnings[0];
  size_t missing = 0;
  for (const SceneImage& image : scene.value().images) {
    if (image.missing) {
      ++missing;
      EXPECT_EQ(image.uri, "Lantern_baseColor.png");
      EXPECT_TRUE(image.bytes.empty());
    } else {
      EXPECT_FALSE(image.bytes.empty());
    }
  }
  EXPECT_EQ(missing, 1u);
  EXPECT_EQ(scene.value().images.size(), 4u);
}

TEST(GltfSceneReader, BoxMetaDracoStreamsHaveTheDeclaredComponentTypes) {
  const std::string path = kAssets + "/BoxMetaDraco/BoxMetaDraco.gltf";
  Result<Bytes> bytes = read_file(path);
  ASSERT_TRUE(bytes.is_ok());
  const Json json = Json::parse(bytes.value().begin(), bytes.value().end());
  Result<Scene> scene = read_path(path, nullptr);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  const ScenePrimitive& prim = scene.value().meshes.at(0).primitives.at(0);
  const Json& declared = json["meshes"][0]["primitives"][0]["attributes"];
  ASSERT_EQ(prim.attributes.size(), declared.size());
  std::set<ComponentType> feature_types;
  for (const SceneAttribute& a : prim.attributes) {
    SCOPED_TRACE(a.semantic);
    const Json& accessor = json["accessors"][declared[a.semantic].get<size_t>()];
    EXPECT_EQ(static_cast<int>(a.data.component_type), accessor["componentType"].get<int>());
    EXPECT_EQ(a.data.count, 36u);  // Draco points, one per corner here
    if (a.semantic.compare(0, 11, "_FEATURE_ID") == 0) feature_types.insert(a.data.component_type);
  }
  EXPECT_EQ(feature_types,
            (std::set<ComponentType>{ComponentType::kUnsignedByte, ComponentType::kUnsignedShort,
                                     ComponentType::kFloat}));
  ASSERT_TRUE(prim.indices.has_value());
  EXPECT_EQ(prim.indices->size(), 36u);
  // The Draco extension is gone; EXT_mesh_features stays.
  ASSERT_TRUE(prim.extensions.is_object());
  EXPECT_FALSE(prim.extensions.contains("KHR_draco_mesh_compression"));
  EXPECT_TRUE(prim.extensions.contains("EXT_mesh_features"));
  EXPECT_TRUE(scene.value().extensions_required.empty());
  EXPECT_EQ(scene.value().extensions_used, std::vector<std::string>{"EXT_mesh_features"});
  // Feature id 0 counts faces: the two corners of one triangle share it.
  const std::vector<uint8_t> ids = values_of<uint8_t>(prim.find("_FEATURE_ID_0")->data);
  EXPECT_EQ(*std::max_element(ids.begin(), ids.end()), 11);
}

TEST(GltfSceneReader, SpheresAreOneMeshInstancedByThreeNodes) {
  Result<Scene> scene =
      read_path(kAssets + "/SpheresScaledInstances/spheres_scaled_instances.gltf", nullptr);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  const Scene& s = scene.value();
  ASSERT_EQ(s.meshes.size(), 1u);
  size_t users = 0;
  for (const SceneNode& n : s.nodes)
    users += n.mesh == 0 ? 1 : 0;
  EXPECT_EQ(users, 3u);
  ASSERT_TRUE(s.nodes[2].scale.has_value());
  EXPECT_EQ((*s.nodes[2].scale)[0], 3.0);
  EXPECT_FALSE(s.nodes[2].rotation.has_value());
  EXPECT_EQ((*s.nodes[3].scale)[0], static_cast<double>(0.1f));  // float32 precision
}

TEST(GltfSceneReader, SkinsAndAnimationsReferToSceneAccessors) {
  Result<Scene> scene = read_path(kAssets + "/Fox/Fox.gltf", nullptr);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  const Scene& s = scene.value();
  ASSERT_TRUE(s.skins.is_array());
  ASSERT_TRUE(s.animations.is_array());
  const size_t ibm = s.skins[0]["inverseBindMatrices"].get<size_t>();
  ASSERT_LT(ibm, s.accessors.size());
  EXPECT_EQ(s.accessors[ibm].type, ElementType::kMat4);
  EXPECT_EQ(s.accessors[ibm].count, s.skins[0]["joints"].size());
  std::set<size_t> used{ibm};
  for (const Json& animation : s.animations) {
    for (const Json& sampler : animation["samplers"]) {
      const size_t input = sampler["input"].get<size_t>();
      const size_t output = sampler["output"].get<size_t>();
      ASSERT_LT(input, s.accessors.size());
      ASSERT_LT(output, s.accessors.size());
      EXPECT_EQ(s.accessors[input].type, ElementType::kScalar);
      used.insert(input);
      used.insert(output);
    }
  }
  // Every scene accessor is referred to, each once in the numbering.
  EXPECT_EQ(used.size(), s.accessors.size());
}

// A quad: 4 float positions, then what each test adds.
std::vector<float> quad_positions() {
  return {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
}

TEST(GltfSceneReader, SparseAccessorsAreMadeDense) {
  std::vector<uint8_t> buffer;
  append(&buffer, quad_positions());                      // 0..47
  append(&buffer, std::vector<uint16_t>{1, 3});           // 48..51 sparse indices
  append(&buffer, std::vector<float>{5, 5, 5, 7, 7, 7});  // 52..75 sparse values
  const std::string text = R"({"asset":{"version":"2.0"},
    "buffers":[{"byteLength":76,"uri":")" +
                           data_uri(buffer) + R"("}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":4},
                   {"buffer":0,"byteOffset":52,"byteLength":24}],
    "accessors":[
      {"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","sparse":{"count":2,
        "indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":2}}},
      {"componentType":5126,"count":4,"type":"VEC3","sparse":{"count":2,
        "indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":2}}}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":0},
                             {"attributes":{"POSITION":1},"mode":0}]}]})";
  maybe_write_seed("sparse.gltf", text);
  Result<Scene> scene = read_text(text);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  const SceneMesh& mesh = scene.value().meshes.at(0);
  EXPECT_EQ(values_of<float>(mesh.primitives[0].attributes[0].data),
            (std::vector<float>{0, 0, 0, 5, 5, 5, 1, 1, 0, 7, 7, 7}));
  EXPECT_EQ(values_of<float>(mesh.primitives[1].attributes[0].data),
            (std::vector<float>{0, 0, 0, 5, 5, 5, 0, 0, 0, 7, 7, 7}));
  EXPECT_FALSE(mesh.primitives[0].indices.has_value());
  EXPECT_EQ(mesh.primitives[0].mode, PrimitiveMode::kPoints);
  // Shared points: (5,5,5), (7,7,7) and (0,0,0) are shared by both primitives.
  EXPECT_EQ(mesh.point_count, 4u);
  EXPECT_EQ(mesh.point_of_vertex[1], (std::vector<uint32_t>{0, 1, 0, 3}));

  // Sparse indices that do not increase are refused.
  std::string bad = text;
  std::vector<uint8_t> swapped = buffer;
  std::swap(swapped[48], swapped[50]);
  bad.replace(bad.find(data_uri(buffer)), data_uri(buffer).size(), data_uri(swapped));
  Result<Scene> refused = read_text(bad);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(refused.status().message().find("sparse"), std::string::npos);
}

TEST(GltfSceneReader, QuantizedStreamsKeepTheirIntegerTypes) {
  // POSITION as SHORT VEC3 with an 8-byte stride, NORMAL as normalized BYTE
  // VEC3 with a 4-byte stride, TEXCOORD_0 as normalized UNSIGNED_SHORT.
  std::vector<uint8_t> buffer;
  append(&buffer, std::vector<int16_t>{0, 0, 0, 9, 100, 0, 0, 9, 100, 100, 0, 9, -3, 100, 0, 9});
  append(&buffer, std::vector<int8_t>{0, 0, 127, 1, 0, 0, 127, 1, 0, 0, 127, 1, 0, 0, -127, 1});
  append(&buffer, std::vector<uint16_t>{0, 0, 65535, 0, 65535, 65535, 0, 65535});
  append(&buffer, std::vector<uint8_t>{0, 1, 2, 0, 2, 3});
  const std::string text = R"({"asset":{"version":"2.0"},
    "extensionsUsed":["KHR_mesh_quantization"],"extensionsRequired":["KHR_mesh_quantization"],
    "buffers":[{"byteLength":70,"uri":")" +
                           data_uri(buffer) + R"("}],
    "bufferViews":[{"buffer":0,"byteLength":32,"byteStride":8},
                   {"buffer":0,"byteOffset":32,"byteLength":16,"byteStride":4},
                   {"buffer":0,"byteOffset":48,"byteLength":16},
                   {"buffer":0,"byteOffset":64,"byteLength":6}],
    "accessors":[{"bufferView":0,"componentType":5122,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5120,"normalized":true,"count":4,"type":"VEC3"},
                 {"bufferView":2,"componentType":5123,"normalized":true,"count":4,"type":"VEC2"},
                 {"bufferView":3,"componentType":5121,"count":6,"type":"SCALAR"}],
    "meshes":[{"primitives":[{"attributes":{"TEXCOORD_0":2,"POSITION":0,"NORMAL":1},
                              "indices":3}]}],
    "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
  maybe_write_seed("quantized.gltf", text);
  Result<Scene> scene = read_text(text);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  const ScenePrimitive& p = scene.value().meshes.at(0).primitives.at(0);
  ASSERT_EQ(p.attributes.size(), 3u);
  EXPECT_EQ(p.attributes[0].semantic, "NORMAL");  // sorted by semantic
  EXPECT_EQ(p.attributes[1].semantic, "POSITION");
  EXPECT_EQ(p.attributes[2].semantic, "TEXCOORD_0");
  const AccessorData& pos = p.find("POSITION")->data;
  EXPECT_EQ(pos.component_type, ComponentType::kShort);
  EXPECT_FALSE(pos.normalized);
  EXPECT_EQ(values_of<int16_t>(pos),
            (std::vector<int16_t>{0, 0, 0, 100, 0, 0, 100, 100, 0, -3, 100, 0}));
  const AccessorData& normal = p.find("NORMAL")->data;
  EXPECT_EQ(normal.component_type, ComponentType::kByte);
  EXPECT_TRUE(normal.normalized);
  EXPECT_EQ(values_of<int8_t>(normal),
            (std::vector<int8_t>{0, 0, 127, 0, 0, 127, 0, 0, 127, 0, 0, -127}));
  EXPECT_EQ(p.find("TEXCOORD_0")->data.component_type, ComponentType::kUnsignedShort);
  EXPECT_EQ(*p.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(scene.value().extensions_required, std::vector<std::string>{"KHR_mesh_quantization"});
  EXPECT_EQ(scene.value().default_scene, 0);
}

// The same triangle list twice: plainly, and with both bufferViews
// compressed by meshoptimizer's encoder into buffer 0 while the views point
// into a fallback buffer that has no data.
TEST(GltfSceneReader, MeshoptCompressedFileReadsLikeThePlainOne) {
  std::vector<float> positions;
  std::vector<uint32_t> triangles;
  for (uint32_t y = 0; y < 6; ++y) {
    for (uint32_t x = 0; x < 6; ++x) {
      positions.insert(positions.end(), {float(x), float(y), float((x * y) % 3)});
      if (x < 5 && y < 5) {
        const uint32_t v = y * 6 + x;
        triangles.insert(triangles.end(), {v, v + 1, v + 7, v, v + 7, v + 6});
      }
    }
  }
  const size_t vertex_count = positions.size() / 3;
  std::vector<uint8_t> vtx(meshopt_encodeVertexBufferBound(vertex_count, 12));
  vtx.resize(
      meshopt_encodeVertexBuffer(vtx.data(), vtx.size(), positions.data(), vertex_count, 12));
  std::vector<uint8_t> idx(meshopt_encodeIndexBufferBound(triangles.size(), vertex_count));
  idx.resize(meshopt_encodeIndexBuffer(idx.data(), idx.size(), triangles.data(), triangles.size()));
  // The encoder may rotate a triangle's corners (winding kept); the plain
  // file holds the order it gives back.
  ASSERT_EQ(meshopt_decodeIndexBuffer(triangles.data(), triangles.size(), idx.data(), idx.size()),
            0);
  std::vector<uint16_t> indices16(triangles.begin(), triangles.end());
  std::vector<uint8_t> plain;
  append(&plain, positions);
  append(&plain, indices16);
  const size_t pos_bytes = positions.size() * 4, idx_bytes = indices16.size() * 2;

  ASSERT_GT(vtx.size(), 0u);
  ASSERT_GT(idx.size(), 0u);
  std::vector<uint8_t> packed = vtx;
  while (packed.size() % 4 != 0)
    packed.push_back(0);
  const size_t idx_offset = packed.size();
  packed.insert(packed.end(), idx.begin(), idx.end());

  const std::string tail = R"("accessors":[
      {"bufferView":0,"componentType":5126,"count":)" +
                           std::to_string(vertex_count) +
                           R"(,"type":"VEC3"},
      {"bufferView":1,"componentType":5123,"count":)" +
                           std::to_string(triangles.size()) +
                           R"(,"type":"SCALAR"}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
  const std::string plain_text = R"({"asset":{"version":"2.0"},
    "buffers":[{"byteLength":)" + std::to_string(plain.size()) +
                                 R"(,"uri":")" + data_uri(plain) + R"("}],
    "bufferViews":[{"buffer":0,"byteLength":)" +
                                 std::to_string(pos_bytes) +
                                 R"(,"byteStride":12},
                   {"buffer":0,"byteOffset":)" +
                                 std::to_string(pos_bytes) + R"(,"byteLength":)" +
                                 std::to_string(idx_bytes) + R"(}],)" + tail;
  const std::string meshopt_text =
      R"({"asset":{"version":"2.0"},
    "extensionsUsed":["EXT_meshopt_compression"],"extensionsRequired":["EXT_meshopt_compression"],
    "buffers":[{"byteLength":)" +
      std::to_string(packed.size()) + R"(,"uri":")" + data_uri(packed) + R"("},
               {"byteLength":)" +
      std::to_string(plain.size()) +
      R"(,"extensions":{"EXT_meshopt_compression":{"fallback":true}}}],
    "bufferViews":[
      {"buffer":1,"byteLength":)" +
      std::to_string(pos_bytes) + R"(,"byteStride":12,"extensions":{"EXT_meshopt_compression":
        {"buffer":0,"byteLength":)" +
      std::to_string(vtx.size()) + R"(,"byteStride":12,"count":)" + std::to_string(vertex_count) +
      R"(,"mode":"ATTRIBUTES"}}},
      {"buffer":1,"byteOffset":)" +
      std::to_string(pos_bytes) + R"(,"byteLength":)" + std::to_string(idx_bytes) +
      R"(,"extensions":{"EXT_meshopt_compression":
        {"buffer":0,"byteOffset":)" +
      std::to_string(idx_offset) + R"(,"byteLength":)" + std::to_string(idx.size()) +
      R"(,"byteStride":2,"count":)" + std::to_string(triangles.size()) +
      R"(,"mode":"TRIANGLES"}}}],)" + tail;
  maybe_write_seed("meshopt.gltf", meshopt_text);
  Result<Scene> a = read_text(plain_text);
  Result<Scene> b = read_text(meshopt_text);
  ASSERT_TRUE(a.is_ok()) << a.status().message();
  ASSERT_TRUE(b.is_ok()) << b.status().message();
  EXPECT_TRUE(a.value() == b.value());
  EXPECT_TRUE(b.value().extensions_used.empty());
  EXPECT_EQ(values_of<float>(b.value().meshes[0].primitives[0].attributes[0].data), positions);
  EXPECT_EQ(*b.value().meshes[0].primitives[0].indices, triangles);
  // The merged-mesh reader reads it too (it used to say "buffer 1 has no uri").
  ImportReport report;
  Result<TriangleMesh> merged = parse_gltf(reinterpret_cast<const uint8_t*>(meshopt_text.data()),
                                           meshopt_text.size(), &report);
  ASSERT_TRUE(merged.is_ok()) << merged.status().message();
  EXPECT_EQ(merged.value().triangles.size(), triangles.size() / 3);

  // A truncated compressed stream is an error, not a crash.
  std::string truncated = meshopt_text;
  const std::string length = R"("byteLength":)" + std::to_string(vtx.size()) + ",";
  truncated.replace(truncated.find(length), length.size(),
                    R"("byteLength":)" + std::to_string(vtx.size() / 2) + ",");
  Result<Scene> bad = read_text(truncated);
  ASSERT_FALSE(bad.is_ok());
  EXPECT_NE(bad.status().message().find("meshoptimizer"), std::string::npos)
      << bad.status().message();
}

// A temporary folder with a buffer file, removed at the end.
class UriTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/lodbake_uri_XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    root_ = pattern;
    ASSERT_EQ(std::system(("mkdir -p '" + root_ + "/asset'").c_str()), 0);
    std::vector<uint8_t> quad;
    append(&quad, quad_positions());
    ASSERT_TRUE(write_file_atomic(root_ + "/asset/my quad.bin", quad).is_ok());
    ASSERT_TRUE(write_file_atomic(root_ + "/outside.bin", quad).is_ok());
  }
  void TearDown() override {
    if (!root_.empty()) std::system(("rm -rf '" + root_ + "'").c_str());
  }
  SceneResources in_asset(bool allow = false) const {
    SceneResources r;
    r.folder = root_ + "/asset";
    r.allow_outside = allow;
    return r;
  }
  std::string gltf_with(const std::string& uri) const {
    return R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":48,"uri":")" + uri + R"("}],
      "bufferViews":[{"buffer":0,"byteLength":48}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":0}]}]})";
  }
  std::string root_;
};

TEST_F(UriTest, RelativeUrisArePercentDecodedAndRead) {
  std::string resolved;
  Result<Bytes> bytes = read_resource(in_asset(), "my%20quad.bin", &resolved);
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  EXPECT_EQ(bytes.value().size(), 48u);
  EXPECT_EQ(resolved, root_ + "/asset/my quad.bin");
  EXPECT_TRUE(read_resource(in_asset(), "./sub/../my%20quad.bin").is_ok());
  Result<Scene> scene = read_text(gltf_with("my%20quad.bin"), nullptr, in_asset());
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  EXPECT_EQ(values_of<float>(scene.value().meshes[0].primitives[0].attributes[0].data),
            quad_positions());
}

TEST_F(UriTest, EscapesFromTheFolderAndSchemesAreRefused) {
  for (const std::string& uri :
       {root_ + "/outside.bin", std::string("../outside.bin"), std::string("%2e%2e/outside.bin"),
        std::string("a/../../outside.bin"), std::string("http://example.com/x.bin"),
        std::string("file:///etc/passwd"), std::string("file:outside.bin")}) {
    SCOPED_TRACE(uri);
    Result<Bytes> bytes = read_resource(in_asset(), uri);
    ASSERT_FALSE(bytes.is_ok());
    EXPECT_EQ(bytes.status().kind(), ErrorKind::kUnsupported);
    EXPECT_NE(bytes.status().message().find(uri.substr(0, 20)), std::string::npos)
        << bytes.status().message();
    Result<Scene> scene = read_text(gltf_with(uri), nullptr, in_asset());
    ASSERT_FALSE(scene.is_ok());
    EXPECT_EQ(scene.status().kind(), ErrorKind::kUnsupported);
  }
  Result<Bytes> absolute = read_resource(in_asset(), root_ + "/outside.bin");
  EXPECT_NE(absolute.status().message().find("--allow-outside"), std::string::npos);
  // --allow-outside lifts the folder rule, not the scheme rule.
  EXPECT_TRUE(read_resource(in_asset(true), "../outside.bin").is_ok());
  EXPECT_TRUE(read_resource(in_asset(true), root_ + "/outside.bin").is_ok());
  EXPECT_FALSE(read_resource(in_asset(true), "http://example.com/x.bin").is_ok());
}

TEST_F(UriTest, MemoryOnlyRefusesFilesAndAMissingBufferIsAnError) {
  Result<Scene> memory = read_text(gltf_with("my%20quad.bin"));
  ASSERT_FALSE(memory.is_ok());
  EXPECT_EQ(memory.status().kind(), ErrorKind::kUnsupported);
  EXPECT_NE(memory.status().message().find(
                "the asset is read from memory; external file 'my quad.bin' cannot be resolved"),
            std::string::npos)
      << memory.status().message();
  Result<Scene> missing = read_text(gltf_with("absent.bin"), nullptr, in_asset());
  ASSERT_FALSE(missing.is_ok());
  EXPECT_EQ(missing.status().kind(), ErrorKind::kIo);
  EXPECT_NE(missing.status().message().find("buffer 0: file 'absent.bin'"), std::string::npos)
      << missing.status().message();
  EXPECT_FALSE(read_resource(in_asset(), "bad%zzescape.bin").is_ok());
}

TEST(GltfSceneReader, UnknownRequiredExtensionIsUnsupported) {
  const std::string text = R"({"asset":{"version":"2.0"},
    "extensionsUsed":["EXT_fancy_geometry"],"extensionsRequired":["EXT_fancy_geometry"]})";
  Result<Scene> scene = read_text(text);
  ASSERT_FALSE(scene.is_ok());
  EXPECT_EQ(scene.status().kind(), ErrorKind::kUnsupported);
  EXPECT_NE(scene.status().message().find("EXT_fancy_geometry"), std::string::npos);
}

TEST(GltfSceneReader, ExtensionsReferringToBufferDataAreDroppedWithAWarning) {
  const std::string text = R"({"asset":{"version":"2.0","copyright":"x","generator":"g"},
    "extensionsUsed":["EXT_structural_metadata","KHR_lights_punctual","VENDOR_blob"],
    "extensions":{"EXT_structural_metadata":{"propertyTables":[{"values":0}]},
                  "KHR_lights_punctual":{"lights":[{"type":"point"}]}},
    "materials":[{"extensions":{"VENDOR_blob":{"bufferView":0}}}]})";
  ImportReport report;
  Result<Scene> scene = read_text(text, &report);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  const Scene& s = scene.value();
  EXPECT_EQ(report.warnings.size(), 2u);
  EXPECT_FALSE(s.extensions.contains("EXT_structural_metadata"));
  EXPECT_TRUE(s.extensions.contains("KHR_lights_punctual"));
  EXPECT_FALSE(s.materials[0]["extensions"].contains("VENDOR_blob"));
  EXPECT_EQ(s.extensions_used, std::vector<std::string>{"KHR_lights_punctual"});
  EXPECT_EQ(s.asset, (Json{{"copyright", "x"}}));
  EXPECT_EQ(s.generator, "g");
}

TEST(GltfSceneReader, InstancingAttributesBecomeSceneAccessors) {
  std::vector<uint8_t> buffer;
  append(&buffer, quad_positions());
  const std::string text = R"({"asset":{"version":"2.0"},
    "extensionsUsed":["EXT_mesh_gpu_instancing"],
    "buffers":[{"byteLength":48,"uri":")" +
                           data_uri(buffer) + R"("}],
    "bufferViews":[{"buffer":0,"byteLength":48}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":0,"componentType":5126,"count":2,"type":"VEC3","byteOffset":24}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":0}]}],
    "nodes":[{"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":
              {"attributes":{"TRANSLATION":1,"SCALE":1}}}}]})";
  maybe_write_seed("instancing.gltf", text);
  ImportReport report;
  Result<Scene> scene = read_text(text, &report);
  ASSERT_TRUE(scene.is_ok()) << scene.status().message();
  const Scene& s = scene.value();
  EXPECT_TRUE(report.warnings.empty());
  ASSERT_EQ(s.accessors.size(), 1u);  // accessor 1, once for both uses
  EXPECT_EQ(s.accessors[0].count, 2u);
  EXPECT_EQ(s.nodes[0].extensions["EXT_mesh_gpu_instancing"]["attributes"],
            (Json{{"SCALE", 0}, {"TRANSLATION", 0}}));
}

TEST(GltfSceneReader, CyclesAndSharedChildrenAreRefused) {
  for (const std::string nodes :
       {R"([{"children":[1]},{"children":[0]}])", R"([{"children":[2]},{"children":[2]},{}])"}) {
    Result<Scene> scene = read_text(R"({"asset":{"version":"2.0"},"nodes":)" + nodes + "}");
    ASSERT_FALSE(scene.is_ok());
    EXPECT_EQ(scene.status().kind(), ErrorKind::kInvalidInput);
  }
}

TEST(GltfSceneReader, DecodedSizeIsBounded) {
  // 2^30 zero elements without a bufferView: refused by the budget, not allocated.
  const std::string text = R"({"asset":{"version":"2.0"},
    "accessors":[{"componentType":5126,"count":1073741824,"type":"VEC3"}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":0}]}]})";
  Result<Scene> scene = read_text(text);
  ASSERT_FALSE(scene.is_ok());
  EXPECT_NE(scene.status().message().find("limit"), std::string::npos) << scene.status().message();
}

TEST(ScenePoints, VerticesWithEqualPositionBytesShareAPoint) {
  auto stream = [](std::vector<float> xyz) {
    SceneAttribute a;
    a.semantic = "POSITION";
    a.data.type = ElementType::kVec3;
    a.data.count = static_cast<uint32_t>(xyz.size() / 3);
    append(&a.data.bytes, xyz);
    return a;
  };
  SceneMesh mesh;
  mesh.primitives.resize(3);
  mesh.primitives[0].attributes = {stream({0, 0, 0, 1, 0, 0, 0, 0, 0})};
  mesh.primitives[1].attributes = {stream({1, 0, 0, -0.0f, 0, 0, 2, 2, 2})};
  weld_mesh_points(&mesh);  // primitive 2 has no POSITION
  EXPECT_EQ(mesh.point_count, 4u);
  ASSERT_EQ(mesh.point_of_vertex.size(), 3u);
  EXPECT_EQ(mesh.point_of_vertex[0], (std::vector<uint32_t>{0, 1, 0}));
  EXPECT_EQ(mesh.point_of_vertex[1], (std::vector<uint32_t>{1, 2, 3}));  // -0 is not +0
  EXPECT_TRUE(mesh.point_of_vertex[2].empty());
}

// weld_mesh_points() written the plain way: an ordered map from the
// element's bytes (zero-padded to 16), component type and normalization to
// the first-seen point number.
void reference_points(const SceneMesh& mesh, std::vector<std::vector<uint32_t>>* points,
                      uint32_t* count) {
  using Key = std::tuple<std::array<uint8_t, 16>, ComponentType, bool>;
  std::map<Key, uint32_t> seen;
  points->assign(mesh.primitives.size(), {});
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const SceneAttribute* position = mesh.primitives[p].find("POSITION");
    if (position == nullptr) continue;
    const AccessorData& d = position->data;
    const uint32_t size = d.element_size();
    if (size > 16 || d.bytes.size() < uint64_t{d.count} * size) continue;
    for (uint32_t v = 0; v < d.count; ++v) {
      Key key{{}, d.component_type, d.normalized};
      std::memcpy(std::get<0>(key).data(), d.bytes.data() + size_t{v} * size, size);
      const auto found = seen.emplace(key, static_cast<uint32_t>(seen.size()));
      (*points)[p].push_back(found.first->second);
    }
  }
  *count = static_cast<uint32_t>(seen.size());
}

TEST(ScenePoints, MatchTheReferenceOnEveryAssetAndOddStreams) {
  std::vector<SceneMesh> meshes;
  for (const ManifestRow& row : manifest()) {
    ImportReport report;
    Result<Scene> scene = read_path(kAssets + "/" + row.file, &report);
    ASSERT_TRUE(scene.is_ok()) << row.file << ": " << scene.status().message();
    for (SceneMesh& m : scene.value().meshes)
      meshes.push_back(std::move(m));
  }
  // Streams that differ only in what a byte comparison sees: a VEC4 whose
  // padding equals a VEC3's, the same bytes as int16 and as normalized
  // int16, NaN payloads, -0 and +0, and a primitive without POSITION.
  auto stream = [](ElementType type, ComponentType component, bool normalized,
                   std::vector<uint8_t> bytes) {
    SceneAttribute a;
    a.semantic = "POSITION";
    a.data.type = type;
    a.data.component_type = component;
    a.data.normalized = normalized;
    a.data.count = static_cast<uint32_t>(bytes.size() / a.data.element_size());
    a.data.bytes = std::move(bytes);
    return a;
  };
  auto floats = [](std::vector<float> values) {
    std::vector<uint8_t> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
  };
  const float nan_a = std::nanf("1"), nan_b = std::nanf("2");
  SceneMesh odd;
  odd.primitives.resize(6);
  odd.primitives[0].attributes = {stream(ElementType::kVec3, ComponentType::kFloat, false,
                                         floats({1, 2, 3, nan_a, 0, 0, -0.0f, 0, 0, 1, 2, 3}))};
  odd.primitives[1].attributes = {stream(ElementType::kVec4, ComponentType::kFloat, false,
                                         floats({1, 2, 3, 0, nan_b, 0, 0, 0, 0, 0, 0, 0}))};
  odd.primitives[2].attributes = {stream(ElementType::kVec3, ComponentType::kShort, false,
                                         {1, 0, 2, 0, 3, 0, 1, 0, 2, 0, 3, 0})};
  odd.primitives[3].attributes = {
      stream(ElementType::kVec3, ComponentType::kShort, true, {1, 0, 2, 0, 3, 0})};
  odd.primitives[5].attributes = {stream(ElementType::kVec3, ComponentType::kFloat, false,
                                         floats({nan_a, 0, 0, 0, 0, 0, 1, 2, 3}))};
  const size_t odd_index = meshes.size();
  meshes.push_back(odd);
  // A mesh big enough to make the table wrap and collide.
  SceneMesh grid;
  grid.primitives.resize(2);
  std::vector<float> xyz;
  for (int i = 0; i < 300; ++i)
    for (int j = 0; j < 300; ++j)
      xyz.insert(xyz.end(), {float(i % 17), float(j), float((i * j) % 5)});
  grid.primitives[0].attributes = {
      stream(ElementType::kVec3, ComponentType::kFloat, false, floats(xyz))};
  std::reverse(xyz.begin(), xyz.end());
  grid.primitives[1].attributes = {
      stream(ElementType::kVec3, ComponentType::kFloat, false, floats(xyz))};
  meshes.push_back(grid);
  ASSERT_GE(meshes.size(), 15u);
  for (size_t m = 0; m < meshes.size(); ++m) {
    SCOPED_TRACE("mesh " + std::to_string(m));
    std::vector<std::vector<uint32_t>> expected;
    uint32_t expected_count = 0;
    reference_points(meshes[m], &expected, &expected_count);
    weld_mesh_points(&meshes[m]);
    EXPECT_EQ(meshes[m].point_count, expected_count);
    EXPECT_EQ(meshes[m].point_of_vertex, expected);
  }
  // The odd streams: VEC3 (1,2,3) and its padded VEC4 are one point; NaN
  // payloads, -0, int16 and normalized int16 are each their own.
  EXPECT_EQ(meshes[odd_index].point_of_vertex[0], (std::vector<uint32_t>{0, 1, 2, 0}));
  EXPECT_EQ(meshes[odd_index].point_of_vertex[1], (std::vector<uint32_t>{0, 3, 4}));
}

TEST(GltfMergedReader, DuckGltfWithItsBinReadsThroughItsFolder) {
  ImportReport r1, r2;
  Result<TriangleMesh> gltf = import_mesh_file(kAssets + "/Duck/Duck.gltf", &r1);
  Result<TriangleMesh> glb = import_mesh_file(kAssets + "/Duck/Duck.glb", &r2);
  ASSERT_TRUE(gltf.is_ok()) << gltf.status().message();
  ASSERT_TRUE(glb.is_ok()) << glb.status().message();
  // The same mesh, to the bit: both flatten the same scene, whose node
  // transforms are read at float32 precision however many digits the JSON
  // prints.
  EXPECT_EQ(gltf.value(), glb.value());
  EXPECT_EQ(gltf.value().triangles.size(), 4212u);
  // Memory only, the same bytes are refused.
  Result<Bytes> bytes = read_file(kAssets + "/Duck/Duck.gltf");
  ASSERT_TRUE(bytes.is_ok());
  const SceneResources memory;
  Result<TriangleMesh> refused = import_mesh("Duck.gltf", bytes.value(), &r1, &memory);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kUnsupported);
}

}  // namespace
}  // namespace lodbake
