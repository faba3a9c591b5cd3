// The asset model every lodbake tool exchanges beside TriangleMesh: a glTF
// 2.0 scene as plain data. Nodes (matrix or TRS, children) use meshes (one
// mesh may be used by many nodes: instancing); a mesh has primitives, each
// with a mode, a material, an index buffer and attribute streams by glTF
// semantic (POSITION, NORMAL, TANGENT, TEXCOORD_n, COLOR_n, JOINTS_n,
// WEIGHTS_n, custom _NAME) and morph targets. Everything lodbake does not
// process (materials, textures, samplers, images, skins, animations, cameras,
// extras, extensions) is carried through as the file's JSON, with the
// accessors and images it refers to held as data here, so a writer can put
// them back whatever buffers it lays out.
//
// Plain data with no behaviour beyond small helpers, so that formats/ (which
// must not depend on lib/) can hold it; readers and writers live in lib/.
// Every stream is decoded: no compression extension (KHR_draco_mesh_compression,
// EXT_meshopt_compression) and no sparse accessor survives reading, and
// KHR_mesh_quantization's integer types are kept as they are.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lodbake {

using SceneJson = nlohmann::json;

// glTF accessor.componentType codes.
enum class ComponentType : uint16_t {
  kByte = 5120,
  kUnsignedByte = 5121,
  kShort = 5122,
  kUnsignedShort = 5123,
  kUnsignedInt = 5125,
  kFloat = 5126,
};

// glTF accessor.type.
enum class ElementType : uint8_t { kScalar, kVec2, kVec3, kVec4, kMat2, kMat3, kMat4 };

// Bytes of one component (1, 2 or 4).
inline uint32_t component_size(ComponentType t) {
  switch (t) {
    case ComponentType::kByte:
    case ComponentType::kUnsignedByte:
      return 1;
    case ComponentType::kShort:
    case ComponentType::kUnsignedShort:
      return 2;
    default:
      return 4;
  }
}

// Components of one element (1 to 16).
inline uint32_t component_count(ElementType t) {
  static constexpr uint32_t kCounts[] = {1, 2, 3, 4, 4, 9, 16};
  return kCounts[static_cast<int>(t)];
}

// A dense accessor: `count` elements of component_count(type) components of
// `component_type`, tightly packed in little-endian order (matrices column by
// column, without the column padding glTF buffers need for 1- and 2-byte
// matrix components). Sparse accessors are read into this dense form.
struct AccessorData {
  ComponentType component_type = ComponentType::kFloat;
  ElementType type = ElementType::kScalar;
  bool normalized = false;
  uint32_t count = 0;
  std::vector<uint8_t> bytes;  // count * element_size() bytes
  std::string name;            // accessor.name, carried

  uint32_t components() const { return component_count(type); }
  uint32_t element_size() const { return component_size(component_type) * components(); }
  bool operator==(const AccessorData& o) const {
    return component_type == o.component_type && type == o.type && normalized == o.normalized &&
           count == o.count && bytes == o.bytes && name == o.name;
  }
  bool operator!=(const AccessorData& o) const { return !(*this == o); }
};

// One attribute stream of a primitive or morph target, by glTF semantic.
struct SceneAttribute {
  std::string semantic;  // "POSITION", "TEXCOORD_1", "_FEATURE_ID_0", ...
  AccessorData data;
  bool operator==(const SceneAttribute& o) const {
    return semantic == o.semantic && data == o.data;
  }
};

// glTF primitive.mode.
enum class PrimitiveMode : uint8_t {
  kPoints = 0,
  kLines = 1,
  kLineLoop = 2,
  kLineStrip = 3,
  kTriangles = 4,
  kTriangleStrip = 5,
  kTriangleFan = 6,
};

struct ScenePrimitive {
  PrimitiveMode mode = PrimitiveMode::kTriangles;
  int32_t material = -1;  // index into Scene::materials, -1 when absent
  // Absent index buffer: vertices are used in order (glTF non-indexed).
  std::optional<std::vector<uint32_t>> indices;
  // Sorted by semantic (the order glTF's JSON object gives no meaning to),
  // so that equal primitives compare equal.
  std::vector<SceneAttribute> attributes;
  std::vector<std::vector<SceneAttribute>> targets;  // morph targets, each sorted by semantic
  SceneJson extras;                                  // null when absent
  SceneJson extensions;  // null when absent; decoded compression extensions removed

  // The stream named `semantic`, or nullptr.
  const SceneAttribute* find(const std::string& semantic) const {
    for (const SceneAttribute& a : attributes)
      if (a.semantic == semantic) return &a;
    return nullptr;
  }
  uint32_t vertex_count() const {
    const SceneAttribute* p = find("POSITION");
    return p != nullptr ? p->data.count : 0;
  }
  bool operator==(const ScenePrimitive& o) const {
    return mode == o.mode && material == o.material && indices == o.indices &&
           attributes == o.attributes && targets == o.targets && extras == o.extras &&
           extensions == o.extensions;
  }
};

