// read_gltf_scene(): a glTF 2.0 asset into the scene model, as the file has
// it (Khronos glTF 2.0 specification; the extensions named below).
//
// Choices where the specification is loose or a policy is needed:
// - Nothing is welded, split, merged or reordered: every mesh, primitive
//   (any mode, indices optional) and stream stays as stored, decoded into
//   dense AccessorData with its component type (KHR_mesh_quantization types
//   stay integers). Attributes and morph-target streams are sorted by
//   semantic, the order glTF's JSON object gives no meaning to.
// - KHR_draco_mesh_compression and EXT_meshopt_compression are decoded and
//   removed from the primitive, extensionsUsed and extensionsRequired;
//   sparse accessors are made dense. A required extension outside
//   scene_required_ok() fails with kUnsupported naming it.
// - Node transforms are read at float32 precision, the precision glTF
//   viewers and writers use: a .gltf and a .glb of the same asset differ
//   only in how many digits they print (Duck: -0.4252049028873444 against
//   -0.42520490288734436), and should read as the same scene.
// - Images: a missing external image is a warning (the geometry is still
//   useful; Lantern ships without its base colour), a missing buffer an
//   error. mimeType is kept as given or, when absent, taken from the bytes'
//   signature (PNG, JPEG, KTX2, WebP), which a GLB writer needs.
// - Carried JSON keeps its references, except accessor references, which
//   become indices into Scene::accessors, numbered in first-reference order:
//   EXT_mesh_gpu_instancing attributes by node, then skins'
//   inverseBindMatrices, then animation samplers' input and output.
//   An extension elsewhere that refers to buffer data (EXT_structural_metadata,
//   CESIUM_primitive_outline, or an unknown one with a bufferView, accessor
//   or buffer member) is dropped with one warning naming it.
// - Bounds: decoded bytes are capped by the document's budget
//   (gltf_document.h), and the node hierarchy is checked to be a forest
//   (gltf_nodes.cpp) before it is kept.
#include <algorithm>
#include <cstring>
#include <map>
#include <new>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "lib/dracoio/gltf_accessor_data.h"
#include "lib/dracoio/gltf_accessors.h"
#include "lib/dracoio/gltf_document.h"
#include "lib/dracoio/gltf_nodes.h"
#include "lib/dracoio/gltf_scene_draco.h"
#include "lib/dracoio/gltf_uri.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_points.h"

