// Internal to lib/dracoio: EXT_meshopt_compression (glTF extension by
// Khronos/meshoptimizer) bufferViews decoded with meshoptimizer's decoder.
#pragma once

#include "formats/support/status.h"
#include "lib/dracoio/gltf_document.h"

namespace lodbake {
namespace dracoio {

// Decodes every bufferView that carries EXT_meshopt_compression into
// doc->decoded_views, charging doc->budget before allocating. Every field
// the decoder's preconditions depend on (mode, filter, stride, count) is
// checked first: meshoptimizer asserts them only in debug builds.
Status decode_meshopt_views(GltfDocument* doc);

}  // namespace dracoio
}  // namespace lodbake
