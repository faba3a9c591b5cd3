// The glTF scene writers (write_scene_glb, write_scene_gltf) on the
// hand-built sample scenes: the output is parsed back here, every written
// accessor decoded through its bufferView (stride, matrix column padding) and
// compared with the scene's streams, and the layout rules glTF sets (and
// Khronos's validator checks, tests/gltf) asserted one by one.
#include <cstring>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "lib/scene/scene_compare.h"
#include "lib/scene/scene_io.h"
#include "tests/gltf/sample_scenes.h"

namespace lodbake {
namespace {

using Json = nlohmann::json;
namespace samples = sample_scenes;

uint32_t u32(const Bytes& b, size_t at) {
  return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16 |
         uint32_t{b[at + 3]} << 24;
}

struct Parsed {
  Json root;
  Bytes bin;
};

// Splits a GLB, checking its header and chunk padding.
Parsed parse_glb(const Bytes& glb) {
  Parsed out;
  EXPECT_GE(glb.size(), 20u);
  if (glb.size() < 20) return out;
  EXPECT_EQ(u32(glb, 0), 0x46546C67u);
  EXPECT_EQ(u32(glb, 4), 2u);
  EXPECT_EQ(u32(glb, 8), glb.size());
  const uint32_t json_size = u32(glb, 12);
  EXPECT_EQ(u32(glb, 16), 0x4E4F534Au);
  EXPECT_EQ(json_size % 4, 0u);
  const std::string json(glb.begin() + 20, glb.begin() + 20 + json_size);
  // Padded with spaces after the document.
  EXPECT_EQ(json.find_first_not_of(' ', json.find_last_of('}') + 1), std::string::npos);
  out.root = Json::parse(json);
  const size_t bin_at = 20 + json_size;
  if (bin_at < glb.size()) {
    const uint32_t bin_size = u32(glb, bin_at);
    EXPECT_EQ(u32(glb, bin_at + 4), 0x004E4942u);
    EXPECT_EQ(bin_size % 4, 0u);
    EXPECT_EQ(bin_at + 8 + bin_size, glb.size());
    out.bin.assign(glb.begin() + bin_at + 8, glb.end());
  }
  return out;
}

uint32_t component_bytes(int code) {
  return component_size(static_cast<ComponentType>(code));
}

// The accessor's elements, tightly packed as AccessorData holds them.
Bytes decode_accessor(const Parsed& gltf, uint32_t index) {
  const Json& accessor = gltf.root["accessors"][index];
  const Json& view = gltf.root["bufferViews"][accessor["bufferView"].get<uint32_t>()];
  const std::string type = accessor["type"];
  const std::map<std::string, uint32_t> rows = {
      {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 2}, {"MAT3", 3}, {"MAT4", 4}};
  const bool matrix = type.rfind("MAT", 0) == 0;
  const uint32_t size = component_bytes(accessor["componentType"]);
  const uint32_t column_bytes = rows.at(type) * size;
  const uint32_t columns = matrix ? rows.at(type) : 1;
  const uint32_t column_stride = matrix ? (column_bytes + 3) / 4 * 4 : column_bytes;
  const uint32_t stride = view.value("byteStride", columns * column_stride);
  const size_t start = view.value("byteOffset", 0u) + accessor.value("byteOffset", 0u);
  const uint32_t count = accessor["count"];
  Bytes out;
  for (uint32_t e = 0; e < count; ++e) {
    for (uint32_t c = 0; c < columns; ++c) {
      const size_t at = start + size_t{e} * stride + size_t{c} * column_stride;
      EXPECT_LE(at + column_bytes, gltf.bin.size());
      if (at + column_bytes > gltf.bin.size()) return out;
      out.insert(out.end(), gltf.bin.begin() + at, gltf.bin.begin() + at + column_bytes);
    }
  }
  return out;
}

std::vector<uint32_t> decode_indices(const Parsed& gltf, uint32_t index) {
  const Json& accessor = gltf.root["accessors"][index];
  const Bytes bytes = decode_accessor(gltf, index);
  const uint32_t size = component_bytes(accessor["componentType"]);
  std::vector<uint32_t> out;
  for (size_t i = 0; i + size <= bytes.size(); i += size) {
    uint32_t v = 0;
    for (uint32_t b = 0; b < size; ++b)
      v |= uint32_t{bytes[i + b]} << (8 * b);
    out.push_back(v);
  }
  return out;
}

void expect_stream(const Parsed& gltf, uint32_t index, const AccessorData& data) {
  const Json& accessor = gltf.root["accessors"][index];
  EXPECT_EQ(accessor["componentType"], static_cast<int>(data.component_type));
  EXPECT_EQ(accessor["count"], data.count);
  EXPECT_EQ(accessor.value("normalized", false), data.normalized);
  EXPECT_EQ(decode_accessor(gltf, index), data.bytes);
}

Parsed glb_of(const Scene& scene, SceneWriteReport* report = nullptr) {
  SceneWriteReport local;
  Result<Bytes> glb = write_scene_glb(scene, report != nullptr ? report : &local);
  EXPECT_TRUE(glb.is_ok()) << glb.status().message();
  return glb.is_ok() ? parse_glb(glb.value()) : Parsed{};
}

TEST(GltfSceneWriter, EveryStreamIndexAndCarriedAccessorReadsBackFromTheBuffer) {
  const Scene scene = samples::full_scene();
  const Parsed gltf = glb_of(scene);
  ASSERT_TRUE(gltf.root.is_object());
  // Carried accessors come first, so skins and animations keep their indices.
  for (uint32_t i = 0; i < scene.accessors.size(); ++i)
    expect_stream(gltf, i, scene.accessors[i]);
  EXPECT_EQ(gltf.root["accessors"][4]["name"], "byte matrices");
  EXPECT_EQ(gltf.root["skins"], scene.skins);
  EXPECT_EQ(gltf.root["animations"], scene.animations);
  EXPECT_EQ(gltf.root["nodes"][5]["extensions"], scene.nodes[5].extensions);
  ASSERT_EQ(gltf.root["meshes"].size(), scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Json& mesh = gltf.root["meshes"][m];
    ASSERT_EQ(mesh["primitives"].size(), scene.meshes[m].primitives.size());
    for (size_t p = 0; p < scene.meshes[m].primitives.size(); ++p) {
      SCOPED_TRACE("mesh " + std::to_string(m) + " primitive " + std::to_string(p));
      const ScenePrimitive& primitive = scene.meshes[m].primitives[p];
      const Json& out = mesh["primitives"][p];
      EXPECT_EQ(out["mode"], static_cast<int>(primitive.mode));
      EXPECT_EQ(out.contains("material"), primitive.material >= 0);
      ASSERT_EQ(out["attributes"].size(), primitive.attributes.size());
      for (const SceneAttribute& a : primitive.attributes)
        expect_stream(gltf, out["attributes"][a.semantic], a.data);
      ASSERT_EQ(out.contains("indices"), primitive.indices.has_value());
      if (primitive.indices) {
        EXPECT_EQ(decode_indices(gltf, out["indices"]), *primitive.indices);
      }
      ASSERT_EQ(out.value("targets", Json::array()).size(), primitive.targets.size());
      for (size_t t = 0; t < primitive.targets.size(); ++t) {
        for (const SceneAttribute& a : primitive.targets[t])
          expect_stream(gltf, out["targets"][t][a.semantic], a.data);
      }
    }
  }
  EXPECT_EQ(gltf.root["meshes"][0]["primitives"][0]["extras"], Json({{"part", "body"}}));
  EXPECT_EQ(gltf.root["meshes"][1]["weights"], Json({0.5, 0.25}));
}

TEST(GltfSceneWriter, LayoutFollowsGltfRules) {
  const Parsed gltf = glb_of(samples::full_scene());
  ASSERT_EQ(gltf.root["buffers"].size(), 1u);
  EXPECT_EQ(gltf.root["buffers"][0]["byteLength"], gltf.bin.size());
  EXPECT_FALSE(gltf.root["buffers"][0].contains("uri"));
  std::vector<bool> covered(gltf.bin.size(), false);
  for (const Json& view : gltf.root["bufferViews"]) {
    EXPECT_EQ(view.value("byteOffset", 0u) % 4, 0u) << view;
    for (size_t i = view.value("byteOffset", 0u);
         i < view.value("byteOffset", 0u) + view["byteLength"].get<size_t>() && i < covered.size();
         ++i) {
      covered[i] = true;
    }
    EXPECT_LE(view.value("byteOffset", 0u) + view["byteLength"].get<size_t>(), gltf.bin.size());
    if (view.value("target", 0) == 34962) {
      ASSERT_TRUE(view.contains("byteStride")) << view;
      EXPECT_EQ(view["byteStride"].get<uint32_t>() % 4, 0u);
    } else {
      EXPECT_FALSE(view.contains("byteStride")) << view;
    }
  }
  for (size_t i = 0; i < covered.size(); ++i) {
    if (!covered[i]) {
      EXPECT_EQ(gltf.bin[i], 0) << "padding byte " << i;
    }
  }
  const Json& quantized = gltf.root["meshes"][0]["primitives"][0];
  // VEC3 UNSIGNED_BYTE colours and VEC3 BYTE normals: 3-byte elements in 4.
  const Json& colors = gltf.root["accessors"][quantized["attributes"]["COLOR_0"].get<int>()];
  EXPECT_EQ(gltf.root["bufferViews"][colors["bufferView"].get<int>()]["byteStride"], 4);
  const Json& normals = gltf.root["accessors"][quantized["attributes"]["NORMAL"].get<int>()];
  EXPECT_EQ(gltf.root["bufferViews"][normals["bufferView"].get<int>()]["byteStride"], 4);
  EXPECT_EQ(gltf.root["bufferViews"][normals["bufferView"].get<int>()]["target"], 34962);
  // POSITION bounds in the component type: integers for UNSIGNED_SHORT.
  const Json& position = gltf.root["accessors"][quantized["attributes"]["POSITION"].get<int>()];
  EXPECT_EQ(position["min"], Json({0, 0, 0}));
  EXPECT_EQ(position["max"], Json({1000, 1000, 7}));
  EXPECT_TRUE(position["max"][0].is_number_integer());
  // Small indices take bytes, in an element array view without stride.
  const Json& indices = gltf.root["accessors"][quantized["indices"].get<int>()];
  EXPECT_EQ(indices["componentType"], 5121);
  EXPECT_EQ(gltf.root["bufferViews"][indices["bufferView"].get<int>()]["target"], 34963);
  // The MAT3 of bytes: each column padded to 4 bytes.
  EXPECT_EQ(
      gltf.root["bufferViews"][gltf.root["accessors"][4]["bufferView"].get<int>()]["byteLength"],
      2 * 12);
  // Animation inputs carry bounds; outputs and skins' matrices need none.
  EXPECT_EQ(gltf.root["accessors"][1]["min"], Json({0.0}));
  EXPECT_EQ(gltf.root["accessors"][1]["max"], Json({1.25}));
  EXPECT_FALSE(gltf.root["accessors"][0].contains("min"));
}

TEST(GltfSceneWriter, IndexTypeIsTheSmallestThatFits) {
  const Scene scene = samples::large_indices_scene();
  const Parsed gltf = glb_of(scene);
  const Json& indices =
      gltf.root["accessors"][gltf.root["meshes"][0]["primitives"][0]["indices"].get<int>()];
  EXPECT_EQ(indices["componentType"], 5125);
  EXPECT_EQ(decode_indices(gltf, gltf.root["meshes"][0]["primitives"][0]["indices"]),
            *scene.meshes[0].primitives[0].indices);

  Scene shorter = samples::full_scene();
  shorter.meshes[2].primitives[0].attributes.clear();
  shorter.meshes[2].primitives[0].attributes.push_back(
      {"POSITION", samples::accessor<float>(ComponentType::kFloat, ElementType::kVec3,
                                            std::vector<float>(3 * 300, 1.0f))});
  shorter.meshes[2].primitives[0].indices = std::vector<uint32_t>{0, 255, 299};
  const Parsed out = glb_of(shorter);
  const int at = out.root["meshes"][2]["primitives"][0]["indices"];
  // 255 is UNSIGNED_BYTE's primitive-restart value: glTF forbids it.
  EXPECT_EQ(out.root["accessors"][at]["componentType"], 5123);
  EXPECT_EQ(decode_indices(out, at), (std::vector<uint32_t>{0, 255, 299}));
}

TEST(GltfSceneWriter, NodesKeepTheirTransformPartsAndAssetNamesLodbake) {
  const Scene scene = samples::full_scene();
  const Parsed gltf = glb_of(scene);
  const Json& nodes = gltf.root["nodes"];
  ASSERT_EQ(nodes.size(), scene.nodes.size());
  EXPECT_EQ(nodes[0]["translation"], Json({1, 2, 3}));
  EXPECT_EQ(nodes[0]["scale"], Json({2, 2, 2}));
  EXPECT_FALSE(nodes[0].contains("matrix"));
  EXPECT_EQ(nodes[1]["matrix"].size(), 16u);
  EXPECT_FALSE(nodes[1].contains("translation"));
  EXPECT_EQ(nodes[1]["camera"], 0);
  EXPECT_EQ(nodes[3]["translation"], Json({0.1, -4, 1e-7}));
  EXPECT_FALSE(nodes[3].contains("rotation"));
  EXPECT_FALSE(nodes[3].contains("scale"));
  EXPECT_FALSE(nodes[2].contains("translation"));
  EXPECT_EQ(nodes[2]["extras"], Json({{"id", 2}}));
  EXPECT_EQ(nodes[4]["weights"], Json({0.125, 1.0}));
  EXPECT_EQ(nodes[6]["skin"], 0);
  EXPECT_EQ(gltf.root["scene"], 0);
  EXPECT_EQ(gltf.root["scenes"][0]["nodes"], Json({0, 6, 7}));
  EXPECT_EQ(gltf.root["scenes"][1]["name"], "props");
  EXPECT_EQ(gltf.root["asset"]["version"], "2.0");
  EXPECT_EQ(gltf.root["asset"]["generator"], std::string("lodbake ") + "0.1.0");
  EXPECT_EQ(gltf.root["asset"]["copyright"], "lodbake tests");
  EXPECT_EQ(gltf.root["materials"], scene.materials);
  EXPECT_EQ(gltf.root["cameras"], scene.cameras);
  EXPECT_EQ(gltf.root["extras"], scene.extras);
}

TEST(GltfSceneWriter, GlbEmbedsImagesWithTheirMediaType) {
  const Scene scene = samples::full_scene();
  const Parsed gltf = glb_of(scene);
  const Json& images = gltf.root["images"];
  ASSERT_EQ(images.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_FALSE(images[i].contains("uri"));
    EXPECT_EQ(images[i]["mimeType"], "image/png");  // image 0 recognized from its bytes
    const Json& view = gltf.root["bufferViews"][images[i]["bufferView"].get<int>()];
    const size_t at = view.value("byteOffset", 0u);
    EXPECT_EQ(
        Bytes(gltf.bin.begin() + at, gltf.bin.begin() + at + view["byteLength"].get<size_t>()),
        scene.images[i].bytes);
  }
  EXPECT_EQ(images[0]["name"], "orange");
  EXPECT_EQ(images[1]["extras"], Json({{"source", "scan"}}));
}

TEST(GltfSceneWriter, GltfWritesBinAndImageFilesBesideIt) {
  const Scene scene = samples::full_scene();
  SceneWriteReport report;
  Result<std::vector<SceneOutputFile>> files = write_scene_gltf(scene, "out/truck.gltf", &report);
  ASSERT_TRUE(files.is_ok()) << files.status().message();
  ASSERT_EQ(files.value().size(), 4u);
  EXPECT_EQ(files.value()[0].name, "truck.gltf");
  EXPECT_EQ(files.value()[1].name, "truck.bin");
  EXPECT_EQ(files.value()[2].name, "image_0.png");
  EXPECT_EQ(files.value()[2].bytes, scene.images[0].bytes);
  EXPECT_EQ(files.value()[3].name, "tex/wood grain.png");
  EXPECT_EQ(files.value()[3].bytes, scene.images[1].bytes);
  const Bytes& text = files.value()[0].bytes;
  const Json root = Json::parse(text.begin(), text.end());
  EXPECT_EQ(root["buffers"][0]["uri"], "truck.bin");
  EXPECT_EQ(root["buffers"][0]["byteLength"], files.value()[1].bytes.size());
  EXPECT_EQ(root["images"][0]["uri"], "image_0.png");
  EXPECT_FALSE(root["images"][0].contains("mimeType"));  // as the scene gave it: none
  EXPECT_EQ(root["images"][1]["uri"], "tex/wood%20grain.png");
  EXPECT_EQ(root["images"][1]["mimeType"], "image/png");
  EXPECT_FALSE(root["images"][1].contains("bufferView"));
  EXPECT_TRUE(report.warnings.empty());
  // Same document as the GLB's, but for where the buffer and images are.
  Parsed bin{root, files.value()[1].bytes};
  for (uint32_t i = 0; i < scene.accessors.size(); ++i)
    expect_stream(bin, i, scene.accessors[i]);
}

TEST(GltfSceneWriter, ImageNamesStayInsideTheOutputFolderAndDoNotCollide) {
  Scene scene = samples::missing_image_scene();
  SceneImage image;
  image.bytes = samples::png_2x2();
  for (const char* uri : {"../../etc/passwd", "/abs/x.png", "c:\\x.png", "present.png",
                          "./sub//present.png", "PRESENT.png", "scene.bin"}) {
    image.uri = uri;
    scene.images.push_back(image);
  }
  image.uri = "present.png";
  image.bytes = samples::png_1x1();  // the same file as image 1: shared
  scene.images.push_back(image);
  SceneWriteReport report;
  Result<std::vector<SceneOutputFile>> files = write_scene_gltf(scene, "scene.gltf", &report);
  ASSERT_TRUE(files.is_ok()) << files.status().message();
  std::vector<std::string> names;
  for (const SceneOutputFile& f : files.value())
    names.push_back(f.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"scene.gltf", "scene.bin", "present.png", "image_2.png",
                                      "image_3.png", "image_4.png", "present_5.png",
                                      "sub/present.png", "PRESENT_7.png", "scene_8.bin"}));
  const Json root = Json::parse(files.value()[0].bytes.begin(), files.value()[0].bytes.end());
  EXPECT_EQ(root["images"][9]["uri"], "present.png");
  // The missing image keeps its reference, percent-encoded, and is reported.
  EXPECT_EQ(root["images"][0]["uri"], "absent%20texture.png");
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("absent texture.png"), std::string::npos);
}