namespace lodbake {
namespace {

using dracoio::GltfDocument;
using dracoio::Json;

constexpr const char* kDraco = "KHR_draco_mesh_compression";
constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";

std::string str(uint64_t v) {
  return std::to_string(v);
}

// Required extensions the scene reader decodes or carries, and those that
// do not change geometry (flatten_scene() accepts the same list but
// instancing, which it does not apply).
bool scene_required_ok(const std::string& name) {
  return name == kDraco || name == kMeshopt || name == kInstancing ||
         name == "KHR_mesh_quantization" || name == "KHR_texture_transform" ||
         name == "KHR_texture_basisu" || name == "EXT_texture_webp" ||
         name == "KHR_lights_punctual" || name.compare(0, 14, "KHR_materials_") == 0;
}

// Extensions known to hold only JSON (and texture or image indices, which
// the scene keeps unchanged): carried without a look inside.
bool carried_as_is(const std::string& name) {
  return name == "KHR_mesh_quantization" || name == "KHR_texture_transform" ||
         name == "KHR_texture_basisu" || name == "EXT_texture_webp" || name == "EXT_texture_avif" ||
         name == "KHR_lights_punctual" || name == "EXT_mesh_features" ||
         name == "KHR_xmp_json_ld" || name == "MSFT_texture_dds" ||
         name.compare(0, 14, "KHR_materials_") == 0;
}

// Extensions known to refer to bufferViews or accessors in their own way.
bool refers_to_buffers(const std::string& name) {
  return name == "EXT_structural_metadata" || name == "CESIUM_primitive_outline" ||
         name == kInstancing || name == kDraco || name == kMeshopt;
}

// True when `value` has, at any depth, a member naming buffer data. Depth is
// bounded by the document's JSON depth check; the walk is iterative anyway.
bool mentions_buffer_data(const Json& value) {
  std::vector<const Json*> stack{&value};
  while (!stack.empty()) {
    const Json* v = stack.back();
    stack.pop_back();
    if (v->is_object()) {
      for (auto it = v->begin(); it != v->end(); ++it) {
        const std::string& k = it.key();
        if (k == "bufferView" || k == "bufferViews" || k == "accessor" || k == "accessors" ||
            k == "buffer" || k == "buffers") {
          return true;
        }
        stack.push_back(&it.value());
      }
    } else if (v->is_array()) {
      for (const Json& e : *v)
        stack.push_back(&e);
    }
  }
  return false;
}

const char* sniff_mime(const std::vector<uint8_t>& b) {
  auto starts = [&b](const char* magic, size_t n, size_t at = 0) {
    return b.size() >= at + n && std::memcmp(b.data() + at, magic, n) == 0;
  };
  if (starts("\x89PNG\r\n\x1a\n", 8)) return "image/png";
  if (starts("\xFF\xD8\xFF", 3)) return "image/jpeg";
  if (starts("\xABKTX 20\xBB", 8)) return "image/ktx2";
  if (starts("RIFF", 4) && starts("WEBP", 4, 8)) return "image/webp";
  return "";
}

class SceneReader {
 public:
  SceneReader(GltfDocument* doc, const SceneResources& resources, ImportReport* report)
      : doc_(*doc), resources_(resources), report_(report) {}

  Result<Scene> run();

 private:
  Status read_extension_lists();
  Status read_meshes();
  Status read_primitive(const Json& prim, const std::string& where, ScenePrimitive* out);
  Status read_streams(const Json& attributes, const dracoio::DracoStreams* draco,
                      const std::string& where, std::vector<SceneAttribute>* out);
  Status read_nodes();
  Status read_scenes();
  Status read_images();
  Status read_carried();
  Result<uint32_t> scene_accessor(const Json& value, const std::string& where);
  Status rewrite_accessor(Json* object, const char* key, const std::string& where);
  // A copy of `value` with every extension that refers to buffer data the
  // scene cannot carry removed (with a warning); `kept` names one that the
  // caller has already rewritten at the top level.
  Json carry(const Json& value, const std::string& where, const char* kept = nullptr);
  // An "extensions" object itself (its members are extension names).
  Json carry_extensions(const Json& extensions, const std::string& where,
                        const char* kept = nullptr) {
    Json wrapped = Json::object();
    wrapped["extensions"] = extensions;
    Json out = carry(wrapped, where, kept)["extensions"];
    return out.is_object() && out.empty() ? Json() : out;
  }
  Json member_or_null(const Json& object, const char* key, const std::string& where) {
    const auto it = object.find(key);
    if (it == object.end()) return Json();
    return std::strcmp(key, "extensions") == 0 ? carry_extensions(*it, where) : carry(*it, where);
  }
  void warn(const std::string& text) {
    if (report_ != nullptr) report_->warnings.push_back(text);
  }

