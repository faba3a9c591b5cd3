// The Draco BASE codec of a build without Draco (LODBAKE_DRACO_CODEC=OFF):
// the same API, every call answering that this build cannot do it, so
// callers need no build switches of their own (readers refuse such sections
// earlier, with LBK-E020: formats/container/section_codecs.h).
#include "formats/sections/draco_codec.h"

namespace lodbake {
namespace {

Status no_draco() {
  return unsupported("this build has no Draco codec (built with LODBAKE_DRACO_CODEC=OFF)");
}

}  // namespace

Result<Bytes> encode_base_draco(const TriangleMesh&, const DracoOptions&) {
  return no_draco();
}

Result<DracoOptions> read_draco_base_options(const uint8_t*, size_t) {
  return no_draco();
}

Result<TriangleMesh> decode_base_draco(const uint8_t*, size_t) {
  return no_draco();
}

}  // namespace lodbake