TEST(GltfSceneWriter, GlbKeepsAMissingImageReference) {
  SceneWriteReport report;
  const Parsed gltf = glb_of(samples::missing_image_scene(), &report);
  EXPECT_EQ(gltf.root["images"][0]["uri"], "absent%20texture.png");
  EXPECT_FALSE(gltf.root["images"][0].contains("bufferView"));
  EXPECT_TRUE(gltf.root["images"][1].contains("bufferView"));
  EXPECT_EQ(report.warnings.size(), 1u);
}

TEST(GltfSceneWriter, ExtensionListsFollowWhatIsWritten) {
  Scene scene = samples::full_scene();
  scene.extensions_used = {"KHR_draco_mesh_compression"};
  scene.extensions_required = {"KHR_draco_mesh_compression"};
  scene.meshes[2].primitives[0].extensions = {{"KHR_draco_mesh_compression", {{"bufferView", 0}}}};
  SceneWriteReport report;
  const Parsed gltf = glb_of(scene, &report);
  // Quantized streams declare KHR_mesh_quantization as used and required;
  // extensions objects use are declared; the decoded compression goes.
  const Json used = gltf.root["extensionsUsed"];
  EXPECT_EQ(used, Json({"EXT_mesh_gpu_instancing", "KHR_materials_emissive_strength",
                        "KHR_mesh_quantization"}));
  EXPECT_EQ(gltf.root["extensionsRequired"], Json({"KHR_mesh_quantization"}));
  EXPECT_FALSE(gltf.root["meshes"][2]["primitives"][0].contains("extensions"));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("KHR_draco_mesh_compression"), std::string::npos);

  // Float streams only: no quantization extension.
  const Parsed plain = glb_of(samples::large_indices_scene());
  EXPECT_FALSE(plain.root.contains("extensionsUsed"));
  EXPECT_FALSE(plain.root.contains("extensionsRequired"));
}

