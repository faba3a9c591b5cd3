// Internal to lib/dracoio: KHR_draco_mesh_compression primitives decoded
// into the scene model's streams, with the component types the primitive's
// accessors declare.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "formats/scene/scene.h"
#include "formats/support/status.h"
#include "lib/dracoio/gltf_document.h"

namespace draco {
class Mesh;
}

namespace lodbake {
namespace dracoio {

struct DracoStreams {
  uint32_t points = 0;  // vertices of the primitive (Draco points)
  std::vector<uint32_t> indices;
  // For each semantic the extension lists, its stream.
  std::map<std::string, AccessorData> attributes;
};

class DracoPrimitiveDecoder {
 public:
  DracoPrimitiveDecoder();
  ~DracoPrimitiveDecoder();

  // Decodes the primitive whose KHR_draco_mesh_compression object is `ext`
  // and whose attributes object is `attributes`: every semantic listed in
  // the extension, converted to its accessor's declared type (count = the
  // Draco point count). Each compressed bufferView is decoded once however
  // many primitives use it: Draco can spend seconds on a few crafted bytes.
  Result<DracoStreams> decode(GltfDocument* doc, const Json& ext, const Json& attributes,
                              const std::string& where);

 private:
  std::map<uint64_t, std::shared_ptr<const draco::Mesh>> meshes_;  // by bufferView
};

}  // namespace dracoio
}  // namespace lodbake
