// A Scene as glTF 2.0 JSON and one buffer (gltf_scene_json.h).
#include "lib/dracoio/gltf_scene_json.h"

#include <algorithm>
#include <set>
#include <utility>

#include "formats/support/version.h"
#include "lib/dracoio/gltf_buffer_writer.h"
#include "lib/dracoio/gltf_image_files.h"

namespace lodbake {
namespace dracoio {
namespace {

using Json = nlohmann::json;

constexpr char kQuantization[] = "KHR_mesh_quantization";
constexpr char kInstancing[] = "EXT_mesh_gpu_instancing";

// Extensions whose data lodbake holds decoded: writing the extension object
// back would describe bytes that are not there.
const std::set<std::string>& decoded_extensions() {
  static const std::set<std::string> kNames = {
      "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"};
  return kNames;
}

bool has_prefix(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

// True when the stream's type is outside glTF 2.0's core attribute table and
// inside KHR_mesh_quantization's (integer positions, normals and tangents;
// non-normalized or signed texture coordinates).
bool needs_quantization(const std::string& semantic, const AccessorData& data) {
  const bool is_float = data.component_type == ComponentType::kFloat;
  if (semantic == "POSITION" || semantic == "NORMAL" || semantic == "TANGENT") return !is_float;
  if (has_prefix(semantic, "TEXCOORD_")) {
    const bool core_integer =
        data.normalized && (data.component_type == ComponentType::kUnsignedByte ||
                            data.component_type == ComponentType::kUnsignedShort);
    return !is_float && !core_integer;
  }
  return false;
}

void put_if_present(Json* object, const char* key, const Json& value) {
  if (!value.is_null()) (*object)[key] = value;
}

size_t array_size(const Json& value) {
  return value.is_array() ? value.size() : 0;
}

Status check_index(int64_t index, size_t limit, const char* what, const std::string& where) {
  if (index < 0 || static_cast<uint64_t>(index) >= limit) {
    return invalid_input(where + " refers to " + what + " " + std::to_string(index) +
                         ", out of range (" + std::to_string(limit) + ")");
  }
  return Status::ok();
}

// A reference in carried JSON into Scene::accessors, when present.
Status check_accessor_ref(const Json& object, const char* key, size_t limit,
                          const std::string& where, std::vector<bool>* mark = nullptr) {
  if (!object.is_object() || !object.contains(key)) return Status::ok();
  const Json& value = object[key];
  if (!value.is_number_integer())
    return invalid_input(where + ": '" + key + "' is not an accessor index");
  const int64_t index = value.get<int64_t>();
  LODBAKE_RETURN_IF_ERROR(check_index(index, limit, "accessor", where + " " + key));
  if (mark != nullptr) (*mark)[static_cast<size_t>(index)] = true;
  return Status::ok();
}

// Checks every reference the carried JSON makes into Scene::accessors and
// marks the animation inputs, which glTF requires to have min and max.
Status check_carried_references(const Scene& scene, std::vector<bool>* animation_inputs) {
  const size_t n = scene.accessors.size();
  if (scene.skins.is_array()) {
    for (size_t s = 0; s < scene.skins.size(); ++s) {
      LODBAKE_RETURN_IF_ERROR(check_accessor_ref(scene.skins[s], "inverseBindMatrices", n,
                                                 "skin " + std::to_string(s)));
    }
  }
  if (scene.animations.is_array()) {
    for (size_t a = 0; a < scene.animations.size(); ++a) {
      const Json& animation = scene.animations[a];
      if (!animation.is_object() || !animation.contains("samplers") ||
          !animation["samplers"].is_array()) {
        continue;
      }
      const Json& samplers = animation["samplers"];
      for (size_t s = 0; s < samplers.size(); ++s) {
        const std::string where =
            "animation " + std::to_string(a) + " sampler " + std::to_string(s);
        LODBAKE_RETURN_IF_ERROR(
            check_accessor_ref(samplers[s], "input", n, where, animation_inputs));
        LODBAKE_RETURN_IF_ERROR(check_accessor_ref(samplers[s], "output", n, where));
      }
    }
  }
  for (size_t i = 0; i < scene.nodes.size(); ++i) {
    const Json& ext = scene.nodes[i].extensions;
    if (!ext.is_object() || !ext.contains(kInstancing) || !ext[kInstancing].is_object()) continue;
    const Json& attributes = ext[kInstancing].value("attributes", Json());
    if (!attributes.is_object()) continue;
    for (auto it = attributes.begin(); it != attributes.end(); ++it) {
      LODBAKE_RETURN_IF_ERROR(check_accessor_ref(attributes, it.key().c_str(), n,
                                                 "node " + std::to_string(i) + " " + kInstancing));
    }
  }
  return Status::ok();
}

class SceneJsonBuilder {
 public:
  SceneJsonBuilder(const Scene& scene, const std::vector<std::string>* image_uris,
                   SceneWriteReport* report)
      : scene_(scene), image_uris_(image_uris), report_(report) {}

  Result<SceneGltf> build() {
    std::vector<bool> animation_inputs(scene_.accessors.size(), false);
    LODBAKE_RETURN_IF_ERROR(check_carried_references(scene_, &animation_inputs));
    for (size_t i = 0; i < scene_.accessors.size(); ++i) {
      LODBAKE_ASSIGN_OR_RETURN(
          uint32_t index,
          buffer_.add_accessor(scene_.accessors[i], GltfBufferWriter::Use::kOther,
                               animation_inputs[i], "accessor " + std::to_string(i)));
      (void)index;  // carried accessors keep their positions 0..n-1
    }
    LODBAKE_RETURN_IF_ERROR(write_meshes());
    LODBAKE_RETURN_IF_ERROR(write_nodes_and_scenes());
    LODBAKE_RETURN_IF_ERROR(write_images());
    write_carried();
    write_extension_lists();
    if (!buffer_.accessors().empty()) root_["accessors"] = buffer_.accessors();
    if (!buffer_.buffer_views().empty()) root_["bufferViews"] = buffer_.buffer_views();
    SceneGltf out;
    out.root = std::move(root_);
    out.bin = buffer_.bytes();
    return out;
  }

 private:
  void warn(std::string message) {
    if (report_ != nullptr) report_->warnings.push_back(std::move(message));
  }

  Result<Json> write_streams(const std::vector<SceneAttribute>& streams, uint32_t vertex_count,
                             const std::string& where) {
    Json attributes = Json::object();
    for (const SceneAttribute& attribute : streams) {
      const std::string name = where + " attribute " + attribute.semantic;
      if (attribute.data.count != vertex_count) {
        return invalid_input(name + " has " + std::to_string(attribute.data.count) +
                             " elements, the primitive " + std::to_string(vertex_count) +
                             " vertices");
      }
      if (needs_quantization(attribute.semantic, attribute.data)) quantized_ = true;
      LODBAKE_ASSIGN_OR_RETURN(
          uint32_t index, buffer_.add_accessor(attribute.data, GltfBufferWriter::Use::kVertices,
                                               attribute.semantic == "POSITION", name));
      attributes[attribute.semantic] = index;
    }
    return attributes;
  }

  Status write_meshes() {
    Json meshes = Json::array();
    for (size_t m = 0; m < scene_.meshes.size(); ++m) {
      const SceneMesh& mesh = scene_.meshes[m];
      const std::string mesh_where = "mesh " + std::to_string(m);
      if (mesh.primitives.empty()) return invalid_input(mesh_where + " has no primitives");
      Json primitives = Json::array();
      for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const ScenePrimitive& primitive = mesh.primitives[p];
        const std::string where = mesh_where + " primitive " + std::to_string(p);
        if (primitive.attributes.empty()) return invalid_input(where + " has no attributes");
        const uint32_t vertex_count = primitive.attributes.front().data.count;
        Json out = {{"mode", static_cast<int>(primitive.mode)}};
        LODBAKE_ASSIGN_OR_RETURN(out["attributes"],
                                 write_streams(primitive.attributes, vertex_count, where));
        if (primitive.indices) {
          LODBAKE_ASSIGN_OR_RETURN(
              out["indices"],
              buffer_.add_indices(*primitive.indices, vertex_count, where + " indices"));
        }
        if (primitive.material >= 0) {
          LODBAKE_RETURN_IF_ERROR(
              check_index(primitive.material, array_size(scene_.materials), "material", where));
          out["material"] = primitive.material;
        }
        if (!primitive.targets.empty()) {
          Json targets = Json::array();
          for (size_t t = 0; t < primitive.targets.size(); ++t) {
            LODBAKE_ASSIGN_OR_RETURN(Json target,
                                     write_streams(primitive.targets[t], vertex_count,
                                                   where + " target " + std::to_string(t)));
            targets.push_back(std::move(target));
          }
          out["targets"] = std::move(targets);
        }
        put_if_present(&out, "extras", primitive.extras);
        put_if_present(&out, "extensions", primitive.extensions);
        primitives.push_back(std::move(out));
      }
      Json out = {{"primitives", std::move(primitives)}};
      if (!mesh.name.empty()) out["name"] = mesh.name;
      if (!mesh.weights.empty()) out["weights"] = mesh.weights;
      put_if_present(&out, "extras", mesh.extras);
      put_if_present(&out, "extensions", mesh.extensions);
      meshes.push_back(std::move(out));
    }
    if (!meshes.empty()) root_["meshes"] = std::move(meshes);
    return Status::ok();
  }

  Status write_nodes_and_scenes() {
    Json nodes = Json::array();
    for (size_t i = 0; i < scene_.nodes.size(); ++i) {
      const SceneNode& node = scene_.nodes[i];
      const std::string where = "node " + std::to_string(i);
      Json out = Json::object();
      if (!node.name.empty()) out["name"] = node.name;
      if (node.mesh >= 0) {
        LODBAKE_RETURN_IF_ERROR(check_index(node.mesh, scene_.meshes.size(), "mesh", where));
        out["mesh"] = node.mesh;
      }
      if (node.skin >= 0) {
        LODBAKE_RETURN_IF_ERROR(check_index(node.skin, array_size(scene_.skins), "skin", where));
        out["skin"] = node.skin;
      }
      if (node.camera >= 0) {
        LODBAKE_RETURN_IF_ERROR(
            check_index(node.camera, array_size(scene_.cameras), "camera", where));
        out["camera"] = node.camera;
      }
      for (const uint32_t child : node.children)
        LODBAKE_RETURN_IF_ERROR(check_index(child, scene_.nodes.size(), "node", where));
      if (!node.children.empty()) out["children"] = node.children;
      if (node.matrix) out["matrix"] = *node.matrix;
      if (node.translation) out["translation"] = *node.translation;
      if (node.rotation) out["rotation"] = *node.rotation;
      if (node.scale) out["scale"] = *node.scale;
      if (!node.weights.empty()) out["weights"] = node.weights;
      put_if_present(&out, "extras", node.extras);
      put_if_present(&out, "extensions", node.extensions);
      nodes.push_back(std::move(out));
    }
    if (!nodes.empty()) root_["nodes"] = std::move(nodes);

    Json scenes = Json::array();
    for (size_t s = 0; s < scene_.scenes.size(); ++s) {
      const SceneRoots& roots = scene_.scenes[s];
      Json out = Json::object();
      if (!roots.name.empty()) out["name"] = roots.name;
      for (const uint32_t node : roots.nodes) {
        LODBAKE_RETURN_IF_ERROR(
            check_index(node, scene_.nodes.size(), "node", "scene " + std::to_string(s)));
      }
      if (!roots.nodes.empty()) out["nodes"] = roots.nodes;
      put_if_present(&out, "extras", roots.extras);
      put_if_present(&out, "extensions", roots.extensions);
      scenes.push_back(std::move(out));
    }
    if (!scenes.empty()) root_["scenes"] = std::move(scenes);
    if (scene_.default_scene >= 0) {
      LODBAKE_RETURN_IF_ERROR(
          check_index(scene_.default_scene, scene_.scenes.size(), "scene", "the default scene"));
      root_["scene"] = scene_.default_scene;
    }
    return Status::ok();
  }

  Status write_images() {
    Json images = Json::array();
    for (size_t i = 0; i < scene_.images.size(); ++i) {
      const SceneImage& image = scene_.images[i];
      const std::string where = "image " + std::to_string(i);
      Json out = Json::object();
      if (!image.name.empty()) out["name"] = image.name;
      if (!image.mime_type.empty()) out["mimeType"] = image.mime_type;
      if (image.missing) {
        // Nothing to write: the reference stays so that the file can be put
        // back beside the output.
        warn(where + " (" + image.uri + ") was missing from the input: its reference is kept");
        out["uri"] = percent_encode(image.uri);
      } else if (image_uris_ == nullptr) {
        LODBAKE_ASSIGN_OR_RETURN(out["bufferView"], buffer_.add_view(image.bytes, where));
        const std::string mime = image_mime_type(image.mime_type, image.bytes);
        if (mime.empty()) {
          warn(where + " is of an unknown type: written without the mimeType GLB needs");
        } else {
          out["mimeType"] = mime;
        }
      } else {
        out["uri"] = (*image_uris_)[i];
      }
      put_if_present(&out, "extras", image.extras);
      put_if_present(&out, "extensions", image.extensions);
      images.push_back(std::move(out));
    }
    if (!images.empty()) root_["images"] = std::move(images);
    return Status::ok();
  }

  void write_carried() {
    const std::pair<const char*, const Json*> arrays[] = {
        {"materials", &scene_.materials},   {"textures", &scene_.textures},
        {"samplers", &scene_.samplers},     {"skins", &scene_.skins},
        {"animations", &scene_.animations}, {"cameras", &scene_.cameras}};
    for (const auto& [key, value] : arrays) {
      // glTF's top-level arrays hold at least one element when present.
      if (!value->is_null() && !(value->is_array() && value->empty())) root_[key] = *value;
    }
    put_if_present(&root_, "extensions", scene_.extensions);
    put_if_present(&root_, "extras", scene_.extras);
    Json asset = scene_.asset.is_object() ? scene_.asset : Json::object();
    asset["version"] = "2.0";
    asset["generator"] = std::string("lodbake ") + kLodbakeVersion;
    root_["asset"] = std::move(asset);
  }

  // Removes the decoded extensions from every `extensions` object and
  // returns the names of those that stay. Iterative, and never inside
  // `extras`, whose members are the application's and not glTF's.
  std::set<std::string> sweep_extensions(std::set<std::string>* dropped) {
    std::set<std::string> used;
    std::vector<Json*> stack = {&root_};
    while (!stack.empty()) {
      Json* value = stack.back();
      stack.pop_back();
      if (value->is_array()) {
        for (Json& element : *value)
          stack.push_back(&element);
        continue;
      }
      if (!value->is_object()) continue;
      auto ext = value->find("extensions");
      if (ext != value->end() && ext->is_object()) {
        for (const std::string& name : decoded_extensions()) {
          if (ext->erase(name) != 0) dropped->insert(name);
        }
        for (auto it = ext->begin(); it != ext->end(); ++it)
          used.insert(it.key());
        if (ext->empty()) value->erase(ext);
      }
      for (auto it = value->begin(); it != value->end(); ++it)
        if (it.key() != "extras") stack.push_back(&it.value());
    }
    return used;
  }

  void write_extension_lists() {
    std::set<std::string> dropped;
    const std::set<std::string> found = sweep_extensions(&dropped);
    std::vector<std::string> used;
    std::vector<std::string> required;
    auto add = [](std::vector<std::string>* list, const std::string& name) {
      if (std::find(list->begin(), list->end(), name) == list->end()) list->push_back(name);
    };
    for (const std::string& name : scene_.extensions_used) {
      if (decoded_extensions().count(name) != 0) {
        dropped.insert(name);
      } else {
        add(&used, name);
      }
    }
    for (const std::string& name : scene_.extensions_required) {
      if (decoded_extensions().count(name) != 0) {
        dropped.insert(name);
      } else {
        add(&required, name);
      }
    }
    // glTF requires every extension an object uses to be declared, and every
    // required one to be used.
    for (const std::string& name : found)
      add(&used, name);
    for (const std::string& name : required)
      add(&used, name);
    if (quantized_) {
      add(&used, kQuantization);
      add(&required, kQuantization);
    }
    for (const std::string& name : dropped) {
      warn("dropped extension " + name +
           ": lodbake holds its data decoded and writes it without the extension");
    }
    if (!used.empty()) root_["extensionsUsed"] = used;
    if (!required.empty()) root_["extensionsRequired"] = required;
  }

  const Scene& scene_;
  const std::vector<std::string>* image_uris_;
  SceneWriteReport* report_;
  GltfBufferWriter buffer_;
  Json root_ = Json::object();
  bool quantized_ = false;
};

}  // namespace

Result<SceneGltf> build_scene_gltf(const Scene& scene, const std::vector<std::string>* image_uris,
                                   SceneWriteReport* report) {
  return SceneJsonBuilder(scene, image_uris, report).build();
}

}  // namespace dracoio
}  // namespace lodbake
