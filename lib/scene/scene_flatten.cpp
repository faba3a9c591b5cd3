// flatten_scene(): the default scene's triangle primitives as one welded
// mesh (scene_flatten.h says what is kept). Every primitive is prepared at
// most once, on its first use, so that a mesh used by many nodes is
// converted once and instanced, and notes come in traversal order.
#include "lib/scene/scene_flatten.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "formats/scene/accessor_values.h"
#include "formats/scene/node_matrix.h"
#include "lib/scene/mesh_weld.h"

namespace lodbake {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

const char* mode_name(PrimitiveMode mode) {
  static constexpr const char* kNames[] = {
      "POINTS", "LINES", "LINE_LOOP", "LINE_STRIP", "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return kNames[static_cast<int>(mode)];
}

// Required extensions that do not change the merged geometry, or that the
// scene reader has already decoded.
bool required_extension_ok(const std::string& name) {
  return name == "KHR_draco_mesh_compression" || name == "EXT_meshopt_compression" ||
         name == "KHR_mesh_quantization" || name == "KHR_texture_transform" ||
         name == "KHR_texture_basisu" || name == "EXT_texture_webp" ||
         name == "KHR_lights_punctual" || name.compare(0, 14, "KHR_materials_") == 0;
}

WeldMode weld_mode(const Scene& scene) {
  if (!scene.asset.is_object()) return WeldMode::kExactPositions;
  const auto extras = scene.asset.find("extras");
  if (extras == scene.asset.end() || !extras->is_object()) return WeldMode::kExactPositions;
  const auto weld = extras->find("lodbake_weld");
  if (weld == extras->end() || !weld->is_string()) return WeldMode::kExactPositions;
  if (*weld == "none") return WeldMode::kNone;
  if (*weld == "manifold_edges") return WeldMode::kManifoldEdges;
  return WeldMode::kExactPositions;
}

struct Prepared {
  bool done = false;
  bool usable = false;
  RawMesh mesh;
};

class Flattener {
 public:
  Flattener(const Scene& scene, uint64_t budget) : scene_(scene), budget_(budget) {}

  Result<TriangleMesh> run(ImportReport* report);

 private:
  Status check_extensions();
  Result<std::vector<uint32_t>> roots();
  void note_ignored_top_level();
  Result<const Prepared*> primitive(size_t mesh, size_t index);
  Status prepare(const ScenePrimitive& prim, const std::string& where, Prepared* out);
  Status charge(uint64_t amount, const std::string& what);
  Status append_instance(const RawMesh& prim, const Mat4& m);
  void note(const std::string& text) {
    if (std::find(notes_.begin(), notes_.end(), text) == notes_.end()) notes_.push_back(text);
  }

  const Scene& scene_;
  uint64_t budget_;
  uint64_t used_ = 0;
  std::vector<std::vector<Prepared>> prepared_;
  std::vector<std::string> notes_;
  RawMesh out_;
  bool normals_all_ = true, normals_any_ = false;
  bool texcoords_all_ = true, texcoords_any_ = false;
  uint64_t skipped_primitives_ = 0;
  uint64_t dropped_degenerate_ = 0;
};

Status Flattener::charge(uint64_t amount, const std::string& what) {
  if (amount > budget_ - std::min(used_, budget_)) {
    return invalid_input(what + " exceeds the limit of " + str(budget_) +
                         " vertices plus triangles for an input of this size");
  }
  used_ += amount;
  return Status::ok();
}

Status Flattener::check_extensions() {
  for (const std::string& name : scene_.extensions_required) {
    if (!required_extension_ok(name)) {
      return unsupported("required glTF extension '" + name.substr(0, 100) + "' is not supported");
    }
  }
  for (const std::string& name : scene_.extensions_used) {
    if (name != "KHR_mesh_quantization") {
      note("ignored glTF extension '" + name.substr(0, 100) + "'");
    }
  }
  return Status::ok();
}

// The root nodes of the default scene (the reader has checked that the
// nodes form a forest and that scenes list roots only once).
Result<std::vector<uint32_t>> Flattener::roots() {
  std::vector<uint32_t> out;
  if (scene_.scenes.empty()) {
    std::vector<uint8_t> is_child(scene_.nodes.size(), 0);
    for (const SceneNode& n : scene_.nodes)
      for (uint32_t c : n.children)
        if (c < is_child.size()) is_child[c] = 1;
    for (uint32_t i = 0; i < is_child.size(); ++i)
      if (!is_child[i]) out.push_back(i);
    if (!scene_.nodes.empty()) note("no scenes: used every root node");
    return out;
  }
  size_t chosen = 0;
  if (scene_.default_scene < 0) {
    note("no default scene given: used scene 0");
  } else {
    chosen = static_cast<size_t>(scene_.default_scene);
    if (chosen >= scene_.scenes.size()) {
      return invalid_input("the default scene " + str(chosen) + " does not exist");
    }
  }
  for (size_t s = 0; s < scene_.scenes.size(); ++s)
    if (s != chosen) note("ignored scene " + str(s) + " (not the default scene)");
  return scene_.scenes[chosen].nodes;
}

void Flattener::note_ignored_top_level() {
  const std::pair<const char*, size_t> kinds[] = {
      {"material", scene_.materials.size()},   {"texture", scene_.textures.size()},
      {"image", scene_.images.size()},         {"sampler", scene_.samplers.size()},
      {"animation", scene_.animations.size()}, {"skin", scene_.skins.size()},
      {"camera", scene_.cameras.size()}};
  for (const auto& kind : kinds) {
    const size_t n = kind.second;
    if (n > 0) note("ignored " + str(n) + " " + kind.first + (n == 1 ? "" : "s"));
  }
}

Status Flattener::prepare(const ScenePrimitive& prim, const std::string& where, Prepared* out) {
  if (prim.mode < PrimitiveMode::kTriangles) {
    ++skipped_primitives_;
    note("skipped " + where + ": mode " + mode_name(prim.mode) + " is not triangles");
    return Status::ok();
  }
  for (const SceneAttribute& a : prim.attributes) {
    if (a.semantic != "POSITION" && a.semantic != "NORMAL" && a.semantic != "TEXCOORD_0") {
      note("ignored vertex attribute '" + a.semantic.substr(0, 100) + "'");
    }
  }
  if (!prim.targets.empty()) note("ignored morph targets");
  const SceneAttribute* position = prim.find("POSITION");
  if (position == nullptr) {
    ++skipped_primitives_;
    note("skipped " + where + ": no POSITION attribute");
    return Status::ok();
  }
  const SceneAttribute* normal = prim.find("NORMAL");
  const SceneAttribute* texcoord = prim.find("TEXCOORD_0");
  const std::pair<const SceneAttribute*, uint32_t> wanted[] = {
      {position, 3}, {normal, 3}, {texcoord, 2}};
  for (const auto& w : wanted) {
    if (w.first == nullptr) continue;
    const AccessorData& d = w.first->data;
    if (d.components() != w.second) {
      return invalid_input(where + ": " + w.first->semantic + " has " + str(d.components()) +
                           " components per element, " + str(w.second) + " expected");
    }
    if (d.count != position->data.count || d.bytes.size() != size_t{d.count} * d.element_size()) {
      return invalid_input(where + ": attribute counts differ from the POSITION count " +
                           str(position->data.count));
    }
  }
  const size_t count = position->data.count;
  const size_t sequence = prim.indices ? prim.indices->size() : count;
  if (prim.indices) {
    for (size_t i = 0; i < prim.indices->size(); ++i) {
      if ((*prim.indices)[i] >= count) {
        return invalid_input(where + ": index " + str((*prim.indices)[i]) + " at position " +
                             str(i) + " out of range (" + str(count) + " vertices)");
      }
    }
  }
  if (prim.mode == PrimitiveMode::kTriangles && sequence % 3 != 0) {
    return invalid_input(where + ": " + str(sequence) + " indices do not form whole triangles");
  }
  LODBAKE_RETURN_IF_ERROR(charge(count + sequence / 3, where));
  RawMesh& raw = out->mesh;
  const std::vector<float> xyz = float_values(position->data);
  raw.positions.resize(count);
  for (size_t v = 0; v < count; ++v)
    raw.positions[v] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
  if (normal != nullptr) raw.normals = float_values(normal->data);
  if (texcoord != nullptr) {
    raw.texcoords = float_values(texcoord->data);
    for (size_t i = 1; i < raw.texcoords.size(); i += 2)
      raw.texcoords[i] = 1.0f - raw.texcoords[i];
  }
  raw.triangles = primitive_triangles(prim);
  if (prim.mode != PrimitiveMode::kTriangles && sequence >= 3) {
    dropped_degenerate_ += (sequence - 2) - raw.triangles.size();
  }
  out->usable = true;
  return Status::ok();
}

Result<const Prepared*> Flattener::primitive(size_t mesh, size_t index) {
  Prepared& slot = prepared_[mesh][index];
  if (!slot.done) {
    slot.done = true;
    LODBAKE_RETURN_IF_ERROR(prepare(scene_.meshes[mesh].primitives[index],
                                    "mesh " + str(mesh) + " primitive " + str(index), &slot));
  }
  return static_cast<const Prepared*>(&slot);
}

Status Flattener::append_instance(const RawMesh& prim, const Mat4& m) {
  LODBAKE_RETURN_IF_ERROR(charge(prim.positions.size() + prim.triangles.size(),
                                 "instancing the meshes of the default scene"));
  if (out_.positions.size() + prim.positions.size() > 0xFFFFFFFEull) {
    return invalid_input("the default scene has more than 2^32 - 2 vertices");
  }
  const bool identity = is_identity(m);
  const double det = linear_determinant(m);
  const uint32_t base = static_cast<uint32_t>(out_.positions.size());
  for (const Vec3f& p : prim.positions) {
    if (identity) {
      out_.positions.push_back(p);
      continue;
    }
    Vec3f q;
    for (int r = 0; r < 3; ++r) {
      q[r] = static_cast<float>(m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
    }
    out_.positions.push_back(q);
  }
  const bool has_normals = !prim.normals.empty();
  normals_any_ = normals_any_ || has_normals;
  if (!has_normals && normals_all_) {
    normals_all_ = false;
    out_.normals.clear();
    out_.normals.shrink_to_fit();
  }
  if (has_normals && normals_all_) {
    // Inverse transpose of the linear part, up to the factor 1/det: the
    // cofactor matrix, with det's sign so mirrored normals point outward.
    auto a = [&](int r, int c) { return m[static_cast<size_t>(c) * 4 + static_cast<size_t>(r)]; };
    const double sign = det < 0 ? -1.0 : 1.0;
    const double cof[3][3] = {
        {a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2),
         a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0)},
        {a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2), a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0),
         a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1)},
        {a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1), a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2),
         a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0)}};
    for (size_t i = 0; i < prim.normals.size(); i += 3) {
      if (identity) {
        out_.normals.insert(out_.normals.end(), &prim.normals[i], &prim.normals[i] + 3);
        continue;
      }
      double n[3];
      for (int r = 0; r < 3; ++r) {
        n[r] = sign * (cof[r][0] * prim.normals[i] + cof[r][1] * prim.normals[i + 1] +
                       cof[r][2] * prim.normals[i + 2]);
      }
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int r = 0; r < 3; ++r) {
        out_.normals.push_back(static_cast<float>(len > 0 ? n[r] / len : n[r]));
      }
    }
  }
  const bool has_texcoords = !prim.texcoords.empty();
  texcoords_any_ = texcoords_any_ || has_texcoords;
  if (!has_texcoords && texcoords_all_) {
    texcoords_all_ = false;
    out_.texcoords.clear();
    out_.texcoords.shrink_to_fit();
  }
  if (has_texcoords && texcoords_all_) {
    out_.texcoords.insert(out_.texcoords.end(), prim.texcoords.begin(), prim.texcoords.end());
  }
  for (const std::array<uint32_t, 3>& t : prim.triangles) {
    if (det < 0) {
      out_.triangles.push_back({base + t[0], base + t[2], base + t[1]});
    } else {
      out_.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }
  return Status::ok();
}

