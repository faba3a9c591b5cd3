// glTF 2.0 / GLB import: every triangle primitive of the default scene, node
// transforms applied, merged into one mesh, then welded by exact position.
//
// Why not draco::GltfDecoder (Draco 1.5.5, Debian 12)? Checked on this
// machine: DecodeFromBuffer reads only GLB, flattens every scene instead of
// the default one, fails the whole file on a LINES primitive, ignores a node
// rotation of exactly [0, 0, 1, 0] (it mistakes it for the identity), reads
// out of bounds on an index past the vertex count and overflows the stack on
// a cycle of node children. So this module parses the JSON itself (bounded,
// see gltf_document.cpp, gltf_accessors.cpp, gltf_nodes.cpp) and uses Draco
// for what it is good at: KHR_draco_mesh_compression primitives (decoded with
// draco::Decoder), .drc files and GLB export.
//
// Choices where the specification is loose or a policy is needed:
// - Order: scene roots in the scene's order, each subtree depth-first in
//   `children` order, each mesh's primitives in order; a mesh used by several
//   nodes is decoded once and instanced.
// - Modes TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN are triangles (strips
//   and fans are unrolled as the specification's formulas say, dropping the
//   zero-area stitching triangles that repeat an index); POINTS and LINE*
//   primitives are skipped with a note.
// - Positions are transformed in double precision, normals by the inverse
//   transpose and renormalized; an identity transform leaves values
//   bit-exact. A mirroring transform (negative determinant) reverses the
//   winding so triangles stay counter-clockwise.
// - TEXCOORD_0 is flipped to v' = 1 - v: lodbake (like OBJ, PLY and Draco)
//   puts the texture origin bottom-left, glTF top-left.
// - NORMAL / TEXCOORD_0 are kept only when every imported triangle primitive
//   has them; otherwise they are dropped with a note.
// - Instancing can multiply geometry: the total of decoded and instanced
//   vertices and triangles is capped at max(2^22, 64 x input bytes).
// - Welding: every exactly equal position is one vertex, except in a file
//   lodbake wrote, whose asset.extras.lodbake_weld says how its index buffer
//   relates to the topology ("none": it is the topology; "manifold_edges":
//   only seams were split), so that a repaired mesh reads back as written
//   (mesh_weld.h, docs/import.md). Other values weld every position.
// - External buffers are read through SceneResources (the caller passes the
//   file's folder); EXT_meshopt_compression views are decoded by the
//   document loader. This reader stays separate from read_gltf_scene()
//   (gltf_scene_import.cpp), which keeps what this one merges or drops;
//   flattening a Scene here instead would make one reader of the two.
// - Draco itself is not bounded in time: a crafted 200-byte Draco stream can
//   keep its texture-coordinate prediction decoder busy for seconds (it
//   loops over an orientation count read from the stream). Each compressed
//   bufferView is therefore decoded at most once.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "draco/compression/decode.h"
#include "draco/core/decoder_buffer.h"
#include "lib/dracoio/draco_convert.h"
#include "lib/dracoio/draco_header.h"
#include "lib/dracoio/draco_io.h"
#include "lib/dracoio/gltf_accessors.h"
#include "lib/dracoio/gltf_document.h"
#include "lib/dracoio/gltf_nodes.h"
#include "lib/dracoio/mesh_weld.h"