  GltfDocument& doc_;
  const SceneResources& resources_;
  ImportReport* report_;
  Scene scene_;
  std::map<int64_t, uint32_t> accessor_index_;  // file accessor -> Scene::accessors
  std::set<std::string> dropped_;
  dracoio::DracoPrimitiveDecoder draco_;
};

Json SceneReader::carry(const Json& value, const std::string& where, const char* kept) {
  Json copy = value;
  std::vector<Json*> stack{&copy};
  bool top = true;
  while (!stack.empty()) {
    Json* v = stack.back();
    stack.pop_back();
    if (v->is_object()) {
      const auto ext = v->find("extensions");
      if (ext != v->end() && ext->is_object()) {
        for (auto it = ext->begin(); it != ext->end();) {
          const std::string& name = it.key();
          const bool keep = (top && kept != nullptr && name == kept) || carried_as_is(name) ||
                            (!refers_to_buffers(name) && !mentions_buffer_data(it.value()));
          if (keep) {
            ++it;
            continue;
          }
          if (dropped_.insert(name).second) {
            warn("dropped glTF extension '" + name.substr(0, 100) + "' (first in " + where +
                 "): it refers to buffer data lodbake does not carry");
          }
          it = ext->erase(it);
        }
      }
      for (auto& member : v->items())
        stack.push_back(&member.value());
    } else if (v->is_array()) {
      for (Json& e : *v)
        stack.push_back(&e);
    }
    top = false;
  }
  return copy;
}

Status SceneReader::read_extension_lists() {
  for (const char* key : {"extensionsRequired", "extensionsUsed"}) {
    LODBAKE_ASSIGN_OR_RETURN(const Json* list, dracoio::member_array(doc_.root, key, "glTF"));
    if (list == nullptr) continue;
    const bool required = std::strcmp(key, "extensionsRequired") == 0;
    for (const Json& e : *list) {
      if (!e.is_string())
        return invalid_input(std::string("glTF: '") + key + "' holds a non-string");
      const std::string& name = e.get_ref<const std::string&>();
      if (required && !scene_required_ok(name)) {
        return unsupported("required glTF extension '" + name.substr(0, 100) +
                           "' is not supported");
      }
      if (name == kDraco || name == kMeshopt) continue;  // decoded
      (required ? scene_.extensions_required : scene_.extensions_used).push_back(name);
    }
  }
  return Status::ok();
}

Result<uint32_t> SceneReader::scene_accessor(const Json& value, const std::string& where) {
  LODBAKE_ASSIGN_OR_RETURN(
      const int64_t index,
      dracoio::as_index(value, dracoio::top_level_count(doc_.root, "accessors"), "accessor",
                        where));
  const auto found = accessor_index_.find(index);
  if (found != accessor_index_.end()) return found->second;
  LODBAKE_ASSIGN_OR_RETURN(AccessorData data, dracoio::read_accessor_data(&doc_, index));
  const uint32_t mine = static_cast<uint32_t>(scene_.accessors.size());
  scene_.accessors.push_back(std::move(data));
  accessor_index_.emplace(index, mine);
  return mine;
}

Status SceneReader::rewrite_accessor(Json* object, const char* key, const std::string& where) {
  if (!object->is_object()) return invalid_input(where + " is not a JSON object");
  const auto it = object->find(key);
  if (it == object->end()) return Status::ok();
  LODBAKE_ASSIGN_OR_RETURN(const uint32_t index, scene_accessor(*it, where + " " + key));
  *it = index;
  return Status::ok();
}

Status SceneReader::read_streams(const Json& attributes, const dracoio::DracoStreams* draco,
                                 const std::string& where, std::vector<SceneAttribute>* out) {
  if (!attributes.is_object()) return invalid_input(where + " is not a JSON object");
  const size_t accessor_count = dracoio::top_level_count(doc_.root, "accessors");
  for (auto it = attributes.begin(); it != attributes.end(); ++it) {
    SceneAttribute a;
    a.semantic = it.key();
    const auto decoded = draco != nullptr ? draco->attributes.find(a.semantic)
                                          : std::map<std::string, AccessorData>::const_iterator();
    if (draco != nullptr && decoded != draco->attributes.end()) {
      a.data = decoded->second;
    } else {
      LODBAKE_ASSIGN_OR_RETURN(
          const int64_t index,
          dracoio::as_index(it.value(), accessor_count, "accessor", where + " " + a.semantic));
      LODBAKE_ASSIGN_OR_RETURN(a.data, dracoio::read_accessor_data(&doc_, index));
    }
    out->push_back(std::move(a));
  }
  // nlohmann's object iterates its keys sorted; sort anyway, the model
  // promises it whatever the JSON library does.
  std::sort(out->begin(), out->end(), [](const SceneAttribute& x, const SceneAttribute& y) {
    return x.semantic < y.semantic;
  });
  return Status::ok();
}

Status SceneReader::read_primitive(const Json& prim, const std::string& where,
                                   ScenePrimitive* out) {
  if (!prim.is_object()) return invalid_input(where + " is not a JSON object");
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t mode, dracoio::member_uint(prim, "mode", 4, 6, where));
  out->mode = static_cast<PrimitiveMode>(mode);
  LODBAKE_ASSIGN_OR_RETURN(
      const int64_t material,
      dracoio::member_index(prim, "material", dracoio::top_level_count(doc_.root, "materials"),
                            "material", where));
  out->material = static_cast<int32_t>(material);
  LODBAKE_ASSIGN_OR_RETURN(const Json* attributes,
                           dracoio::member_object(prim, "attributes", where));
  if (attributes == nullptr || attributes->empty()) {
    return invalid_input(where + " has no attributes");
  }
  LODBAKE_ASSIGN_OR_RETURN(const Json* extensions,
                           dracoio::member_object(prim, "extensions", where));
  const Json* draco_ext = nullptr;
  if (extensions != nullptr) {
    const auto it = extensions->find(kDraco);
    if (it != extensions->end()) draco_ext = &*it;
  }
  dracoio::DracoStreams draco;
  if (draco_ext != nullptr) {
    LODBAKE_ASSIGN_OR_RETURN(draco, draco_.decode(&doc_, *draco_ext, *attributes, where));
  }
  LODBAKE_RETURN_IF_ERROR(read_streams(*attributes, draco_ext != nullptr ? &draco : nullptr,
                                       where + " attributes", &out->attributes));
  const uint32_t vertices = out->attributes.front().data.count;
  for (const SceneAttribute& a : out->attributes) {
    if (a.data.count != vertices) {
      return invalid_input(where + ": attribute " + a.semantic.substr(0, 100) + " has " +
                           str(a.data.count) + " elements, " + out->attributes.front().semantic +
                           " " + str(vertices));
    }
  }
  if (draco_ext != nullptr) {
    out->indices = std::move(draco.indices);
  } else {
    LODBAKE_ASSIGN_OR_RETURN(
        const int64_t indices,
        dracoio::member_index(prim, "indices", dracoio::top_level_count(doc_.root, "accessors"),
                              "accessor", where + " indices"));
    if (indices >= 0) {
      LODBAKE_ASSIGN_OR_RETURN(const AccessorData data,
                               dracoio::read_accessor_data(&doc_, indices));
      if (data.type != ElementType::kScalar ||
          (data.component_type != ComponentType::kUnsignedByte &&
           data.component_type != ComponentType::kUnsignedShort &&
           data.component_type != ComponentType::kUnsignedInt)) {
        return invalid_input(where + ": indices accessor " + str(static_cast<uint64_t>(indices)) +
                             " is not SCALAR unsigned byte, short or int");
      }
      LODBAKE_RETURN_IF_ERROR(doc_.budget.charge(uint64_t{data.count} * 4, where + " indices"));
      std::vector<uint32_t> values(data.count);
      const uint32_t size = data.element_size();
      for (uint32_t i = 0; i < data.count; ++i) {
        uint32_t v = 0;
        std::memcpy(&v, data.bytes.data() + size_t{i} * size, size);  // little-endian host
        values[i] = v;
      }
      out->indices = std::move(values);
    }
  }
  if (out->indices) {
    for (size_t i = 0; i < out->indices->size(); ++i) {
      if ((*out->indices)[i] >= vertices) {
        return invalid_input(where + ": index " + str((*out->indices)[i]) + " at position " +
                             str(i) + " out of range (" + str(vertices) + " vertices)");
      }
    }
  }
  LODBAKE_ASSIGN_OR_RETURN(const Json* targets, dracoio::member_array(prim, "targets", where));
  if (targets != nullptr) {
    for (size_t t = 0; t < targets->size(); ++t) {
      const std::string tw = where + " target " + str(t);
      std::vector<SceneAttribute> streams;
      LODBAKE_RETURN_IF_ERROR(read_streams((*targets)[t], nullptr, tw, &streams));
      for (const SceneAttribute& a : streams) {
        if (a.data.count != vertices) {
          return invalid_input(tw + ": " + a.semantic.substr(0, 100) + " has " + str(a.data.count) +
                               " elements, the primitive " + str(vertices));
        }
      }
      out->targets.push_back(std::move(streams));
    }
  }
  out->extras = member_or_null(prim, "extras", where);
  if (extensions != nullptr) {
    Json kept = *extensions;
    kept.erase(kDraco);
    out->extensions = carry_extensions(kept, where);
  }
  return Status::ok();
}

Result<std::vector<float>> read_floats(const Json& object, const char* key,
                                       const std::string& where) {
  std::vector<float> out;
  LODBAKE_ASSIGN_OR_RETURN(const Json* values, dracoio::member_array(object, key, where));
  if (values == nullptr) return out;
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<double> numbers,
                           dracoio::member_numbers(object, key, values->size(), where));
  out.assign(numbers.begin(), numbers.end());
  return out;
}

