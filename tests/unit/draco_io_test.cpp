// Tests of lib/dracoio: glTF/GLB import (scene choice, transforms, welding,
// notes, hostile input), Draco .drc import and GLB export (round trip,
// determinism). Golden files under tests/data/gltf/ are refreshed with
// LODBAKE_REGENERATE_GOLDEN=1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "draco/compression/encode.h"
#include "draco/core/encoder_buffer.h"
#include "draco/io/gltf_encoder.h"
#include "draco/point_cloud/point_cloud_builder.h"
#include "formats/support/file_io.h"
#include "formats/support/version.h"
#include "lib/dracoio/draco_convert.h"
#include "lib/dracoio/draco_io.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using Json = nlohmann::json;

using testing_util::env_or;
using testing_util::expect_error;
using testing_util::has_note;
using testing_util::read_bytes;
using testing_util::text_bytes;

std::string gltf_data_dir() {
  return env_or("LODBAKE_SOURCE_DIR", LODBAKE_TEST_SOURCE_DIR) + "/tests/data/gltf/";
}

Bytes read_data(const std::string& name) {
  return read_bytes(gltf_data_dir() + name);
}

Result<TriangleMesh> gltf(const Bytes& b, ImportReport* report = nullptr) {
  return parse_gltf(b.data(), b.size(), report);
}
Result<TriangleMesh> gltf(const std::string& s, ImportReport* report = nullptr) {
  return gltf(text_bytes(s), report);
}

void put_u32(Bytes* out, uint32_t v) {
  for (int i = 0; i < 4; ++i)
    out->push_back(static_cast<uint8_t>(v >> (8 * i)));
}

// A GLB container around `json` and an optional BIN chunk.
Bytes make_glb(const std::string& json, const Bytes& bin) {
  std::string j = json;
  while (j.size() % 4 != 0)
    j += ' ';
  Bytes b = bin;
  while (b.size() % 4 != 0)
    b.push_back(0);
  Bytes out;
  put_u32(&out, 0x46546C67);
  put_u32(&out, 2);
  put_u32(&out, static_cast<uint32_t>(12 + 8 + j.size() + (bin.empty() ? 0 : 8 + b.size())));
  put_u32(&out, static_cast<uint32_t>(j.size()));
  put_u32(&out, 0x4E4F534A);
  out.insert(out.end(), j.begin(), j.end());
  if (!bin.empty()) {
    put_u32(&out, static_cast<uint32_t>(b.size()));
    put_u32(&out, 0x004E4942);
    out.insert(out.end(), b.begin(), b.end());
  }
  return out;
}

Json scene_json() {
  const Bytes b = read_data("instanced_scene.gltf");
  return Json::parse(b.begin(), b.end());
}

// The quad's 140-byte buffer of instanced_scene.gltf.
Bytes scene_buffer() {
  const std::string uri = scene_json()["buffers"][0]["uri"];
  const std::string b64 = uri.substr(uri.find(',') + 1);
  Bytes out;
  uint32_t acc = 0;
  int bits = 0;
  for (char c : b64) {
    const char* p =
        std::strchr("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/", c);
    if (c == '=' || p == nullptr) break;
    acc = (acc << 6) | static_cast<uint32_t>(p -
                                             "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopq"
                                             "rstuvwxyz0123456789+/");
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<uint8_t>(acc >> bits));
    }
  }
  return out;
}

// The same asset as a GLB with the buffer in the BIN chunk.
Bytes scene_as_glb(Json j) {
  j["buffers"][0].erase("uri");
  return make_glb(j.dump(), scene_buffer());
}

// Resolves attribute `a` of `mesh` at corner k of triangle t.
std::vector<float> corner_value(const TriangleMesh& mesh, const MeshAttribute& a, size_t t, int k) {
  const uint32_t i =
      a.binding == AttributeBinding::kPerCorner ? a.corners[t][k] : mesh.triangles[t][k];
  return std::vector<float>(a.values.begin() + i * a.components,
                            a.values.begin() + (i + 1) * a.components);
}

// True when every triangle of `expected` appears in `actual` (Draco may
// reorder triangles and rotate their corners) with corner positions, and
// normals when both carry them, equal within `tolerance`.
bool same_triangles_any_order(const TriangleMesh& actual, const TriangleMesh& expected,
                              float tolerance) {
  if (actual.triangles.size() != expected.triangles.size()) return false;
  auto close = [&](const std::vector<float>& a, const std::vector<float>& b) {
    for (size_t i = 0; i < a.size(); ++i) {
      if (std::fabs(a[i] - b[i]) > tolerance) return false;
    }
    return true;
  };
  auto pos = [](const TriangleMesh& m, size_t t, int k) {
    const Vec3f& p = m.positions[m.triangles[t][k]];
    return std::vector<float>{p[0], p[1], p[2]};
  };
  const bool normals = actual.normals.present() && expected.normals.present();
  for (size_t e = 0; e < expected.triangles.size(); ++e) {
    bool found = false;
    for (size_t a = 0; a < actual.triangles.size() && !found; ++a) {
      for (int s = 0; s < 3 && !found; ++s) {
        bool all = true;
        for (int k = 0; k < 3 && all; ++k) {
          all = close(pos(actual, a, (k + s) % 3), pos(expected, e, k)) &&
                (!normals || close(corner_value(actual, actual.normals, a, (k + s) % 3),
                                   corner_value(expected, expected.normals, e, k)));
        }
        found = all;
      }
    }
    if (!found) return false;
  }
  return true;
}