namespace lodbake {
namespace {

using dracoio::GltfDocument;
using dracoio::Json;

using dracoio::RawMesh;

constexpr uint64_t kMinBudget = uint64_t{1} << 22;
constexpr uint64_t kBudgetPerInputByte = 64;
constexpr int64_t kModeTriangles = 4, kModeStrip = 5;  // 6 is TRIANGLE_FAN

std::string str(uint64_t v) {
  return std::to_string(v);
}

const char* mode_name(int64_t mode) {
  static constexpr const char* kNames[] = {
      "POINTS", "LINES", "LINE_LOOP", "LINE_STRIP", "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return kNames[mode];
}

// Required extensions that do not change geometry, or that this reader handles.
bool required_extension_ok(const std::string& name) {
  return name == "KHR_draco_mesh_compression" || name == "EXT_meshopt_compression" ||
         name == "KHR_mesh_quantization" || name == "KHR_texture_transform" ||
         name == "KHR_texture_basisu" || name == "EXT_texture_webp" ||
         name == "KHR_lights_punctual" || name.compare(0, 14, "KHR_materials_") == 0;
}

struct Primitive {
  bool usable = false;
  RawMesh mesh;
};

class GltfImporter {
 public:
  GltfImporter(const GltfDocument& doc, uint64_t input_size)
      : doc_(doc), budget_(std::max(kMinBudget, kBudgetPerInputByte * input_size)) {}

  Result<TriangleMesh> run(ImportReport* report);

 private:
  Status check_extensions();
  void note_ignored_top_level();
  Result<const Primitive*> primitive(size_t mesh, size_t index);
  Status decode_primitive(const Json& prim, const std::string& where, Primitive* out);
  Status decode_draco_primitive(const Json& ext, int64_t normal, int64_t texcoord,
                                const std::string& where, RawMesh* out);
  Status assemble_triangles(const std::vector<uint32_t>& indices, int64_t mode, size_t vertices,
                            const std::string& where, RawMesh* out);
  Status charge(uint64_t amount, const std::string& what);
  Status append_instance(const RawMesh& prim, const Mat4& m);
  void note(const std::string& text);

  // The welding the file asks for (lodbake's GLB writer marks its files).
  dracoio::WeldMode weld_mode() const {
    const auto asset = doc_.root.find("asset");
    if (asset == doc_.root.end() || !asset->is_object()) return dracoio::WeldMode::kExactPositions;
    const auto extras = asset->find("extras");
    if (extras == asset->end() || !extras->is_object()) return dracoio::WeldMode::kExactPositions;
    const auto weld = extras->find("lodbake_weld");
    if (weld == extras->end() || !weld->is_string()) return dracoio::WeldMode::kExactPositions;
    if (*weld == "none") return dracoio::WeldMode::kNone;
    if (*weld == "manifold_edges") return dracoio::WeldMode::kManifoldEdges;
    return dracoio::WeldMode::kExactPositions;
  }

  const GltfDocument& doc_;
  uint64_t budget_;
  uint64_t used_ = 0;
  std::vector<std::vector<std::unique_ptr<Primitive>>> cache_;
  std::vector<std::string> notes_;
  std::map<uint64_t, std::shared_ptr<const draco::Mesh>> draco_meshes_;  // by bufferView
  RawMesh out_;
  bool normals_all_ = true, normals_any_ = false;
  bool texcoords_all_ = true, texcoords_any_ = false;
  uint64_t skipped_primitives_ = 0;
  uint64_t dropped_degenerate_ = 0;
};

void GltfImporter::note(const std::string& text) {
  for (const std::string& n : notes_) {
    if (n == text) return;
  }
  notes_.push_back(text);
}

Status GltfImporter::charge(uint64_t amount, const std::string& what) {
  if (amount > budget_ - used_) {
    return invalid_input(what + " exceeds the limit of " + str(budget_) +
                         " vertices plus triangles for an input of this size");
  }
  used_ += amount;
  return Status::ok();
}

Status GltfImporter::check_extensions() {
  LODBAKE_ASSIGN_OR_RETURN(const Json* required,
                           dracoio::member_array(doc_.root, "extensionsRequired", "glTF"));
  if (required != nullptr) {
    for (const Json& e : *required) {
      if (!e.is_string()) return invalid_input("glTF: 'extensionsRequired' holds a non-string");
      const std::string& name = e.get_ref<const std::string&>();
      if (!required_extension_ok(name)) {
        return unsupported("required glTF extension '" + name.substr(0, 100) +
                           "' is not supported");
      }
    }
  }
  LODBAKE_ASSIGN_OR_RETURN(const Json* used,
                           dracoio::member_array(doc_.root, "extensionsUsed", "glTF"));
  if (used != nullptr) {
    for (const Json& e : *used) {
      if (!e.is_string()) continue;
      const std::string& name = e.get_ref<const std::string&>();
      if (name != "KHR_draco_mesh_compression" && name != "KHR_mesh_quantization" &&
          name != "EXT_meshopt_compression") {
        note("ignored glTF extension '" + name.substr(0, 100) + "'");
      }
    }
  }
  return Status::ok();
}

void GltfImporter::note_ignored_top_level() {
  static constexpr const char* kKinds[][2] = {{"materials", "material"},   {"textures", "texture"},
                                              {"images", "image"},         {"samplers", "sampler"},
                                              {"animations", "animation"}, {"skins", "skin"},
                                              {"cameras", "camera"}};
  for (const auto& kind : kKinds) {
    const size_t n = dracoio::top_level_count(doc_.root, kind[0]);
    if (n > 0) note("ignored " + str(n) + " " + (n == 1 ? kind[1] : kind[0]));
  }
}

Status GltfImporter::assemble_triangles(const std::vector<uint32_t>& indices, int64_t mode,
                                        size_t vertices, const std::string& where, RawMesh* out) {
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertices) {
      return invalid_input(where + ": index " + str(indices[i]) + " at position " + str(i) +
                           " out of range (" + str(vertices) + " vertices)");
    }
  }
  const size_t n = indices.size();
  if (mode == kModeTriangles) {
    if (n % 3 != 0) {
      return invalid_input(where + ": " + str(n) + " indices do not form whole triangles");
    }
    out->triangles.reserve(n / 3);
    for (size_t i = 0; i + 2 < n; i += 3) {
      out->triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
    }
    return Status::ok();
  }
  for (size_t i = 0; i + 2 < n; ++i) {
    Triangle t;
    if (mode == kModeStrip) {
      t = i % 2 == 0 ? Triangle{indices[i], indices[i + 1], indices[i + 2]}
                     : Triangle{indices[i], indices[i + 2], indices[i + 1]};
    } else {
      t = Triangle{indices[i + 1], indices[i + 2], indices[0]};
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++dropped_degenerate_;
      continue;
    }
    out->triangles.push_back(t);
  }
  return Status::ok();
}

Status GltfImporter::decode_draco_primitive(const Json& ext, int64_t normal, int64_t texcoord,
                                            const std::string& where, RawMesh* out) {
  const std::string ext_where = where + " KHR_draco_mesh_compression";
  if (!ext.is_object()) return invalid_input(ext_where + " is not a JSON object");
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t view, dracoio::member_uint(ext, "bufferView", UINT64_MAX,
                                                                     UINT32_MAX, ext_where));
  if (view == UINT64_MAX) return invalid_input(ext_where + " has no bufferView");
  LODBAKE_ASSIGN_OR_RETURN(const dracoio::ByteSpan bytes,
                           dracoio::buffer_view_bytes(doc_, static_cast<int64_t>(view), ext_where));
  LODBAKE_ASSIGN_OR_RETURN(const Json* ids, dracoio::member_object(ext, "attributes", ext_where));
  if (ids == nullptr) return invalid_input(ext_where + " has no attributes");
  auto id_of = [&](const char* name) -> Result<int64_t> {
    LODBAKE_ASSIGN_OR_RETURN(const uint64_t id,
                             dracoio::member_uint(*ids, name, UINT64_MAX, UINT32_MAX, ext_where));
    return id == UINT64_MAX ? int64_t{-1} : static_cast<int64_t>(id);
  };
  LODBAKE_ASSIGN_OR_RETURN(const int64_t position_id, id_of("POSITION"));
  if (position_id < 0) return invalid_input(ext_where + " has no POSITION attribute id");
  LODBAKE_ASSIGN_OR_RETURN(const int64_t normal_id, id_of("NORMAL"));
  LODBAKE_ASSIGN_OR_RETURN(const int64_t texcoord_id, id_of("TEXCOORD_0"));
  // Each compressed bufferView is decoded once however many primitives use
  // it: Draco's decoders can spend seconds on a few crafted bytes.
  std::shared_ptr<const draco::Mesh>& mesh = draco_meshes_[view];
  if (mesh == nullptr) {
    const Status header = dracoio::check_draco_header(bytes.data, bytes.size);
    if (!header.is_ok()) return Status(header.kind(), ext_where + ": " + header.message());
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) {
      return invalid_input(ext_where +
                           ": Draco decoding failed: " + decoded.status().error_msg_string());
    }
    mesh = std::shared_ptr<const draco::Mesh>(std::move(decoded).value());
  }
  LODBAKE_RETURN_IF_ERROR(
      charge(uint64_t{mesh->num_points()} + mesh->num_faces(), where + " (Draco-compressed)"));
  LODBAKE_ASSIGN_OR_RETURN(
      *out, dracoio::raw_mesh_from_draco(*mesh, position_id, normal >= 0 ? normal_id : -1,
                                         texcoord >= 0 ? texcoord_id : -1));
  // An attribute listed on the primitive but not compressed is stored plainly.
  const std::pair<int64_t, int64_t> plain[] = {{normal, normal_id}, {texcoord, texcoord_id}};
  for (int a = 0; a < 2; ++a) {
    if (plain[a].first < 0 || plain[a].second >= 0) continue;
    const uint32_t components = a == 0 ? 3 : 2;
    LODBAKE_ASSIGN_OR_RETURN(std::vector<float> values,
                             dracoio::read_float_accessor(doc_, plain[a].first, components));
    if (values.size() != out->positions.size() * components) {
      return invalid_input(where + ": uncompressed " + (a == 0 ? "NORMAL" : "TEXCOORD_0") +
                           " count differs from the Draco point count");
    }
    (a == 0 ? out->normals : out->texcoords) = std::move(values);
  }
  return Status::ok();
}