std::string name_of(const Json& object) {
  const auto it = object.find("name");
  return it != object.end() && it->is_string() ? it->get<std::string>() : std::string();
}

Status SceneReader::read_meshes() {
  LODBAKE_ASSIGN_OR_RETURN(const Json* meshes, dracoio::member_array(doc_.root, "meshes", "glTF"));
  if (meshes == nullptr) return Status::ok();
  scene_.meshes.resize(meshes->size());
  for (size_t m = 0; m < meshes->size(); ++m) {
    const std::string where = "mesh " + str(m);
    const Json& mesh = (*meshes)[m];
    if (!mesh.is_object()) return invalid_input(where + " is not a JSON object");
    SceneMesh& out = scene_.meshes[m];
    out.name = name_of(mesh);
    LODBAKE_ASSIGN_OR_RETURN(const Json* prims, dracoio::member_array(mesh, "primitives", where));
    if (prims == nullptr || prims->empty()) return invalid_input(where + " has no primitives");
    out.primitives.resize(prims->size());
    for (size_t p = 0; p < prims->size(); ++p) {
      LODBAKE_RETURN_IF_ERROR(
          read_primitive((*prims)[p], where + " primitive " + str(p), &out.primitives[p]));
    }
    LODBAKE_ASSIGN_OR_RETURN(out.weights, read_floats(mesh, "weights", where));
    out.extras = member_or_null(mesh, "extras", where);
    out.extensions = member_or_null(mesh, "extensions", where);
    weld_mesh_points(&out);
  }
  return Status::ok();
}