// A unit cube: vertex x + 2y + 4z at (x, y, z); flat normals per corner (one
// value per face); texcoords per vertex, exactly representable after the
// v -> 1 - v flips of export and import.
TriangleMesh cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.positions.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
  }
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  m.normals.binding = AttributeBinding::kPerCorner;
  m.normals.components = 3;
  m.normals.values = {0, 0, -1, 0, 0, 1, 0, -1, 0, 0, 1, 0, -1, 0, 0, 1, 0, 0};
  for (uint32_t t = 0; t < 12; ++t)
    m.normals.corners.push_back({t / 2, t / 2, t / 2});
  m.texcoords.binding = AttributeBinding::kPerVertex;
  m.texcoords.components = 2;
  for (const Vec3f& p : m.positions) {
    m.texcoords.values.push_back(0.25f * p[0] + 0.5f * p[2]);
    m.texcoords.values.push_back(0.5f * p[1]);
  }
  return m;
}

void maybe_regenerate(const std::string& path, const Bytes& bytes) {
  if (env_or("LODBAKE_REGENERATE_GOLDEN", "0") != "1") return;
  ASSERT_TRUE(write_file_atomic(path, bytes).is_ok()) << path;
}

std::string corpus_dir() {
  return env_or("LODBAKE_SOURCE_DIR", LODBAKE_TEST_SOURCE_DIR) + "/tests/fuzz/corpus/";
}

Bytes draco_compressed_cube_glb() {
  auto dm = dracoio::to_draco_mesh(cube());
  EXPECT_TRUE(dm.is_ok());
  dm.value()->SetCompressionEnabled(true);
  draco::GltfEncoder encoder;
  draco::EncoderBuffer buffer;
  EXPECT_TRUE(encoder.EncodeToBuffer(*dm.value(), &buffer).ok());
  return Bytes(buffer.data(), buffer.data() + buffer.size());
}

Bytes encode_drc(const TriangleMesh& mesh) {
  auto dm = dracoio::to_draco_mesh(mesh);
  EXPECT_TRUE(dm.is_ok());
  draco::Encoder encoder;
  draco::EncoderBuffer buffer;
  EXPECT_TRUE(encoder.EncodeMeshToBuffer(*dm.value(), &buffer).ok());
  return Bytes(buffer.data(), buffer.data() + buffer.size());
}

TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

// ---------------------------------------------------------------- glTF import

TEST(GltfImport, DefaultSceneWithComposedTransformsAndInstancing) {
  ImportReport report;
  auto r = gltf(read_data("instanced_scene.gltf"), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const TriangleMesh& m = r.value();
  // Roots of scene 1 in order: node 0 (translation 10,0,0) then its child
  // node 1 (T(0,0,1) R(180 deg about z) S(2), composed with its parent),
  // then node 2 (matrix: mirror x, translate y by 5). Node 3 (scene 0) and
  // the LINES primitive are left out.
  const std::vector<Vec3f> expected = {{10, 0, 0}, {11, 0, 0}, {11, 1, 0}, {10, 1, 0},   // node 0
                                       {10, 0, 1}, {8, 0, 1},  {8, -2, 1}, {10, -2, 1},  // node 1
                                       {0, 5, 0},  {-1, 5, 0}, {-1, 6, 0}, {0, 6, 0}};   // node 2
  EXPECT_EQ(m.positions, expected);
  // The mirrored instance has its winding reversed to stay counter-clockwise.
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3},  {4, 5, 6},
                                           {4, 6, 7}, {8, 10, 9}, {8, 11, 10}};
  EXPECT_EQ(m.triangles, triangles);
  ASSERT_EQ(m.normals.binding, AttributeBinding::kPerVertex);
  for (size_t v = 0; v < 12; ++v) {
    EXPECT_EQ(m.normals.values[3 * v + 0], 0.0f);
    EXPECT_EQ(m.normals.values[3 * v + 1], 0.0f);
    EXPECT_EQ(m.normals.values[3 * v + 2], 1.0f) << v;
  }
  ASSERT_EQ(m.texcoords.binding, AttributeBinding::kPerVertex);
  // glTF's (u, v) = (1, 0) at the quad's second vertex becomes (1, 1).
  EXPECT_EQ(m.texcoords.values[2], 1.0f);
  EXPECT_EQ(m.texcoords.values[3], 1.0f);
  EXPECT_EQ(report.format, "gltf");
  EXPECT_EQ(report.file_faces, 6u);
  EXPECT_EQ(report.welded_vertices, 0u);
  EXPECT_TRUE(has_note(report, "skipped mesh 0 primitive 1: mode LINES is not triangles"));
  EXPECT_TRUE(has_note(report, "ignored scene 0 (not the default scene)"));
}