struct SceneMesh {
  std::string name;
  std::vector<ScenePrimitive> primitives;
  std::vector<float> weights;  // default morph weights
  SceneJson extras;
  SceneJson extensions;
  // The primitives of one mesh share positions along their borders: vertex v
  // of primitive p is point point_of_vertex[p][v], and two vertices (of the
  // same or different primitives) are the same point exactly when their
  // POSITION values are bit-for-bit equal. Derived from the streams by
  // weld_mesh_points() (lib/scene); not part of equality.
  std::vector<std::vector<uint32_t>> point_of_vertex;
  uint32_t point_count = 0;

  bool operator==(const SceneMesh& o) const {
    return name == o.name && primitives == o.primitives && weights == o.weights &&
           extras == o.extras && extensions == o.extensions;
  }
};

struct SceneNode {
  std::string name;
  int32_t mesh = -1;
  int32_t skin = -1;
  int32_t camera = -1;
  std::vector<uint32_t> children;
  // glTF allows a matrix or TRS; what the file gave is kept, absent parts
  // stay absent (so a writer gives back the same JSON).
  std::optional<std::array<double, 16>> matrix;  // column-major
  std::optional<std::array<double, 3>> translation;
  std::optional<std::array<double, 4>> rotation;  // quaternion x, y, z, w
  std::optional<std::array<double, 3>> scale;
  std::vector<float> weights;
  SceneJson extras;
  SceneJson extensions;

  bool operator==(const SceneNode& o) const {
    return name == o.name && mesh == o.mesh && skin == o.skin && camera == o.camera &&
           children == o.children && matrix == o.matrix && translation == o.translation &&
           rotation == o.rotation && scale == o.scale && weights == o.weights &&
           extras == o.extras && extensions == o.extensions;
  }
};

// glTF scenes[i].
struct SceneRoots {
  std::string name;
  std::vector<uint32_t> nodes;
  SceneJson extras;
  SceneJson extensions;
  bool operator==(const SceneRoots& o) const {
    return name == o.name && nodes == o.nodes && extras == o.extras && extensions == o.extensions;
  }
};

struct SceneImage {
  std::string name;
  std::string mime_type;  // as the file gave it, or empty
  // The file name to write the image under beside a .gltf: the URI the
  // input gave (percent-decoded, relative), or empty for an embedded image
  // (bufferView or data: URI), which a writer names itself.
  std::string uri;
  std::vector<uint8_t> bytes;
  // The input named a file that is not there (read with a warning): a
  // writer keeps the reference and has no bytes to write.
  bool missing = false;
  SceneJson extras;
  SceneJson extensions;
  bool operator==(const SceneImage& o) const {
    return name == o.name && mime_type == o.mime_type && uri == o.uri && bytes == o.bytes &&
           missing == o.missing && extras == o.extras && extensions == o.extensions;
  }
};

struct Scene {
  // The file's "asset" object without "version" and "generator"
  // (copyright, minVersion, extras, extensions): a writer writes version
  // 2.0 and names lodbake as the generator.
  SceneJson asset;
  std::string generator;  // the input's asset.generator; not part of equality
  std::vector<SceneRoots> scenes;
  int32_t default_scene = -1;  // glTF "scene", -1 when absent
  std::vector<SceneNode> nodes;
  std::vector<SceneMesh> meshes;
  std::vector<SceneImage> images;
  // Accessors that carried JSON refers to (skin.inverseBindMatrices,
  // animation sampler input and output, extension data such as
  // EXT_mesh_gpu_instancing attributes). In the carried JSON below, every
  // such reference is an index into this vector, and every image reference
  // an index into `images`.
  std::vector<AccessorData> accessors;
  // Top-level arrays carried unchanged (JSON arrays; null when absent).
  SceneJson materials;
  SceneJson textures;
  SceneJson samplers;
  SceneJson skins;
  SceneJson animations;
  SceneJson cameras;
  // extensionsUsed / extensionsRequired as the reader leaves them (decoded
  // compression extensions removed); top-level extensions and extras.
  std::vector<std::string> extensions_used;
  std::vector<std::string> extensions_required;
  SceneJson extensions;
  SceneJson extras;

  bool operator==(const Scene& o) const {
    return asset == o.asset && scenes == o.scenes && default_scene == o.default_scene &&
           nodes == o.nodes && meshes == o.meshes && images == o.images &&
           accessors == o.accessors && materials == o.materials && textures == o.textures &&
           samplers == o.samplers && skins == o.skins && animations == o.animations &&
           cameras == o.cameras && extensions_used == o.extensions_used &&
           extensions_required == o.extensions_required && extensions == o.extensions &&
           extras == o.extras;
  }
};

}  // namespace lodbake