// `v` rounded to float32. Through a volatile: GCC 12 at -O3 vectorizes the
// plain double -> float -> double round trip of read_vector's loop into a
// copy that skips the rounding (seen on this toolchain: Spheres' 0.1 scale
// came back unrounded).
double float_precision(double v) {
  volatile float f = static_cast<float>(v);
  return f;
}

template <size_t N>
Result<std::optional<std::array<double, N>>> read_vector(const Json& node, const char* key,
                                                         const std::string& where) {
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<double> values,
                           dracoio::member_numbers(node, key, N, where));
  std::optional<std::array<double, N>> out;
  if (values.empty()) return out;
  out.emplace();
  for (size_t i = 0; i < N; ++i)
    (*out)[i] = float_precision(values[i]);
  return out;
}

Status SceneReader::read_nodes() {
  LODBAKE_ASSIGN_OR_RETURN(const dracoio::NodeForest forest,
                           dracoio::load_nodes(doc_.root, scene_.meshes.size()));
  LODBAKE_ASSIGN_OR_RETURN(const Json* nodes, dracoio::member_array(doc_.root, "nodes", "glTF"));
  if (nodes == nullptr) return Status::ok();
  scene_.nodes.resize(nodes->size());
  const size_t skins = dracoio::top_level_count(doc_.root, "skins");
  const size_t cameras = dracoio::top_level_count(doc_.root, "cameras");
  for (size_t i = 0; i < nodes->size(); ++i) {
    const std::string where = "node " + str(i);
    const Json& node = (*nodes)[i];
    SceneNode& out = scene_.nodes[i];
    out.name = name_of(node);
    out.mesh = static_cast<int32_t>(forest.mesh[i]);
    LODBAKE_ASSIGN_OR_RETURN(const int64_t skin,
                             dracoio::member_index(node, "skin", skins, "skin", where));
    LODBAKE_ASSIGN_OR_RETURN(const int64_t camera,
                             dracoio::member_index(node, "camera", cameras, "camera", where));
    out.skin = static_cast<int32_t>(skin);
    out.camera = static_cast<int32_t>(camera);
    out.children = forest.children[i];
    LODBAKE_ASSIGN_OR_RETURN(out.matrix, read_vector<16>(node, "matrix", where));
    LODBAKE_ASSIGN_OR_RETURN(out.translation, read_vector<3>(node, "translation", where));
    LODBAKE_ASSIGN_OR_RETURN(out.rotation, read_vector<4>(node, "rotation", where));
    LODBAKE_ASSIGN_OR_RETURN(out.scale, read_vector<3>(node, "scale", where));
    LODBAKE_ASSIGN_OR_RETURN(out.weights, read_floats(node, "weights", where));
    out.extras = member_or_null(node, "extras", where);
    const auto ext = node.find("extensions");
    if (ext == node.end()) continue;
    if (!ext->is_object()) return invalid_input(where + ": 'extensions' is not an object");
    Json extensions = *ext;
    const auto instancing = extensions.find(kInstancing);
    if (instancing != extensions.end()) {
      const std::string iw = where + " " + kInstancing;
      LODBAKE_ASSIGN_OR_RETURN(const Json* attributes,
                               dracoio::member_object(*instancing, "attributes", iw));
      if (attributes == nullptr) return invalid_input(iw + " has no attributes");
      Json rewritten = Json::object();
      for (auto it = attributes->begin(); it != attributes->end(); ++it) {
        LODBAKE_ASSIGN_OR_RETURN(const uint32_t index,
                                 scene_accessor(it.value(), iw + " " + it.key()));
        rewritten[it.key()] = index;
      }
      (*instancing)["attributes"] = std::move(rewritten);
    }
    out.extensions = carry_extensions(extensions, where, kInstancing);
  }
  return Status::ok();
}