Result<TriangleMesh> Flattener::run(ImportReport* report) {
  LODBAKE_RETURN_IF_ERROR(check_extensions());
  prepared_.resize(scene_.meshes.size());
  for (size_t i = 0; i < scene_.meshes.size(); ++i)
    prepared_[i].resize(scene_.meshes[i].primitives.size());
  LODBAKE_ASSIGN_OR_RETURN(const std::vector<uint32_t> scene_roots, roots());
  note_ignored_top_level();

  const size_t node_count = scene_.nodes.size();
  // Iterative, and each node entered once: a scene from anywhere (not only
  // the glTF reader, which checks this) cannot loop or instance twice.
  std::vector<uint8_t> reached(node_count, 0);
  std::vector<std::pair<uint32_t, Mat4>> stack;
  for (auto it = scene_roots.rbegin(); it != scene_roots.rend(); ++it)
    stack.emplace_back(*it, identity_matrix());
  while (!stack.empty()) {
    const uint32_t index = stack.back().first;
    const Mat4 parent = stack.back().second;
    stack.pop_back();
    if (index >= node_count || reached[index]) {
      return invalid_input("node " + str(index) + " does not exist or is reached twice");
    }
    reached[index] = 1;
    const SceneNode& node = scene_.nodes[index];
    const Mat4 world = multiply(parent, local_matrix(node));
    if (node.mesh >= 0) {
      const size_t mesh = static_cast<size_t>(node.mesh);
      if (mesh >= scene_.meshes.size()) {
        return invalid_input("node " + str(index) + ": mesh " + str(mesh) + " out of range (" +
                             str(scene_.meshes.size()) + " meshes)");
      }
      for (size_t p = 0; p < prepared_[mesh].size(); ++p) {
        LODBAKE_ASSIGN_OR_RETURN(const Prepared* prim, primitive(mesh, p));
        if (prim->usable) LODBAKE_RETURN_IF_ERROR(append_instance(prim->mesh, world));
      }
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
      stack.emplace_back(*it, world);
  }
  if (out_.triangles.empty()) {
    return invalid_input("no triangles in the default scene" +
                         (skipped_primitives_ > 0 ? " (" + str(skipped_primitives_) +
                                                        " non-triangle primitives skipped)"
                                                  : std::string()));
  }
  if (normals_any_ && !normals_all_) note("ignored NORMAL: only some triangle primitives have it");
  if (texcoords_any_ && !texcoords_all_) {
    note("ignored TEXCOORD_0: only some triangle primitives have it");
  }
  if (dropped_degenerate_ > 0) {
    note("dropped " + str(dropped_degenerate_) +
         " zero-area stitching triangles of triangle strips/fans");
  }
  const uint64_t triangles = out_.triangles.size();
  uint64_t welded = 0;
  TriangleMesh mesh = weld_vertices(std::move(out_), weld_mode(scene_), &welded);
  if (report != nullptr) {
    report->file_faces = triangles + dropped_degenerate_;
    report->welded_vertices = welded;
    for (std::string& n : notes_)
      report->notes.push_back(std::move(n));
  }
  return mesh;
}

}  // namespace

Result<TriangleMesh> flatten_scene(const Scene& scene, uint64_t budget, ImportReport* report) {
  try {
    Flattener flattener(scene, budget);
    return flattener.run(report);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while merging the scene's meshes");
  }
}

}  // namespace lodbake
