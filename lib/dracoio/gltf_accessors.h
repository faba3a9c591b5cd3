// Internal to lib/dracoio: bounded access to glTF accessors and buffer
// views. Every view is checked against its buffer (offsets, lengths,
// overflow-safe) before any byte is read.
#pragma once

#include <cstdint>
#include <string>

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

}  // namespace dracoio
}  // namespace lodbake