Status SceneReader::read_scenes() {
  LODBAKE_ASSIGN_OR_RETURN(const Json* scenes, dracoio::member_array(doc_.root, "scenes", "glTF"));
  const size_t count = scenes == nullptr ? 0 : scenes->size();
  LODBAKE_ASSIGN_OR_RETURN(const int64_t chosen,
                           dracoio::member_index(doc_.root, "scene", count, "scene", "glTF"));
  scene_.default_scene = static_cast<int32_t>(chosen);
  std::vector<int64_t> parent(scene_.nodes.size(), -1);
  for (size_t p = 0; p < scene_.nodes.size(); ++p) {
    for (uint32_t c : scene_.nodes[p].children)
      parent[c] = static_cast<int64_t>(p);
  }
  for (size_t s = 0; s < count; ++s) {
    const std::string where = "scene " + str(s);
    const Json& scene = (*scenes)[s];
    if (!scene.is_object()) return invalid_input(where + " is not a JSON object");
    SceneRoots out;
    out.name = name_of(scene);
    LODBAKE_ASSIGN_OR_RETURN(const Json* nodes, dracoio::member_array(scene, "nodes", where));
    std::set<uint32_t> listed;
    if (nodes != nullptr) {
      for (const Json& value : *nodes) {
        LODBAKE_ASSIGN_OR_RETURN(const int64_t node,
                                 dracoio::as_index(value, scene_.nodes.size(), "node", where));
        const uint32_t n = static_cast<uint32_t>(node);
        if (parent[n] >= 0) {
          return invalid_input(where + " lists node " + str(n) + ", which is a child of node " +
                               str(static_cast<uint64_t>(parent[n])));
        }
        if (!listed.insert(n).second) {
          return invalid_input(where + " lists node " + str(n) + " twice");
        }
        out.nodes.push_back(n);
      }
    }
    out.extras = member_or_null(scene, "extras", where);
    out.extensions = member_or_null(scene, "extensions", where);
    scene_.scenes.push_back(std::move(out));
  }
  return Status::ok();
}