TEST(GltfSceneWriter, SceneWithoutDataHasNoBuffer) {
  Scene scene;
  scene.nodes.resize(1);
  SceneWriteReport report;
  Result<Bytes> glb = write_scene_glb(scene, &report);
  ASSERT_TRUE(glb.is_ok());
  const Parsed gltf = parse_glb(glb.value());
  EXPECT_FALSE(gltf.root.contains("buffers"));
  EXPECT_TRUE(gltf.bin.empty());
  Result<std::vector<SceneOutputFile>> files = write_scene_gltf(scene, "a.gltf", &report);
  ASSERT_TRUE(files.is_ok());
  EXPECT_EQ(files.value().size(), 1u);
}

TEST(GltfSceneWriter, EqualScenesGiveEqualBytes) {
  SceneWriteReport report;
  Result<Bytes> a = write_scene_glb(samples::full_scene(), &report);
  Result<Bytes> b = write_scene_glb(samples::full_scene(), &report);
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  EXPECT_EQ(a.value(), b.value());
  Scene changed = samples::full_scene();
  changed.nodes[3].translation->at(0) = 0.2;
  Result<Bytes> c = write_scene_glb(changed, &report);
  ASSERT_TRUE(c.is_ok());
  EXPECT_NE(a.value(), c.value());
}

