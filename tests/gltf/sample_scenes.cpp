// Hand-built sample scenes (sample_scenes.h). Every stream holds valid data
// (unit normals, weights summing to one, increasing animation times), so that
// the validator's findings are the writer's.
#include "tests/gltf/sample_scenes.h"

namespace lodbake {
namespace sample_scenes {

std::vector<uint8_t> png_1x1() {
  return {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
          0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00,
          0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x78,
          0xda, 0x63, 0xf8, 0xdf, 0xc0, 0x00, 0x00, 0x04, 0x01, 0x01, 0x80, 0xfb, 0xd7, 0xcb,
          0xf1, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
}

std::vector<uint8_t> png_2x2() {
  return {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
          0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x02, 0x00, 0x00, 0x00, 0xfd,
          0xd4, 0x9a, 0x73, 0x00, 0x00, 0x00, 0x10, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xe0,
          0x3a, 0x21, 0x07, 0x44, 0x0c, 0x10, 0x0a, 0x00, 0x19, 0xfe, 0x03, 0xc1, 0x43, 0x31, 0xb0,
          0xdd, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
}

namespace {

using Json = nlohmann::json;
using CT = ComponentType;
using ET = ElementType;

SceneAttribute stream(const std::string& semantic, AccessorData data) {
  return SceneAttribute{semantic, std::move(data)};
}

// A float triangle: one position per vertex, upward normals.
ScenePrimitive float_triangle(float offset) {
  ScenePrimitive p;
  p.attributes.push_back(
      stream("NORMAL", accessor<float>(CT::kFloat, ET::kVec3, {0, 0, 1, 0, 0, 1, 0, 0, 1})));
  p.attributes.push_back(stream(
      "POSITION",
      accessor<float>(CT::kFloat, ET::kVec3, {offset, 0, 0, offset + 1, 0, 0, offset, 1, 0})));
  p.indices = std::vector<uint32_t>{0, 1, 2};
  return p;
}

}  // namespace

Scene full_scene() {
  Scene s;
  s.asset = {{"copyright", "lodbake tests"}, {"extras", {{"made_by", "sample_scenes"}}}};
  s.generator = "hand";

  // Mesh 0: quantized streams (3-byte elements that need padding to a
  // 4-byte stride), small indices; a non-indexed float primitive; a line
  // primitive with a custom attribute.
  SceneMesh quantized;
  quantized.name = "quantized";
  {
    ScenePrimitive p;
    p.material = 0;
    p.attributes.push_back(
        stream("COLOR_0", accessor<uint8_t>(CT::kUnsignedByte, ET::kVec3,
                                            {255, 0, 0, 0, 255, 0, 0, 0, 255, 9, 9, 9}, true)));
    p.attributes.push_back(
        stream("NORMAL", accessor<int8_t>(CT::kByte, ET::kVec3,
                                          {0, 0, 127, 0, 0, 127, 0, 0, 127, 0, 127, 0}, true)));
    p.attributes.push_back(
        stream("POSITION", accessor<uint16_t>(CT::kUnsignedShort, ET::kVec3,
                                              {0, 0, 0, 1000, 0, 0, 0, 1000, 0, 1000, 1000, 7})));
    p.attributes.push_back(
        stream("TEXCOORD_0", accessor<uint16_t>(CT::kUnsignedShort, ET::kVec2,
                                                {0, 0, 65535, 0, 0, 65535, 65535, 65535}, true)));
    p.indices = std::vector<uint32_t>{0, 1, 2, 2, 1, 3};
    p.extras = {{"part", "body"}};
    quantized.primitives.push_back(std::move(p));
  }
  {
    ScenePrimitive p = float_triangle(2);
    p.material = 0;
    p.indices.reset();  // drawn in vertex order
    p.attributes.push_back(
        stream("TEXCOORD_0", accessor<float>(CT::kFloat, ET::kVec2, {0, 0, 1, 0, 0, 1})));
    quantized.primitives.push_back(std::move(p));
  }
  {
    ScenePrimitive p;
    p.mode = PrimitiveMode::kLines;
    p.attributes.push_back(
        stream("POSITION", accessor<float>(CT::kFloat, ET::kVec3, {0, 0, 0, 0, 0, 5})));
    p.attributes.push_back(
        stream("_TEMPERATURE", accessor<float>(CT::kFloat, ET::kScalar, {20.5f, -3.25f})));
    p.indices = std::vector<uint32_t>{0, 1};
    quantized.primitives.push_back(std::move(p));
  }
  quantized.extras = {{"lod", 0}};
  s.meshes.push_back(std::move(quantized));

  // Mesh 1: two morph targets, one of them quantized.
  SceneMesh morph;
  morph.name = "morph";
  {
    ScenePrimitive p = float_triangle(0);
    p.targets.push_back({stream(
        "POSITION", accessor<float>(CT::kFloat, ET::kVec3, {0, 0, 1, 0, 0, 1, 0, 0, 0.5f}))});
    p.targets.push_back(
        {stream("NORMAL",
                accessor<int8_t>(CT::kByte, ET::kVec3, {0, 10, 0, 0, -10, 0, 0, 0, 0}, true)),
         stream("POSITION", accessor<int16_t>(CT::kShort, ET::kVec3,
                                              {0, 0, -32767, 0, 0, 100, 0, 0, 0}, true))});
    morph.primitives.push_back(std::move(p));
  }
  morph.weights = {0.5f, 0.25f};
  s.meshes.push_back(std::move(morph));

  // Mesh 2: used by an instanced node.
  SceneMesh instanced;
  instanced.name = "instanced";
  instanced.primitives.push_back(float_triangle(0));
  s.meshes.push_back(std::move(instanced));

  // Mesh 3: skinned by two joints.
  SceneMesh skinned;
  skinned.name = "skinned";
  {
    ScenePrimitive p = float_triangle(0);
    p.attributes.insert(
        p.attributes.begin(),
        stream("JOINTS_0", accessor<uint8_t>(CT::kUnsignedByte, ET::kVec4,
                                             {0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0})));
    p.attributes.push_back(
        stream("WEIGHTS_0", accessor<uint8_t>(CT::kUnsignedByte, ET::kVec4,
                                              {128, 127, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0}, true)));
    skinned.primitives.push_back(std::move(p));
  }
  s.meshes.push_back(std::move(skinned));

  // Carried accessors: 0 inverse bind matrices, 1 animation times, 2
  // animation translations, 3 instance translations, 4 a MAT3 of bytes
  // (columns padded to 4 bytes in the buffer).
  std::vector<float> ibm(32, 0.0f);
  for (int m = 0; m < 2; ++m)
    for (int d = 0; d < 4; ++d)
      ibm[m * 16 + d * 5] = 1.0f;
  ibm[16 + 13] = -1.0f;  // joint 1 sits at y = 1
  s.accessors.push_back(accessor<float>(CT::kFloat, ET::kMat4, ibm));
  s.accessors.push_back(accessor<float>(CT::kFloat, ET::kScalar, {0.0f, 0.5f, 1.25f}));
  s.accessors.push_back(accessor<float>(CT::kFloat, ET::kVec3, {0, 1, 0, 0, 2, 0, 0.5f, 1, 0}));
  s.accessors.push_back(accessor<float>(CT::kFloat, ET::kVec3, {0, 0, 0, 3, 0, 0, 6, 0, 0}));
  s.accessors.push_back(
      accessor<uint8_t>(CT::kUnsignedByte, ET::kMat3,
                        {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18}));
  s.accessors.back().name = "byte matrices";

  // Nodes: 0 the root (TRS); 1 a matrix with a camera; 2 and 3 share mesh
  // 0; 4 the morph mesh with its own weights; 5 instanced; 6 skinned by
  // joints 7 and 8.
  s.nodes.resize(9);
  s.nodes[0].name = "root";
  s.nodes[0].children = {1, 2, 3, 4, 5};
  s.nodes[0].translation = std::array<double, 3>{1, 2, 3};
  s.nodes[0].rotation = std::array<double, 4>{0, 0.7071067811865476, 0, 0.7071067811865476};
  s.nodes[0].scale = std::array<double, 3>{2, 2, 2};
  s.nodes[1].name = "camera";
  s.nodes[1].camera = 0;
  s.nodes[1].matrix = std::array<double, 16>{2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 5, 6, 7, 1};
  s.nodes[2].mesh = 0;
  s.nodes[2].extras = {{"id", 2}};
  s.nodes[3].mesh = 0;
  s.nodes[3].translation = std::array<double, 3>{0.1, -4, 1e-7};
  s.nodes[4].mesh = 1;
  s.nodes[4].weights = {0.125f, 1.0f};
  s.nodes[5].mesh = 2;
  s.nodes[5].extensions = {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", 3}}}}}};
  s.nodes[6].name = "skinned";
  s.nodes[6].mesh = 3;
  s.nodes[6].skin = 0;
  s.nodes[7].name = "hip";
  s.nodes[7].children = {8};
  s.nodes[8].name = "knee";
  s.nodes[8].translation = std::array<double, 3>{0, 1, 0};

  SceneRoots roots;
  roots.name = "main";
  roots.nodes = {0, 6, 7};
  roots.extras = {{"layer", "all"}};
  s.scenes.push_back(roots);
  SceneRoots props;
  props.name = "props";
  props.nodes = {7};
  s.scenes.push_back(props);
  s.default_scene = 0;

  SceneImage embedded;
  embedded.name = "orange";
  embedded.bytes = png_1x1();  // no media type given: a writer recognizes it
  s.images.push_back(embedded);
  SceneImage named;
  named.uri = "tex/wood grain.png";
  named.mime_type = "image/png";
  named.bytes = png_2x2();
  named.extras = {{"source", "scan"}};
  s.images.push_back(named);

  s.samplers = Json::array({{{"magFilter", 9729}, {"wrapS", 33071}}});
  s.textures = Json::array({{{"source", 0}, {"sampler", 0}}, {{"source", 1}}});
  s.materials = Json::array(
      {{{"name", "painted"},
        {"pbrMetallicRoughness",
         {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 1}}}}},
        {"emissiveFactor", {1, 0.5, 0}},
        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 2.5}}}}}}});
  s.cameras = Json::array(
      {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 100}}}}});
  s.skins = Json::array({{{"joints", {7, 8}}, {"inverseBindMatrices", 0}, {"skeleton", 7}}});
  s.animations = Json::array(
      {{{"name", "walk"},
        {"samplers", {{{"input", 1}, {"output", 2}, {"interpolation", "LINEAR"}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", 8}, {"path", "translation"}}}}}}}});
  s.extensions_used = {"KHR_materials_emissive_strength", "EXT_mesh_gpu_instancing",
                       "KHR_mesh_quantization"};
  s.extensions_required = {"KHR_mesh_quantization"};
  s.extras = {{"note", "hand-built"}};
  return s;
}

Scene large_indices_scene() {
  // A triangle strip's worth of triangles over 70,000 vertices: the indices
  // need UNSIGNED_INT.
  Scene s;
  constexpr uint32_t kColumns = 35000;
  std::vector<float> positions;
  for (uint32_t c = 0; c < kColumns; ++c) {
    for (int row = 0; row < 2; ++row) {
      positions.push_back(static_cast<float>(c) * 0.01f);
      positions.push_back(static_cast<float>(row));
      positions.push_back(0.0f);
    }
  }
  ScenePrimitive p;
  p.attributes.push_back(stream("POSITION", accessor<float>(CT::kFloat, ET::kVec3, positions)));
  std::vector<uint32_t> indices;
  for (uint32_t c = 0; c + 1 < kColumns; ++c) {
    const uint32_t a = 2 * c;
    indices.insert(indices.end(), {a, a + 2, a + 1, a + 1, a + 2, a + 3});
  }
  p.indices = std::move(indices);
  SceneMesh mesh;
  mesh.primitives.push_back(std::move(p));
  s.meshes.push_back(std::move(mesh));
  s.nodes.resize(1);
  s.nodes[0].mesh = 0;
  s.scenes.push_back(SceneRoots{"", {0}, nullptr, nullptr});
  s.default_scene = 0;
  return s;
}

Scene missing_image_scene() {
  Scene s;
  SceneMesh mesh;
  ScenePrimitive p = float_triangle(0);
  p.attributes.push_back(
      stream("TEXCOORD_0", accessor<float>(CT::kFloat, ET::kVec2, {0, 0, 1, 0, 0, 1})));
  p.material = 0;
  mesh.primitives.push_back(std::move(p));
  s.meshes.push_back(std::move(mesh));
  s.nodes.resize(1);
  s.nodes[0].mesh = 0;
  SceneImage missing;
  missing.uri = "absent texture.png";
  missing.missing = true;
  s.images.push_back(missing);
  SceneImage present;
  present.uri = "present.png";
  present.bytes = png_1x1();
  s.images.push_back(present);
  s.textures = Json::array({{{"source", 0}}, {{"source", 1}}});
  s.materials = Json::array(
      {{{"pbrMetallicRoughness",
         {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 1}}}}}}});
  return s;
}

std::vector<NamedScene> all() {
  std::vector<NamedScene> out;
  out.push_back({"full", full_scene(), {}});
  out.push_back({"large_indices", large_indices_scene(), {}});
  out.push_back({"missing_image", missing_image_scene(), {"absent texture.png"}});
  Scene empty;
  empty.nodes.resize(1);
  empty.nodes[0].name = "lonely";
  out.push_back({"empty", std::move(empty), {}});
  return out;
}

}  // namespace sample_scenes
}  // namespace lodbake