Status SceneReader::read_images() {
  LODBAKE_ASSIGN_OR_RETURN(const Json* images, dracoio::member_array(doc_.root, "images", "glTF"));
  if (images == nullptr) return Status::ok();
  const size_t views = dracoio::top_level_count(doc_.root, "bufferViews");
  for (size_t i = 0; i < images->size(); ++i) {
    const std::string where = "image " + str(i);
    const Json& image = (*images)[i];
    if (!image.is_object()) return invalid_input(where + " is not a JSON object");
    SceneImage out;
    out.name = name_of(image);
    const auto mime = image.find("mimeType");
    if (mime != image.end() && mime->is_string()) out.mime_type = mime->get<std::string>();
    LODBAKE_ASSIGN_OR_RETURN(
        const int64_t view, dracoio::member_index(image, "bufferView", views, "bufferView", where));
    const auto uri = image.find("uri");
    if (view >= 0) {
      LODBAKE_ASSIGN_OR_RETURN(const dracoio::ByteSpan bytes,
                               dracoio::buffer_view_bytes(doc_, view, where));
      out.bytes.assign(bytes.data, bytes.data + bytes.size);
    } else if (uri != image.end()) {
      if (!uri->is_string()) return invalid_input(where + ": 'uri' is not a string");
      const std::string& text = uri->get_ref<const std::string&>();
      if (text.compare(0, 5, "data:") == 0) {
        LODBAKE_ASSIGN_OR_RETURN(out.bytes, dracoio::decode_data_uri(text, where));
      } else {
        LODBAKE_ASSIGN_OR_RETURN(out.uri, dracoio::percent_decode(text));
        auto bytes = read_resource(resources_, text);
        if (bytes.is_ok()) {
          out.bytes = std::move(bytes).value();
        } else if (bytes.status().kind() == ErrorKind::kIo || resources_.folder.empty()) {
          // Read from memory (a container's SCNE keeps an image the input
          // lacked as a reference), an image by URI is missing, not fatal.
          out.missing = true;
          warn(where + " '" + out.uri.substr(0, 200) + "' is missing");
        } else {
          return Status(bytes.status().kind(), where + ": " + bytes.status().message());
        }
      }
    } else {
      return invalid_input(where + " has neither a uri nor a bufferView");
    }
    if (out.mime_type.empty()) out.mime_type = sniff_mime(out.bytes);
    out.extras = member_or_null(image, "extras", where);
    out.extensions = member_or_null(image, "extensions", where);
    scene_.images.push_back(std::move(out));
  }
  return Status::ok();
}

