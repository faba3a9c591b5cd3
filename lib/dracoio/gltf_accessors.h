// Internal to lib/dracoio: bounded reading of glTF accessors. Every accessor
// is checked against its buffer view and buffer (offsets, stride, count,
// overflow-safe) before any element is read or any memory is allocated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/support/status.h"
#include "lib/dracoio/gltf_document.h"

namespace lodbake {
namespace dracoio {

// The JSON object of accessor `index`, named `where` in messages: an error
// when out of range or not an object.
Result<const Json*> accessor_object(const GltfDocument& doc, int64_t index,
                                    const std::string& where);

// The bytes of buffer view `index` (checked against its buffer).
Result<ByteSpan> buffer_view_bytes(const GltfDocument& doc, int64_t index,
                                   const std::string& where);

// Reads accessor `index`, which must have `components` components per
// element (e.g. 3 for VEC3), as floats: float components as they are,
// integer components normalized when the accessor says so (glTF 2.0
// "Animations" / KHR_mesh_quantization rules), converted otherwise.
Result<std::vector<float>> read_float_accessor(const GltfDocument& doc, int64_t index,
                                               uint32_t components);

// Reads index accessor `index` (SCALAR, unsigned byte/short/int).
Result<std::vector<uint32_t>> read_index_accessor(const GltfDocument& doc, int64_t index);

}  // namespace dracoio
}  // namespace lodbake
