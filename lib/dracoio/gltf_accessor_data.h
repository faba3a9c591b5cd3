// Internal to lib/dracoio: glTF accessors read as the scene model's dense
// AccessorData (component type kept, matrix column padding removed, sparse
// substitution applied), bounded by the document's decode budget.
#pragma once

#include <cstdint>
#include <string>

#include "formats/scene/scene.h"
#include "formats/support/status.h"
#include "lib/dracoio/gltf_document.h"

namespace lodbake {
namespace dracoio {

// Accessor `index` as dense data: every element bounds-checked against its
// bufferView, the output charged to doc->budget before it is allocated.
Result<AccessorData> read_accessor_data(GltfDocument* doc, int64_t index);

// The componentType, type, normalized and count an accessor declares
// (AccessorData with no bytes), checked: for decoders that produce the data
// themselves (KHR_draco_mesh_compression).
Result<AccessorData> accessor_declaration(const GltfDocument& doc, int64_t index);

// The element type named by a glTF accessor.type string, false when unknown.
bool parse_element_type(const std::string& name, ElementType* out);

}  // namespace dracoio
}  // namespace lodbake