Status GltfImporter::decode_primitive(const Json& prim, const std::string& where, Primitive* out) {
  if (!prim.is_object()) return invalid_input(where + " is not a JSON object");
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t mode_value,
                           dracoio::member_uint(prim, "mode", kModeTriangles, 6, where));
  const int64_t mode = static_cast<int64_t>(mode_value);
  if (mode < kModeTriangles) {
    ++skipped_primitives_;
    note("skipped " + where + ": mode " + mode_name(mode) + " is not triangles");
    return Status::ok();
  }
  LODBAKE_ASSIGN_OR_RETURN(const Json* attributes,
                           dracoio::member_object(prim, "attributes", where));
  if (attributes == nullptr) return invalid_input(where + " has no attributes");
  const size_t accessor_total = dracoio::top_level_count(doc_.root, "accessors");
  int64_t position = -1, normal = -1, texcoord = -1;
  for (auto it = attributes->begin(); it != attributes->end(); ++it) {
    int64_t* slot = it.key() == "POSITION"     ? &position
                    : it.key() == "NORMAL"     ? &normal
                    : it.key() == "TEXCOORD_0" ? &texcoord
                                               : nullptr;
    if (slot == nullptr) {
      note("ignored vertex attribute '" + it.key().substr(0, 100) + "'");
      continue;
    }
    LODBAKE_ASSIGN_OR_RETURN(
        *slot, dracoio::as_index(it.value(), accessor_total, "accessor", where + " " + it.key()));
  }
  if (prim.contains("targets")) note("ignored morph targets");
  if (position < 0) {
    ++skipped_primitives_;
    note("skipped " + where + ": no POSITION attribute");
    return Status::ok();
  }
  RawMesh& raw = out->mesh;
  const Json* draco_ext = nullptr;
  LODBAKE_ASSIGN_OR_RETURN(const Json* extensions,
                           dracoio::member_object(prim, "extensions", where));
  if (extensions != nullptr) {
    const auto it = extensions->find("KHR_draco_mesh_compression");
    if (it != extensions->end()) draco_ext = &*it;
  }
  if (draco_ext != nullptr) {
    LODBAKE_RETURN_IF_ERROR(decode_draco_primitive(*draco_ext, normal, texcoord, where, &raw));
  } else {
    int64_t indices_accessor = -1;
    LODBAKE_ASSIGN_OR_RETURN(
        indices_accessor,
        dracoio::member_index(prim, "indices", accessor_total, "accessor", where + " indices"));
    // Reading first bounds the allocation by the bytes present; the charge
    // then stops files that decode the same large accessor many times.
    LODBAKE_ASSIGN_OR_RETURN(const std::vector<float> xyz,
                             dracoio::read_float_accessor(doc_, position, 3));
    const size_t count = xyz.size() / 3;
    LODBAKE_RETURN_IF_ERROR(charge(count, where));
    raw.positions.resize(count);
    for (size_t v = 0; v < count; ++v)
      raw.positions[v] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
    if (normal >= 0) {
      LODBAKE_ASSIGN_OR_RETURN(raw.normals, dracoio::read_float_accessor(doc_, normal, 3));
    }
    if (texcoord >= 0) {
      LODBAKE_ASSIGN_OR_RETURN(raw.texcoords, dracoio::read_float_accessor(doc_, texcoord, 2));
    }
    if ((normal >= 0 && raw.normals.size() != 3 * count) ||
        (texcoord >= 0 && raw.texcoords.size() != 2 * count)) {
      return invalid_input(where + ": attribute counts differ from the POSITION count " +
                           str(count));
    }
    std::vector<uint32_t> indices;
    if (indices_accessor >= 0) {
      LODBAKE_ASSIGN_OR_RETURN(indices, dracoio::read_index_accessor(doc_, indices_accessor));
    } else {
      indices.resize(count);
      for (size_t i = 0; i < count; ++i)
        indices[i] = static_cast<uint32_t>(i);
    }
    LODBAKE_RETURN_IF_ERROR(charge(indices.size() / 3, where));
    LODBAKE_RETURN_IF_ERROR(assemble_triangles(indices, mode, count, where, &raw));
  }
  for (size_t i = 1; i < raw.texcoords.size(); i += 2)
    raw.texcoords[i] = 1.0f - raw.texcoords[i];
  out->usable = true;
  return Status::ok();
}

