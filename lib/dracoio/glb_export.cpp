// GLB export through Draco's glTF encoder (draco::GltfEncoder, uncompressed:
// the mesh carries no Draco compression settings). The encoder writes one
// node, one mesh, one primitive and one default grey material and no
// timestamps, so equal meshes give equal bytes. It flips texture coordinates
// to glTF's top-left origin, the inverse of what parse_gltf does on import.
// Its generator string is a constant ("draco_decoder") that Draco offers no
// way to set, so the JSON chunk is rewritten afterwards (members kept in
// Draco's order) to name lodbake and its version in `asset.generator` and to
// say in `asset.extras.lodbake_weld` how parse_gltf must weld the vertices
// back: "none" when every attribute is per vertex (the index buffer is the
// topology, split vertices of a repaired mesh included), "manifold_edges"
// when per-corner attributes made seams (mesh_weld.h, docs/import.md).
#include <new>
#include <string>

#include <nlohmann/json.hpp>

#include "draco/core/encoder_buffer.h"
#include "draco/io/gltf_encoder.h"
#include "formats/support/version.h"
#include "lib/dracoio/draco_convert.h"
#include "lib/dracoio/draco_io.h"

namespace lodbake {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr size_t kGlbHeaderSize = 12;
constexpr size_t kGlbChunkHeaderSize = 8;

uint32_t load_u32(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

void append_u32(Bytes* out, uint32_t value) {
  for (int i = 0; i < 4; ++i)
    out->push_back(static_cast<uint8_t>(value >> (8 * i)));
}

// `glb` with its JSON chunk's asset.generator set to "lodbake VERSION" and
// asset.extras.lodbake_weld to `weld`; the chunks after the JSON chunk are
// copied unchanged.
Result<Bytes> mark_asset(const Bytes& glb, const char* weld) {
  if (glb.size() < kGlbHeaderSize + kGlbChunkHeaderSize || load_u32(glb.data()) != kGlbMagic ||
      load_u32(glb.data() + 8) != glb.size() || load_u32(glb.data() + 16) != kGlbJsonChunk) {
    return runtime_error("glTF encoding failed: the encoder's GLB has an unexpected layout");
  }
  const size_t json_size = load_u32(glb.data() + 12);
  const size_t json_start = kGlbHeaderSize + kGlbChunkHeaderSize;
  if (json_size > glb.size() - json_start)
    return runtime_error("glTF encoding failed: the encoder's JSON chunk overruns the GLB");
  nlohmann::ordered_json root = nlohmann::ordered_json::parse(
      glb.begin() + static_cast<std::ptrdiff_t>(json_start),
      glb.begin() + static_cast<std::ptrdiff_t>(json_start + json_size), nullptr, false);
  if (root.is_discarded() || !root.is_object() || !root["asset"].is_object())
    return runtime_error("glTF encoding failed: the encoder's JSON chunk has no asset object");
  root["asset"]["generator"] = std::string("lodbake ") + kLodbakeVersion;
  root["asset"]["extras"]["lodbake_weld"] = weld;
  std::string json = root.dump();
  json.append((4 - json.size() % 4) % 4, ' ');  // chunks are 4-byte aligned, padded with spaces
  const size_t rest = glb.size() - json_start - json_size;
  Bytes out;
  out.reserve(kGlbHeaderSize + kGlbChunkHeaderSize + json.size() + rest);
  append_u32(&out, kGlbMagic);
  append_u32(&out, load_u32(glb.data() + 4));  // container version, as written
  append_u32(&out,
             static_cast<uint32_t>(kGlbHeaderSize + kGlbChunkHeaderSize + json.size() + rest));
  append_u32(&out, static_cast<uint32_t>(json.size()));
  append_u32(&out, kGlbJsonChunk);
  out.insert(out.end(), json.begin(), json.end());
  out.insert(out.end(), glb.begin() + static_cast<std::ptrdiff_t>(json_start + json_size),
             glb.end());
  return out;
}

Result<Bytes> write_glb_unchecked(const TriangleMesh& mesh) {
  LODBAKE_ASSIGN_OR_RETURN(std::unique_ptr<draco::Mesh> draco_mesh, dracoio::to_draco_mesh(mesh));
  draco::GltfEncoder encoder;
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeToBuffer(*draco_mesh, &buffer);
  if (!status.ok()) return runtime_error("glTF encoding failed: " + status.error_msg_string());
  const auto* bytes = reinterpret_cast<const uint8_t*>(buffer.data());
  const bool seams = mesh.normals.binding == AttributeBinding::kPerCorner ||
                     mesh.texcoords.binding == AttributeBinding::kPerCorner;
  return mark_asset(Bytes(bytes, bytes + buffer.size()), seams ? "manifold_edges" : "none");
}

}  // namespace

Result<Bytes> write_glb(const TriangleMesh& mesh) {
  try {
    return write_glb_unchecked(mesh);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while writing GLB");
  } catch (const std::exception& e) {
    return runtime_error(std::string("glTF encoding failed: ") + e.what());
  }
}

}  // namespace lodbake