TEST(GltfImport, GlbGivesTheSameMeshAsGltf) {
  auto text = gltf(read_data("instanced_scene.gltf"));
  ImportReport report;
  auto binary = gltf(scene_as_glb(scene_json()), &report);
  ASSERT_TRUE(text.is_ok());
  ASSERT_TRUE(binary.is_ok()) << binary.status().message();
  EXPECT_EQ(text.value(), binary.value());
  EXPECT_EQ(report.format, "glb");
  maybe_regenerate(corpus_dir() + "gltf/instanced_scene.glb", scene_as_glb(scene_json()));
}

TEST(GltfImport, WithoutSceneUsesSceneZeroAndWithoutScenesEveryRoot) {
  Json j = scene_json();
  j.erase("scene");
  ImportReport report;
  auto r = gltf(j.dump(), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  ASSERT_EQ(r.value().positions.size(), 4u);
  EXPECT_EQ(r.value().positions[0], (Vec3f{100, 0, 0}));
  EXPECT_TRUE(has_note(report, "no default scene given: used scene 0"));

  j.erase("scenes");
  ImportReport report2;
  auto all = gltf(j.dump(), &report2);
  ASSERT_TRUE(all.is_ok()) << all.status().message();
  EXPECT_EQ(all.value().positions.size(), 16u);  // nodes 0 (+1), 2, 3
  EXPECT_TRUE(has_note(report2, "no scenes: used every root node"));
}

TEST(GltfImport, StripsAndFansAreTrianglesAndSeamsAreWelded) {
  ImportReport report;
  auto r = gltf(read_data("strip_fan.gltf"), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const std::vector<Triangle> expected = {{0, 1, 3}, {1, 2, 3}, {1, 2, 0}, {2, 3, 0}};
  EXPECT_EQ(r.value().triangles, expected);
  EXPECT_EQ(r.value().positions.size(), 4u);
  EXPECT_EQ(report.welded_vertices, 4u);  // the fan's 4 vertices repeat the strip's
  EXPECT_EQ(report.file_faces, 5u);
  EXPECT_TRUE(has_note(report, "dropped 1 zero-area stitching triangles"));
  EXPECT_TRUE(has_note(report, "ignored vertex attribute 'COLOR_0'"));
}

TEST(GltfImport, WeldingMakesDisagreeingAttributesPerCorner) {
  // Two quads sharing an edge, each with its own normal: the shared positions
  // weld, the normals cannot stay per vertex.
  Json j = scene_json();
  j["scenes"][1]["nodes"] = {0};
  j["nodes"][0] = {{"mesh", 0}, {"children", {1}}};
  j["nodes"][1] = {{"mesh", 1}, {"matrix", {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1}}};
  j["meshes"][0]["primitives"].erase(1);
  j["meshes"].push_back(j["meshes"][0]);
  ImportReport report;
  auto r = gltf(j.dump(), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const TriangleMesh& m = r.value();
  // Rotating the quad 90 degrees about x keeps its edge on the x axis.
  EXPECT_EQ(m.positions.size(), 6u);
  EXPECT_EQ(report.welded_vertices, 2u);
  ASSERT_EQ(m.normals.binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(corner_value(m, m.normals, 0, 0), (std::vector<float>{0, 0, 1}));
  EXPECT_EQ(corner_value(m, m.normals, 2, 0), (std::vector<float>{0, -1, 0}));
  // Texture coordinates agree across the seam, so they stay per vertex.
  EXPECT_EQ(m.texcoords.binding, AttributeBinding::kPerVertex);
}

TEST(GltfImport, AttributeOnlySomePrimitivesHaveIsDroppedWithANote) {
  Json j = scene_json();
  j["meshes"][0]["primitives"][1] = {{"attributes", {{"POSITION", 0}}}, {"indices", 1}};
  ImportReport report;
  auto r = gltf(j.dump(), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_FALSE(r.value().normals.present());
  EXPECT_FALSE(r.value().texcoords.present());
  EXPECT_TRUE(has_note(report, "ignored NORMAL: only some triangle primitives have it"));
  EXPECT_TRUE(has_note(report, "ignored TEXCOORD_0: only some triangle primitives have it"));
}

TEST(GltfImport, IgnoredContentIsNoted) {
  Json j = scene_json();
  j["materials"] = Json::array({Json::object(), Json::object()});
  j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 3;
  j["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = 3;
  j["extensionsUsed"] = {"KHR_materials_unlit"};
  ImportReport report;
  ASSERT_TRUE(gltf(j.dump(), &report).is_ok());
  EXPECT_TRUE(has_note(report, "ignored 2 materials"));
  EXPECT_TRUE(has_note(report, "ignored vertex attribute 'TEXCOORD_1'"));
  EXPECT_TRUE(has_note(report, "ignored vertex attribute 'JOINTS_0'"));
  EXPECT_TRUE(has_note(report, "ignored glTF extension 'KHR_materials_unlit'"));
}

TEST(GltfImport, NormalizedIntegerTexcoordsAreConverted) {
  // Three unindexed vertices; TEXCOORD_0 as normalized unsigned bytes with
  // the 4-byte stride glTF asks of vertex attributes.
  Bytes bin(36 + 12, 0);
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::memcpy(bin.data(), xyz, sizeof(xyz));
  bin[36 + 4] = 255;  // vertex 1: (1, 0)
  bin[36 + 9] = 51;   // vertex 2: (0, 0.2)
  Json j = {
      {"asset", {{"version", "2.0"}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}}}}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
        {{"bufferView", 1},
         {"componentType", 5121},
         {"normalized", true},
         {"count", 3},
         {"type", "VEC2"}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteLength", 36}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 12}, {"byteStride", 4}}}},
      {"buffers", {{{"byteLength", 48}}}}};
  auto r = gltf(make_glb(j.dump(), bin));
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const std::vector<float> expected = {0, 1, 1, 1, 0, 1.0f - 51 / 255.0f};
  EXPECT_EQ(r.value().texcoords.values, expected);
}

TEST(GltfImport, SparseAccessorsAreRead) {
  // Three unindexed vertices; a sparse accessor moves vertex 1 to (2, 0, 0).
  Bytes bin(52, 0);
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::memcpy(bin.data(), xyz, sizeof(xyz));
  bin[36] = 1;  // the sparse index (unsigned byte)
  const float moved[3] = {2, 0, 0};
  std::memcpy(&bin[40], moved, sizeof(moved));
  Json j = {{"asset", {{"version", "2.0"}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
            {"accessors",
             {{{"bufferView", 0},
               {"componentType", 5126},
               {"count", 3},
               {"type", "VEC3"},
               {"sparse",
                {{"count", 1},
                 {"indices", {{"bufferView", 1}, {"componentType", 5121}}},
                 {"values", {{"bufferView", 2}}}}}}}},
            {"bufferViews",
             {{{"buffer", 0}, {"byteLength", 36}},
              {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 1}},
              {{"buffer", 0}, {"byteOffset", 40}, {"byteLength", 12}}}},
            {"buffers", {{{"byteLength", 52}}}}};
  auto r = gltf(make_glb(j.dump(), bin));
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const std::vector<Vec3f> expected = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(r.value().positions, expected);
}

TEST(GltfImport, ExternalBufferIsRefusedWhenReadFromMemory) {
  auto r = gltf(read_data("external_buffer.gltf"));
  expect_error(r, ErrorKind::kUnsupported,
               "buffer 0: the asset is read from memory; external file 'quad.bin' cannot be "
               "resolved");
}

TEST(GltfImport, NoTrianglesIsAnError) {
  Json j = scene_json();
  j["meshes"][0]["primitives"].erase(0);
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "no triangles in the default scene (1 non-triangle primitives skipped)");
}

TEST(GltfImport, DracoCompressedPrimitive) {
  const Bytes glb = draco_compressed_cube_glb();
  maybe_regenerate(gltf_data_dir() + "cube_draco.glb", glb);
  for (const Bytes& bytes : {glb, read_data("cube_draco.glb")}) {
    ImportReport report;
    auto r = gltf(bytes, &report);
    ASSERT_TRUE(r.is_ok()) << r.status().message();
    const TriangleMesh& m = r.value();
    const TriangleMesh c = cube();
    ASSERT_EQ(m.triangles.size(), 12u);
    EXPECT_EQ(m.positions.size(), 8u);
    EXPECT_EQ(report.welded_vertices, 16u);
    ASSERT_EQ(m.normals.binding, AttributeBinding::kPerCorner);
    // Draco reorders and quantizes; every corner stays within its error.
    EXPECT_TRUE(same_triangles_any_order(m, c, 1e-3f));
  }
}

TEST(GltfImport, PrimitivesSharingACompressedBufferView) {
  // Two primitives over one Draco bufferView (decoded once, used twice).
  const Bytes glb = read_data("cube_draco.glb");
  uint32_t json_length = 0;
  std::memcpy(&json_length, &glb[12], 4);
  Json j = Json::parse(glb.begin() + 20, glb.begin() + 20 + json_length);
  const Bytes bin(glb.begin() + 20 + json_length + 8, glb.end());
  j["meshes"][0]["primitives"].push_back(j["meshes"][0]["primitives"][0]);
  j["meshes"][0]["primitives"][1]["attributes"].erase("NORMAL");
  j["meshes"][0]["primitives"][1]["extensions"]["KHR_draco_mesh_compression"]["attributes"].erase(
      "NORMAL");
  ImportReport report;
  auto r = gltf(make_glb(j.dump(), bin), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().triangles.size(), 24u);
  EXPECT_EQ(r.value().positions.size(), 8u);
  EXPECT_FALSE(r.value().normals.present());
  EXPECT_TRUE(has_note(report, "ignored NORMAL: only some triangle primitives have it"));
}

// Hostile glTF.

TEST(GltfHostile, IndexOutOfRange) {
  Bytes bin = scene_buffer();
  bin[48] = 200;  // first index
  Json j = scene_json();
  j["buffers"][0].erase("uri");
  expect_error(gltf(make_glb(j.dump(), bin)), ErrorKind::kInvalidInput,
               "mesh 0 primitive 0: index 200 at position 0 out of range (4 vertices)");
}

TEST(GltfHostile, NodeGraphMustBeAForest) {
  Json j = scene_json();
  j["nodes"][1]["children"] = {0};
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput, "part of a cycle");
  j = scene_json();
  j["nodes"][2]["children"] = {1};
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput, "node 1 has two parents (nodes 0 and 2)");
  j = scene_json();
  j["nodes"][0]["children"] = {0};
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput, "node 0 is its own child");
  j = scene_json();
  j["scenes"][1]["nodes"] = {0, 1};
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "scene 1 lists node 1, which is a child of node 0");
  j = scene_json();
  j["nodes"][0]["mesh"] = 5;
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput, "node 0: mesh 5 out of range (1 meshes)");
}