TEST(GltfSceneWriter, ScenesThatCannotBeValidGltfAreRefused) {
  SceneWriteReport report;
  Scene empty_stream = samples::full_scene();
  empty_stream.meshes[2].primitives[0].attributes[1].data.count = 0;
  empty_stream.meshes[2].primitives[0].attributes[1].data.bytes.clear();
  Result<Bytes> out = write_scene_glb(empty_stream, &report);
  ASSERT_FALSE(out.is_ok());
  EXPECT_EQ(out.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(out.status().message().find("mesh 2 primitive 0 attribute"), std::string::npos)
      << out.status().message();

  Scene bad_index = samples::full_scene();
  (*bad_index.meshes[2].primitives[0].indices)[1] = 3;
  out = write_scene_glb(bad_index, &report);
  ASSERT_FALSE(out.is_ok());
  EXPECT_NE(out.status().message().find("out of range (3 vertices)"), std::string::npos)
      << out.status().message();

  Scene bad_skin = samples::full_scene();
  bad_skin.skins[0]["inverseBindMatrices"] = 5;
  out = write_scene_glb(bad_skin, &report);
  ASSERT_FALSE(out.is_ok());
  EXPECT_NE(out.status().message().find("skin 0"), std::string::npos) << out.status().message();

  Scene short_bytes = samples::full_scene();
  short_bytes.accessors[1].bytes.pop_back();
  out = write_scene_glb(short_bytes, &report);
  ASSERT_FALSE(out.is_ok());
  EXPECT_EQ(out.status().kind(), ErrorKind::kInvalidInput);
}

TEST(SceneCompare, NamesTheFirstDifference) {
  const Scene a = samples::full_scene();
  EXPECT_EQ(first_scene_difference(a, a), "");
  Scene b = a;
  b.generator = "another tool";  // not part of equality
  EXPECT_EQ(first_scene_difference(a, b), "");

  b = a;
  float half = 0.5f;
  std::memcpy(b.meshes[0].primitives[1].attributes[2].data.bytes.data() + 3 * 4, &half, 4);
  EXPECT_EQ(first_scene_difference(a, b),
            "mesh 0 primitive 1 attribute TEXCOORD_0: element 1 component 1 differs (0 vs 0.5)");

  b = a;
  b.nodes[3].translation.reset();
  EXPECT_EQ(first_scene_difference(a, b),
            "node 3 translation differs ([0.1,-4.0,1e-07] vs absent)");

  b = a;
  b.materials[0]["name"] = "matte";
  EXPECT_EQ(first_scene_difference(a, b), "materials differ at /0/name (\"painted\" vs \"matte\")");

  b = a;
  (*b.meshes[0].primitives[0].indices)[4] = 0;
  EXPECT_EQ(first_scene_difference(a, b), "mesh 0 primitive 0 index 4 differs (1 vs 0)");

  b = a;
  b.images[1].uri = "elsewhere.png";
  b.images[1].mime_type.clear();
  EXPECT_EQ(first_scene_difference(a, b), "image 1 mime type differs (\"image/png\" vs \"\")");
  SceneCompareOptions bytes_only;
  bytes_only.image_storage = false;
  EXPECT_EQ(first_scene_difference(a, b, bytes_only), "");
  b.images[1].bytes[20] ^= 1;
  EXPECT_EQ(first_scene_difference(a, b, bytes_only),
            "image 1 bytes differ from byte 20 (73 vs 73 bytes)");

  b = a;
  b.accessors.pop_back();
  EXPECT_EQ(first_scene_difference(a, b), "accessor count differs (5 vs 4)");
}

}  // namespace
}  // namespace lodbake
