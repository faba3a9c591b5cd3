// first_scene_difference() (lib/scene/scene_compare.h). It lives in
// lib/dracoio until lib/scene has a library of its own.
#include "lib/scene/scene_compare.h"

#include "formats/scene/accessor_values.h"

#include <cstdio>
#include <cstring>
#include <sstream>

namespace lodbake {
namespace {

using Json = nlohmann::json;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.9g", v);
  return text;
}

const char* component_name(ComponentType t) {
  switch (t) {
    case ComponentType::kByte:
      return "BYTE";
    case ComponentType::kUnsignedByte:
      return "UNSIGNED_BYTE";
    case ComponentType::kShort:
      return "SHORT";
    case ComponentType::kUnsignedShort:
      return "UNSIGNED_SHORT";
    case ComponentType::kUnsignedInt:
      return "UNSIGNED_INT";
    case ComponentType::kFloat:
      return "FLOAT";
  }
  return "?";
}

const char* element_name(ElementType t) {
  static const char* const kNames[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
  return kNames[static_cast<int>(t)];
}

std::string json_text(const Json& j) {
  std::string s = j.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

// The first difference between two JSON values, as "at /path (x vs y)".
std::string json_difference(const Json& a, const Json& b) {
  if (a == b) return "";
  const Json patch = Json::diff(a, b);
  if (patch.empty() || !patch[0].contains("path")) return "differs";
  const std::string path = patch[0]["path"].get<std::string>();
  const Json::json_pointer pointer(path);
  const std::string left = a.contains(pointer) ? json_text(a.at(pointer)) : "absent";
  const std::string right = b.contains(pointer) ? json_text(b.at(pointer)) : "absent";
  return "at " + (path.empty() ? std::string("/") : path) + " (" + left + " vs " + right + ")";
}

template <typename T>
std::string optional_text(const T& value) {
  if (!value) return "absent";
  return json_text(Json(*value));
}

// Keeps the first difference noted; later checks are skipped once one is found.
class Finder {
 public:
  bool found() const { return !line_.empty(); }
  const std::string& line() const { return line_; }
  void note(const std::string& line) {
    if (line_.empty()) line_ = line;
  }

  template <typename T>
  void value(const std::string& what, const T& a, const T& b) {
    if (!found() && !(a == b))
      note(what + " differs (" + json_text(Json(a)) + " vs " + json_text(Json(b)) + ")");
  }
  template <typename T>
  void optional(const std::string& what, const T& a, const T& b) {
    if (!found() && !(a == b))
      note(what + " differs (" + optional_text(a) + " vs " + optional_text(b) + ")");
  }
  void json(const std::string& what, const Json& a, const Json& b) {
    if (!found() && a != b) note(what + " differ " + json_difference(a, b));
  }
  bool count(const std::string& what, size_t a, size_t b) {
    if (!found() && a != b)
      note(what + " count differs (" + std::to_string(a) + " vs " + std::to_string(b) + ")");
    return !found();
  }

  void accessor(const std::string& where, const AccessorData& a, const AccessorData& b) {
    if (found() || a == b) return;
    if (a.component_type != b.component_type) {
      return note(where + ": component type differs (" + component_name(a.component_type) + " vs " +
                  component_name(b.component_type) + ")");
    }
    if (a.type != b.type) {
      return note(where + ": type differs (" + element_name(a.type) + " vs " +
                  element_name(b.type) + ")");
    }
    value(where + ": normalized", a.normalized, b.normalized);
    value(where + ": count", a.count, b.count);
    value(where + ": name", a.name, b.name);
    if (found()) return;
    if (a.bytes.size() != b.bytes.size()) {
      return note(where + ": byte size differs (" + std::to_string(a.bytes.size()) + " vs " +
                  std::to_string(b.bytes.size()) + ")");
    }
    const uint32_t size = component_size(a.component_type);
    for (size_t i = 0; i + size <= a.bytes.size(); i += size) {
      if (std::memcmp(a.bytes.data() + i, b.bytes.data() + i, size) == 0) continue;
      const size_t element = i / size / a.components();
      const uint32_t component = static_cast<uint32_t>(i / size % a.components());
      return note(where + ": element " + std::to_string(element) + " component " +
                  std::to_string(component) + " differs (" +
                  number(stored_value(a, element, component)) + " vs " +
                  number(stored_value(b, element, component)) + ")");
    }
  }

  void streams(const std::string& where, const std::vector<SceneAttribute>& a,
               const std::vector<SceneAttribute>& b) {
    for (size_t i = 0; i < std::min(a.size(), b.size()) && !found(); ++i) {
      if (a[i].semantic != b[i].semantic) {
        return note(where + " attribute " + std::to_string(i) + " differs (" + a[i].semantic +
                    " vs " + b[i].semantic + ")");
      }
      accessor(where + " attribute " + a[i].semantic, a[i].data, b[i].data);
    }
    count(where + " attribute", a.size(), b.size());
  }

  void primitive(const std::string& where, const ScenePrimitive& a, const ScenePrimitive& b) {
    value(where + " mode", static_cast<int>(a.mode), static_cast<int>(b.mode));
    value(where + " material", a.material, b.material);
    if (found()) return;
    if (a.indices.has_value() != b.indices.has_value()) {
      return note(where + " indices differ (" + (a.indices ? "present" : "absent") + " vs " +
                  (b.indices ? "present" : "absent") + ")");
    }
    if (a.indices && *a.indices != *b.indices) {
      const std::vector<uint32_t>& x = *a.indices;
      const std::vector<uint32_t>& y = *b.indices;
      for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
        if (x[i] != y[i]) {
          return note(where + " index " + std::to_string(i) + " differs (" + std::to_string(x[i]) +
                      " vs " + std::to_string(y[i]) + ")");
        }
      }
      count(where + " index", x.size(), y.size());
      return;
    }
    streams(where, a.attributes, b.attributes);
    for (size_t t = 0; t < std::min(a.targets.size(), b.targets.size()); ++t)
      streams(where + " target " + std::to_string(t), a.targets[t], b.targets[t]);
    count(where + " target", a.targets.size(), b.targets.size());
    json(where + " extras", a.extras, b.extras);
    json(where + " extensions", a.extensions, b.extensions);
  }

  void node(const std::string& where, const SceneNode& a, const SceneNode& b) {
    value(where + " name", a.name, b.name);
    value(where + " mesh", a.mesh, b.mesh);
    value(where + " skin", a.skin, b.skin);
    value(where + " camera", a.camera, b.camera);
    value(where + " children", a.children, b.children);
    optional(where + " matrix", a.matrix, b.matrix);
    optional(where + " translation", a.translation, b.translation);
    optional(where + " rotation", a.rotation, b.rotation);
    optional(where + " scale", a.scale, b.scale);
    value(where + " weights", a.weights, b.weights);
    json(where + " extras", a.extras, b.extras);
    json(where + " extensions", a.extensions, b.extensions);
  }

  void image(const std::string& where, const SceneImage& a, const SceneImage& b,
             const SceneCompareOptions& options) {
    value(where + " name", a.name, b.name);
    if (options.image_storage) {
      value(where + " mime type", a.mime_type, b.mime_type);
      value(where + " uri", a.uri, b.uri);
    }
    value(where + " missing", a.missing, b.missing);
    if (!found() && a.bytes != b.bytes) {
      size_t i = 0;
      while (i < a.bytes.size() && i < b.bytes.size() && a.bytes[i] == b.bytes[i])
        ++i;
      note(where + " bytes differ from byte " + std::to_string(i) + " (" +
           std::to_string(a.bytes.size()) + " vs " + std::to_string(b.bytes.size()) + " bytes)");
    }
    json(where + " extras", a.extras, b.extras);
    json(where + " extensions", a.extensions, b.extensions);
  }

 private:
  std::string line_;
};

}  // namespace

std::string first_scene_difference(const Scene& a, const Scene& b,
                                   const SceneCompareOptions& options) {
  Finder f;
  f.json("asset", a.asset, b.asset);
  if (f.count("scene", a.scenes.size(), b.scenes.size())) {
    for (size_t i = 0; i < a.scenes.size(); ++i) {
      const std::string where = "scene " + std::to_string(i);
      f.value(where + " name", a.scenes[i].name, b.scenes[i].name);
      f.value(where + " nodes", a.scenes[i].nodes, b.scenes[i].nodes);
      f.json(where + " extras", a.scenes[i].extras, b.scenes[i].extras);
      f.json(where + " extensions", a.scenes[i].extensions, b.scenes[i].extensions);
    }
  }
  f.value("default scene", a.default_scene, b.default_scene);
  if (f.count("node", a.nodes.size(), b.nodes.size())) {
    for (size_t i = 0; i < a.nodes.size(); ++i)
      f.node("node " + std::to_string(i), a.nodes[i], b.nodes[i]);
  }
  if (f.count("mesh", a.meshes.size(), b.meshes.size())) {
    for (size_t m = 0; m < a.meshes.size(); ++m) {
      const SceneMesh& x = a.meshes[m];
      const SceneMesh& y = b.meshes[m];
      const std::string where = "mesh " + std::to_string(m);
      f.value(where + " name", x.name, y.name);
      if (f.count(where + " primitive", x.primitives.size(), y.primitives.size())) {
        for (size_t p = 0; p < x.primitives.size(); ++p)
          f.primitive(where + " primitive " + std::to_string(p), x.primitives[p], y.primitives[p]);
      }
      f.value(where + " weights", x.weights, y.weights);
      f.json(where + " extras", x.extras, y.extras);
      f.json(where + " extensions", x.extensions, y.extensions);
    }
  }
  if (f.count("image", a.images.size(), b.images.size())) {
    for (size_t i = 0; i < a.images.size(); ++i)
      f.image("image " + std::to_string(i), a.images[i], b.images[i], options);
  }
  if (f.count("accessor", a.accessors.size(), b.accessors.size())) {
    for (size_t i = 0; i < a.accessors.size(); ++i)
      f.accessor("accessor " + std::to_string(i), a.accessors[i], b.accessors[i]);
  }
  f.json("materials", a.materials, b.materials);
  f.json("textures", a.textures, b.textures);
  f.json("samplers", a.samplers, b.samplers);
  f.json("skins", a.skins, b.skins);
  f.json("animations", a.animations, b.animations);
  f.json("cameras", a.cameras, b.cameras);
  f.value("extensionsUsed", a.extensions_used, b.extensions_used);
  f.value("extensionsRequired", a.extensions_required, b.extensions_required);
  f.json("extensions", a.extensions, b.extensions);
  f.json("extras", a.extras, b.extras);
  if (!f.found() && options.image_storage && !(a == b)) return "scenes differ";
  return f.line();
}

}  // namespace lodbake