TEST(GltfHostile, AccessorAndBufferBounds) {
  Json j = scene_json();
  j["accessors"][0]["count"] = 5;
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "accessor 0: 5 elements from byte 0 need 60 bytes, its bufferView holds 48");
  j = scene_json();
  j["bufferViews"][3]["byteLength"] = 40;
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "bufferView 3: bytes 108 to 148 lie outside buffer 0 of 140 bytes");
  j = scene_json();
  j["buffers"][0]["byteLength"] = 141;
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "buffer 0 declares 141 bytes, its data: URI holds 140");
  j = scene_json();
  // The reader's decoding budget stops it before the bounds are looked at.
  j["accessors"][0]["count"] = 4294967295ull;
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "accessor 0 would decode more than 67108864 bytes in all");
  j = scene_json();
  j["accessors"][0]["sparse"] = Json::object();
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "accessor 0 sparse: 'count' is missing, zero or above the accessor's");
  j = scene_json();
  j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 3;
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "mesh 0 primitive 0: NORMAL has 2 components per element, 3 expected");
  j = scene_json();
  j["accessors"][1]["count"] = 5;
  j["bufferViews"][1]["byteLength"] = 12;
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput, "5 indices do not form whole triangles");
  j = scene_json();
  j["buffers"][0]["uri"] = "data:application/octet-stream;base64,AA!A";
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput, "invalid base64 character");
}

