// glTF 2.0 accessors and buffer views (specification sections "Accessors",
// "Buffers and Buffer Views"): the bounds every read goes through. The
// elements themselves are read by gltf_accessor_data.cpp.
#include "lib/dracoio/gltf_accessors.h"

#include <string>

namespace lodbake {
namespace dracoio {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

}  // namespace

Result<const Json*> accessor_object(const GltfDocument& doc, int64_t index,
                                    const std::string& where) {
  LODBAKE_ASSIGN_OR_RETURN(const Json* accessors, member_array(doc.root, "accessors", "glTF"));
  if (accessors == nullptr || index < 0 || static_cast<uint64_t>(index) >= accessors->size()) {
    return invalid_input(where + " out of range (" +
                         str(accessors == nullptr ? 0 : accessors->size()) + " accessors)");
  }
  const Json& a = (*accessors)[static_cast<size_t>(index)];
  if (!a.is_object()) return invalid_input(where + " is not a JSON object");
  return &a;
}

Result<ByteSpan> buffer_view_bytes(const GltfDocument& doc, int64_t index,
                                   const std::string& where) {
  LODBAKE_ASSIGN_OR_RETURN(const Json* views, member_array(doc.root, "bufferViews", "glTF"));
  const size_t view_count = views == nullptr ? 0 : views->size();
  if (index < 0 || static_cast<uint64_t>(index) >= view_count) {
    return invalid_input(where + ": bufferView " + str(static_cast<uint64_t>(index)) +
                         " out of range (" + str(view_count) + " bufferViews)");
  }
  const std::string view_where = "bufferView " + str(static_cast<uint64_t>(index));
  const Json& v = (*views)[static_cast<size_t>(index)];
  if (!v.is_object()) return invalid_input(view_where + " is not a JSON object");
  const auto decoded = doc.decoded_views.find(index);
  if (decoded != doc.decoded_views.end()) {
    return ByteSpan{decoded->second.data(), decoded->second.size()};
  }
  LODBAKE_ASSIGN_OR_RETURN(const int64_t buffer,
                           member_index(v, "buffer", doc.buffers.size(), "buffer", view_where));
  if (buffer < 0) return invalid_input(view_where + " has no buffer");
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t offset,
                           member_uint(v, "byteOffset", 0, 0xFFFFFFFFFFull, view_where));
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t length,
                           member_uint(v, "byteLength", 0, 0xFFFFFFFFFFull, view_where));
  const ByteSpan& bytes = doc.buffers[static_cast<size_t>(buffer)];
  if (offset + length > bytes.size) {
    return invalid_input(view_where + ": bytes " + str(offset) + " to " + str(offset + length) +
                         " lie outside buffer " + str(static_cast<uint64_t>(buffer)) + " of " +
                         str(bytes.size) + " bytes");
  }
  return ByteSpan{bytes.data + offset, static_cast<size_t>(length)};
}

}  // namespace dracoio
}  // namespace lodbake