Result<const Primitive*> GltfImporter::primitive(size_t mesh, size_t index) {
  std::unique_ptr<Primitive>& slot = cache_[mesh][index];
  if (slot == nullptr) {
    const Json& m = doc_.root.at("meshes").at(mesh);
    auto decoded = std::make_unique<Primitive>();
    const std::string where = "mesh " + str(mesh) + " primitive " + str(index);
    LODBAKE_RETURN_IF_ERROR(decode_primitive(m.at("primitives").at(index), where, decoded.get()));
    slot = std::move(decoded);
  }
  return static_cast<const Primitive*>(slot.get());
}

Status GltfImporter::append_instance(const RawMesh& prim, const Mat4& m) {
  LODBAKE_RETURN_IF_ERROR(charge(prim.positions.size() + prim.triangles.size(),
                                 "instancing the meshes of the default scene"));
  if (out_.positions.size() + prim.positions.size() > 0xFFFFFFFEull) {
    return invalid_input("the default scene has more than 2^32 - 2 vertices");
  }
  const bool identity = dracoio::is_identity(m);
  const double det = dracoio::linear_determinant(m);
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
  for (const Triangle& t : prim.triangles) {
    if (det < 0) {
      out_.triangles.push_back({base + t[0], base + t[2], base + t[1]});
    } else {
      out_.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }
  return Status::ok();
}

Result<TriangleMesh> GltfImporter::run(ImportReport* report) {
  LODBAKE_RETURN_IF_ERROR(check_extensions());
  LODBAKE_ASSIGN_OR_RETURN(const Json* meshes, dracoio::member_array(doc_.root, "meshes", "glTF"));
  const size_t mesh_count = meshes == nullptr ? 0 : meshes->size();
  cache_.resize(mesh_count);
  for (size_t i = 0; i < mesh_count; ++i) {
    const std::string where = "mesh " + str(i);
    if (!(*meshes)[i].is_object()) return invalid_input(where + " is not a JSON object");
    LODBAKE_ASSIGN_OR_RETURN(const Json* prims,
                             dracoio::member_array((*meshes)[i], "primitives", where));
    if (prims == nullptr) return invalid_input(where + " has no primitives");
    cache_[i].resize(prims->size());
  }
  LODBAKE_ASSIGN_OR_RETURN(const dracoio::NodeForest forest,
                           dracoio::load_nodes(doc_.root, mesh_count));
  LODBAKE_ASSIGN_OR_RETURN(const dracoio::SceneChoice scene,
                           dracoio::choose_scene(doc_.root, forest));
  for (const std::string& n : scene.notes)
    note(n);
  note_ignored_top_level();

  std::vector<std::pair<uint32_t, Mat4>> stack;
  for (auto it = scene.roots.rbegin(); it != scene.roots.rend(); ++it) {
    stack.emplace_back(*it, identity_matrix());
  }
  while (!stack.empty()) {
    const uint32_t node = stack.back().first;
    const Mat4 world = multiply(stack.back().second, forest.local[node]);
    stack.pop_back();
    const int64_t mesh = forest.mesh[node];
    if (mesh >= 0) {
      for (size_t p = 0; p < cache_[static_cast<size_t>(mesh)].size(); ++p) {
        LODBAKE_ASSIGN_OR_RETURN(const Primitive* prim, primitive(static_cast<size_t>(mesh), p));
        if (prim->usable) LODBAKE_RETURN_IF_ERROR(append_instance(prim->mesh, world));
      }
    }
    const auto& children = forest.children[node];
    for (auto it = children.rbegin(); it != children.rend(); ++it)
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
  TriangleMesh mesh = dracoio::weld_vertices(std::move(out_), weld_mode(), &welded);
  if (report != nullptr) {
    report->format = doc_.binary ? "glb" : "gltf";
    report->file_faces = triangles + dropped_degenerate_;
    report->welded_vertices = welded;
    for (std::string& n : notes_)
      report->notes.push_back(std::move(n));
  }
  return mesh;
}

Result<TriangleMesh> parse_gltf_unchecked(const uint8_t* data, size_t size, ImportReport* report,
                                          const SceneResources& resources) {
  LODBAKE_ASSIGN_OR_RETURN(const GltfDocument doc,
                           dracoio::load_gltf_document(data, size, resources));
  GltfImporter importer(doc, size);
  return importer.run(report);
}

}  // namespace

Result<TriangleMesh> parse_gltf(const uint8_t* data, size_t size, ImportReport* report,
                                const SceneResources& resources) {
  return dracoio::guard_exceptions<TriangleMesh>(
      [&] { return parse_gltf_unchecked(data, size, report, resources); });
}

}  // namespace lodbake