Status SceneReader::read_carried() {
  LODBAKE_ASSIGN_OR_RETURN(const Json* skins, dracoio::member_array(doc_.root, "skins", "glTF"));
  if (skins != nullptr) {
    Json rewritten = *skins;
    for (size_t i = 0; i < rewritten.size(); ++i) {
      LODBAKE_RETURN_IF_ERROR(
          rewrite_accessor(&rewritten[i], "inverseBindMatrices", "skin " + str(i)));
    }
    scene_.skins = carry(rewritten, "skins");
  }
  LODBAKE_ASSIGN_OR_RETURN(const Json* animations,
                           dracoio::member_array(doc_.root, "animations", "glTF"));
  if (animations != nullptr) {
    Json rewritten = *animations;
    for (size_t a = 0; a < rewritten.size(); ++a) {
      const std::string where = "animation " + str(a);
      if (!rewritten[a].is_object()) return invalid_input(where + " is not a JSON object");
      const auto samplers = rewritten[a].find("samplers");
      if (samplers == rewritten[a].end()) continue;
      if (!samplers->is_array()) return invalid_input(where + ": 'samplers' is not an array");
      for (size_t s = 0; s < samplers->size(); ++s) {
        const std::string sw = where + " sampler " + str(s);
        LODBAKE_RETURN_IF_ERROR(rewrite_accessor(&(*samplers)[s], "input", sw));
        LODBAKE_RETURN_IF_ERROR(rewrite_accessor(&(*samplers)[s], "output", sw));
      }
    }
    scene_.animations = carry(rewritten, "animations");
  }
  const std::pair<const char*, SceneJson*> arrays[] = {{"materials", &scene_.materials},
                                                       {"textures", &scene_.textures},
                                                       {"samplers", &scene_.samplers},
                                                       {"cameras", &scene_.cameras}};
  for (const auto& a : arrays) {
    LODBAKE_ASSIGN_OR_RETURN(const Json* value, dracoio::member_array(doc_.root, a.first, "glTF"));
    if (value != nullptr) *a.second = carry(*value, a.first);
  }
  scene_.extensions = member_or_null(doc_.root, "extensions", "the top-level extensions");
  scene_.extras = member_or_null(doc_.root, "extras", "the top-level extras");
  const Json& asset = doc_.root.at("asset");
  const auto generator = asset.find("generator");
  if (generator != asset.end() && generator->is_string()) {
    scene_.generator = generator->get<std::string>();
  }
  Json kept = carry(asset, "asset");
  kept.erase("version");
  kept.erase("generator");
  if (!kept.empty()) scene_.asset = std::move(kept);
  return Status::ok();
}

Result<Scene> SceneReader::run() {
  LODBAKE_RETURN_IF_ERROR(read_extension_lists());
  LODBAKE_RETURN_IF_ERROR(read_meshes());
  LODBAKE_RETURN_IF_ERROR(read_nodes());
  LODBAKE_RETURN_IF_ERROR(read_scenes());
  LODBAKE_RETURN_IF_ERROR(read_images());
  LODBAKE_RETURN_IF_ERROR(read_carried());
  // An extension dropped everywhere it appeared is no longer used.
  for (const std::string& name : dropped_) {
    for (auto* list : {&scene_.extensions_used, &scene_.extensions_required}) {
      list->erase(std::remove(list->begin(), list->end(), name), list->end());
    }
  }
  if (report_ != nullptr) {
    report_->format = doc_.binary ? "glb" : "gltf";
    uint64_t triangles = 0;
    for (const SceneMesh& m : scene_.meshes) {
      for (const ScenePrimitive& p : m.primitives) {
        if (p.mode == PrimitiveMode::kTriangles) {
          triangles += p.indices ? p.indices->size() / 3 : p.vertex_count() / 3;
        }
      }
    }
    report_->file_faces = triangles;
  }
  return std::move(scene_);
}

Result<Scene> read_unchecked(const uint8_t* data, size_t size, const SceneResources& resources,
                             ImportReport* report) {
  LODBAKE_ASSIGN_OR_RETURN(GltfDocument doc, dracoio::load_gltf_document(data, size, resources));
  SceneReader reader(&doc, resources, report);
  return reader.run();
}

}  // namespace

Result<Scene> read_gltf_scene(const uint8_t* data, size_t size, const SceneResources& resources,
                              ImportReport* report) {
  return dracoio::guard_exceptions<Scene>(
      [&] { return read_unchecked(data, size, resources, report); });
}

}  // namespace lodbake
