// GLB export through Draco's glTF encoder (draco::GltfEncoder, uncompressed:
// the mesh carries no Draco compression settings). The encoder writes one
// node, one mesh, one primitive and one default grey material, a constant
// generator string ("draco_decoder") and no timestamps, so equal meshes give
// equal bytes. It flips texture coordinates to glTF's top-left origin, the
// inverse of what parse_gltf does on import.
#include <new>
#include <string>

#include "draco/core/encoder_buffer.h"
#include "draco/io/gltf_encoder.h"
#include "lib/dracoio/draco_convert.h"
#include "lib/dracoio/draco_io.h"

namespace lodbake {
namespace {

Result<Bytes> write_glb_unchecked(const TriangleMesh& mesh) {
  LODBAKE_ASSIGN_OR_RETURN(std::unique_ptr<draco::Mesh> draco_mesh, dracoio::to_draco_mesh(mesh));
  draco::GltfEncoder encoder;
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeToBuffer(*draco_mesh, &buffer);
  if (!status.ok()) return runtime_error("glTF encoding failed: " + status.error_msg_string());
  const auto* bytes = reinterpret_cast<const uint8_t*>(buffer.data());
  return Bytes(bytes, bytes + buffer.size());
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