TEST(GltfHostile, GlbContainer) {
  const Bytes good = scene_as_glb(scene_json());
  ASSERT_TRUE(gltf(good).is_ok());
  Bytes longer = good;
  longer.push_back(0);
  expect_error(gltf(longer), ErrorKind::kInvalidInput, "1 trailing bytes follow");
  Bytes shorter(good.begin(), good.end() - 4);
  expect_error(gltf(shorter), ErrorKind::kInvalidInput, "the data ends at byte");
  Bytes version = good;
  version[4] = 1;
  expect_error(gltf(version), ErrorKind::kUnsupported, "GLB version 1 is not supported");
  Bytes chunk = good;
  chunk[12] = 0xFF;
  chunk[13] = 0xFF;
  expect_error(gltf(chunk), ErrorKind::kInvalidInput, "GLB chunk at byte 12 declares");
  expect_error(gltf(Bytes(good.begin(), good.begin() + 8)), ErrorKind::kInvalidInput,
               "GLB header needs 12 bytes, the data has 8");
  Json j = scene_json();
  j["buffers"][0].erase("uri");
  j["buffers"][0]["byteLength"] = 1000;
  expect_error(gltf(make_glb(j.dump(), scene_buffer())), ErrorKind::kInvalidInput,
               "buffer 0 declares 1000 bytes, the GLB BIN chunk holds 140");
  expect_error(gltf(make_glb(j.dump(), Bytes())), ErrorKind::kInvalidInput,
               "refers to a BIN chunk the GLB lacks");
}

TEST(GltfHostile, JsonLevel) {
  expect_error(gltf(std::string(100000, '[')), ErrorKind::kInvalidInput,
               "JSON nesting deeper than 64 levels at byte 64");
  expect_error(gltf(std::string("{\"asset\": ")), ErrorKind::kInvalidInput,
               "glTF JSON: syntax error at byte");
  expect_error(gltf(std::string("[]")), ErrorKind::kInvalidInput, "glTF JSON is not an object");
  expect_error(gltf(std::string("{}")), ErrorKind::kInvalidInput, "glTF has no 'asset' object");
  expect_error(gltf(std::string(R"({"asset": {"version": "1.0"}})")), ErrorKind::kUnsupported,
               "glTF version '1.0' is not supported");
  Json j = scene_json();
  j["extensionsRequired"] = {"KHR_gaussian_splatting"};
  expect_error(gltf(j.dump()), ErrorKind::kUnsupported,
               "required glTF extension 'KHR_gaussian_splatting' is not supported");
  j = scene_json();
  j["nodes"][0]["translation"] = {1, "x", 3};
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "node 0: 'translation' is not an array of 3 numbers");
  j = scene_json();
  j["nodes"][0]["rotation"] = {0, 0, 0, 0};
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput,
               "node 0: 'rotation' is not a usable quaternion");
  j = scene_json();
  j["meshes"][0]["primitives"][0]["mode"] = 7;
  expect_error(gltf(j.dump()), ErrorKind::kInvalidInput, "mesh 0 primitive 0: 'mode' 7 exceeds 6");
}

TEST(GltfHostile, InstancingIsBounded) {
  // One mesh of 3,000 vertices (unindexed triangles) instanced by 4,000
  // nodes: 16 million vertices and triangles from an input of about 200 KB.
  const size_t n = 3000;
  Bytes bin(n * 12);
  for (size_t i = 0; i < n; ++i) {
    const float p[3] = {float(i), float(i % 3), 0};
    std::memcpy(&bin[i * 12], p, 12);
  }
  Json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", n * 12}}}},
      {"buffers", {{{"byteLength", n * 12}}}}};
  Json nodes = Json::array();
  Json roots = Json::array();
  for (int i = 0; i < 4000; ++i) {
    nodes.push_back({{"mesh", 0}, {"translation", {i, 0, 0}}});
    roots.push_back(i);
  }
  j["nodes"] = nodes;
  j["scenes"] = {{{"nodes", roots}}};
  expect_error(gltf(make_glb(j.dump(), bin)), ErrorKind::kInvalidInput,
               "instancing the meshes of the default scene exceeds the limit of");
}

TEST(GltfHostile, EveryTruncationAndHeaderBitFlipFailsCleanly) {
  const Bytes glb = scene_as_glb(scene_json());
  for (size_t len = 0; len < glb.size(); ++len) {
    EXPECT_FALSE(gltf(Bytes(glb.begin(), glb.begin() + len)).is_ok()) << len;
  }
  const Bytes text = read_data("instanced_scene.gltf");
  for (size_t len = 0; len + 2 < text.size(); len += 7) {
    EXPECT_FALSE(gltf(Bytes(text.begin(), text.begin() + len)).is_ok()) << len;
  }
  for (size_t byte = 0; byte < 20; ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      Bytes flipped = glb;
      flipped[byte] ^= static_cast<uint8_t>(1u << bit);
      auto r = gltf(flipped);  // must not crash; a few flips stay valid JSON padding
      if (!r.is_ok()) {
        EXPECT_FALSE(r.status().message().empty());
      }
    }
  }
}

// ---------------------------------------------------------------- Draco

TEST(DracoImport, DragonHasTheManifestCounts) {
  const std::string path = env_or("LODBAKE_SHARED_DATA", LODBAKE_TEST_SHARED_DATA) +
                           "/meshes/stanford_dragon_vrip_qp20_cl10.drc";
  auto bytes = read_file(path);
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  ImportReport report;
  auto r = parse_draco(bytes.value().data(), bytes.value().size(), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().vertex_count(), 435545u);
  EXPECT_EQ(r.value().triangle_count(), 871306u);
  EXPECT_EQ(report.format, "draco");
  EXPECT_EQ(report.welded_vertices, 0u);
}

TEST(DracoImport, TetrahedronRoundTrip) {
  const Bytes drc = encode_drc(tetrahedron());
  auto r = parse_draco(drc.data(), drc.size(), nullptr);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().vertex_count(), 4u);
  EXPECT_EQ(r.value().triangle_count(), 4u);
  // Draco reorders; every input triangle must appear with its orientation.
  EXPECT_TRUE(same_triangles_any_order(r.value(), tetrahedron(), 0.0f));
  // The fuzz seed is this encoding.
  maybe_regenerate(corpus_dir() + "draco/tetrahedron.drc", drc);
  const Bytes seed = [] {
    auto f = read_file(corpus_dir() + "draco/tetrahedron.drc");
    return f.is_ok() ? f.value() : Bytes();
  }();
  auto s = parse_draco(seed.data(), seed.size(), nullptr);
  ASSERT_TRUE(s.is_ok()) << s.status().message();
  EXPECT_EQ(s.value(), r.value());
}

TEST(DracoImport, SeamAttributesBecomePerCorner) {
  const TriangleMesh c = cube();
  const Bytes drc = encode_drc(c);
  maybe_regenerate(corpus_dir() + "draco/cube_normals_texcoords.drc", drc);
  ImportReport report;
  auto r = parse_draco(drc.data(), drc.size(), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const TriangleMesh& m = r.value();
  EXPECT_EQ(m.vertex_count(), 8u);
  ASSERT_EQ(m.triangle_count(), 12u);
  ASSERT_EQ(m.normals.binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(m.texcoords.binding, AttributeBinding::kPerVertex);
  EXPECT_TRUE(same_triangles_any_order(m, c, 0.0f));
}

TEST(DracoImport, PointCloudAndGarbageAreRefused) {
  draco::PointCloudBuilder builder;
  builder.Start(2);
  const int att = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const float p[2][3] = {{0, 0, 0}, {1, 2, 3}};
  builder.SetAttributeValueForPoint(att, draco::PointIndex(0), p[0]);
  builder.SetAttributeValueForPoint(att, draco::PointIndex(1), p[1]);
  auto cloud = builder.Finalize(false);
  draco::Encoder encoder;
  draco::EncoderBuffer buffer;
  ASSERT_TRUE(encoder.EncodePointCloudToBuffer(*cloud, &buffer).ok());
  const Bytes cloud_bytes(buffer.data(), buffer.data() + buffer.size());
  maybe_regenerate(corpus_dir() + "draco/point_cloud.drc", cloud_bytes);
  auto r = parse_draco(cloud_bytes.data(), cloud_bytes.size(), nullptr);
  expect_error(r, ErrorKind::kUnsupported, "holds a point cloud, not a triangle mesh");

  const Bytes garbage = text_bytes("this is not a Draco file at all");
  expect_error(parse_draco(garbage.data(), garbage.size(), nullptr), ErrorKind::kInvalidInput,
               "not a Draco file");
  const Bytes drc = encode_drc(tetrahedron());
  for (size_t len = 0; len < drc.size(); ++len) {
    EXPECT_FALSE(parse_draco(drc.data(), len, nullptr).is_ok()) << len;
  }
}

TEST(DracoImport, LegacyBitstreamVersionsAreRefusedBeforeDecoding) {
  // Found by fuzz_draco: 34 bytes claiming bitstream 1.61 made Draco's
  // legacy edgebreaker path allocate and fill about 24 GB.
  auto f = read_file(corpus_dir() + "draco/legacy_v1_huge_corner_table.drc");
  ASSERT_TRUE(f.is_ok()) << f.status().message();
  expect_error(parse_draco(f.value().data(), f.value().size(), nullptr), ErrorKind::kUnsupported,
               "Draco mesh bitstream version 1.61 is not supported (only 2.2");
  Bytes drc = encode_drc(tetrahedron());
  drc[6] = 1;  // 2.1
  expect_error(parse_draco(drc.data(), drc.size(), nullptr), ErrorKind::kUnsupported,
               "bitstream version 2.1 is not supported");
}

TEST(DracoImport, BoolAttributeIsRefusedBeforeItIsRead) {
  // Found by fuzz_draco: a POSITION of Draco type DT_BOOL holding 0xFF made
  // Draco's ConvertValue load an invalid bool (undefined behaviour).
  auto f = read_file(corpus_dir() + "draco/crash_bool_attribute.drc");
  ASSERT_TRUE(f.is_ok()) << f.status().message();
  expect_error(parse_draco(f.value().data(), f.value().size(), nullptr), ErrorKind::kInvalidInput,
               "attribute has data type 11, not a number type");
}

// ---------------------------------------------------------------- GLB export

TEST(GlbExport, RoundTripKeepsPositionsTrianglesAndCornerValues) {
  const TriangleMesh c = cube();
  auto glb = write_glb(c);
  ASSERT_TRUE(glb.is_ok()) << glb.status().message();
  ImportReport report;
  auto r = gltf(glb.value(), &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const TriangleMesh& m = r.value();
  // Guarantee: without coincident vertices, positions and triangles come
  // back identical and in the same order; every corner keeps its values.
  EXPECT_EQ(m.positions, c.positions);
  EXPECT_EQ(m.triangles, c.triangles);
  EXPECT_EQ(report.welded_vertices, 16u);  // 24 GLB vertices, one per (vertex, normal)
  EXPECT_EQ(m.normals.binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(m.texcoords, c.texcoords);
  for (size_t t = 0; t < 12; ++t) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(corner_value(m, m.normals, t, k), corner_value(c, c.normals, t, k));
    }
  }
  EXPECT_TRUE(has_note(report, "ignored 1 material"));  // Draco's default material
}

TEST(GlbExport, PerVertexMeshRoundTripsExactly) {
  TriangleMesh m = tetrahedron();
  m.positions.push_back({5, 5, 5});  // unreferenced vertices are kept
  m.normals.binding = AttributeBinding::kPerVertex;
  m.normals.components = 3;
  for (int v = 0; v < 5; ++v)
    m.normals.values.insert(m.normals.values.end(), {0.0f, float(v), 1});
  auto glb = write_glb(m);
  ASSERT_TRUE(glb.is_ok()) << glb.status().message();
  auto r = gltf(glb.value());
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value(), m);
}

// The JSON chunk of a GLB written by write_glb.
nlohmann::json glb_json(const Bytes& glb) {
  uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + length);
}

TEST(GlbExport, NamesLodbakeAndHowToWeld) {
  auto plain = write_glb(tetrahedron());
  ASSERT_TRUE(plain.is_ok()) << plain.status().message();
  const nlohmann::json json = glb_json(plain.value());
  EXPECT_EQ(json["asset"]["generator"], std::string("lodbake ") + kLodbakeVersion);
  EXPECT_EQ(json["asset"]["version"], "2.0");
  EXPECT_EQ(json["asset"]["extras"]["lodbake_weld"], "none");
  auto seams = write_glb(cube());  // per-corner normals
  ASSERT_TRUE(seams.is_ok()) << seams.status().message();
  EXPECT_EQ(glb_json(seams.value())["asset"]["extras"]["lodbake_weld"], "manifold_edges");
  // The rewritten GLB is well formed: the length fields agree with the bytes.
  uint32_t total = 0, json_length = 0;
  std::memcpy(&total, seams.value().data() + 8, 4);
  std::memcpy(&json_length, seams.value().data() + 12, 4);
  EXPECT_EQ(total, seams.value().size());
  EXPECT_EQ(json_length % 4, 0u);
}

// Two tetrahedra sharing the apex position through two vertices (what
// repair makes of two cones touching at a point), optionally with
// per-corner texture coordinates.
TriangleMesh split_apex(bool per_corner) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                 {0, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
                 {4, 6, 5}, {4, 5, 7}, {4, 7, 6}, {5, 6, 7}};
  if (per_corner) {
    m.texcoords.binding = AttributeBinding::kPerCorner;
    m.texcoords.components = 2;
    for (size_t c = 0; c < m.triangles.size() * 3; ++c) {
      m.texcoords.values.push_back(float(c % 3));  // every triangle its own corner values
      m.texcoords.values.push_back(0.5f);
    }
    m.texcoords.corners.resize(m.triangles.size());
    for (uint32_t t = 0; t < m.triangles.size(); ++t)
      m.texcoords.corners[t] = {3 * t, 3 * t + 1, 3 * t + 2};
  }
  return m;
}

TEST(GlbExport, SplitVerticesComeBackSplit) {
  for (bool per_corner : {false, true}) {
    SCOPED_TRACE(per_corner ? "per-corner texture coordinates" : "per-vertex");
    const TriangleMesh m = split_apex(per_corner);
    auto glb = write_glb(m);
    ASSERT_TRUE(glb.is_ok()) << glb.status().message();
    auto r = gltf(glb.value());
    ASSERT_TRUE(r.is_ok()) << r.status().message();
    EXPECT_EQ(r.value().positions, m.positions);
    EXPECT_EQ(r.value().triangles, m.triangles);
  }
}

TEST(GltfImport, FilesWithoutLodbakesMarkWeldEveryEqualPosition) {
  // The same GLB with the marker's name changed (same length): a foreign
  // file, whose seams and split vertices are all welded.
  auto glb = write_glb(split_apex(true));
  ASSERT_TRUE(glb.is_ok()) << glb.status().message();
  Bytes foreign = glb.value();
  const std::string mark = "lodbake_weld";
  auto at = std::search(foreign.begin(), foreign.end(), mark.begin(), mark.end());
  ASSERT_NE(at, foreign.end());
  at[8] = 'x';
  ImportReport report;
  auto r = gltf(foreign, &report);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().vertex_count(), 7u);  // the two apexes are one vertex
  EXPECT_EQ(r.value().triangles[4][0], 0u);
  // An unknown marker value welds every position too.
  at[8] = 'w';
  std::string value = "\"manifold_edges\"";
  auto v = std::search(foreign.begin(), foreign.end(), value.begin(), value.end());
  ASSERT_NE(v, foreign.end());
  v[1] = 'M';
  auto unknown = gltf(foreign);
  ASSERT_TRUE(unknown.is_ok()) << unknown.status().message();
  EXPECT_EQ(unknown.value().vertex_count(), 7u);
}

TEST(GlbExport, IsDeterministicAndMatchesTheGoldenFile) {
  auto a = write_glb(cube());
  auto b = write_glb(cube());
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  EXPECT_EQ(a.value(), b.value());
  maybe_regenerate(gltf_data_dir() + "cube_written.glb", a.value());
  EXPECT_EQ(a.value(), read_data("cube_written.glb"));
}

TEST(GlbExport, InvalidMeshesAreRefused) {
  TriangleMesh m = tetrahedron();
  m.triangles[2][1] = 9;
  auto r = write_glb(m);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(), "triangle 2: vertex index 9 out of range (4 vertices)");
  EXPECT_FALSE(write_glb(TriangleMesh()).is_ok());
  TriangleMesh bad_normals = tetrahedron();
  bad_normals.normals.binding = AttributeBinding::kPerVertex;
  bad_normals.normals.components = 3;
  bad_normals.normals.values = {0, 0, 1};
  auto n = write_glb(bad_normals);
  ASSERT_FALSE(n.is_ok());
  EXPECT_EQ(n.status().message(), "normals are per vertex but have 1 values for 4 vertices");
  TriangleMesh nan = tetrahedron();
  nan.positions[3][1] = std::nanf("");
  auto f = write_glb(nan);
  ASSERT_FALSE(f.is_ok());
  EXPECT_EQ(f.status().message(), "vertex 3 has a non-finite coordinate, which glTF cannot store");
}

}  // namespace
}  // namespace lodbake
