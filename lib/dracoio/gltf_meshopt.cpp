// EXT_meshopt_compression (KhronosGroup/glTF, extensions/2.0/Vendor/
// EXT_meshopt_compression): a bufferView's bytes are stored compressed in
// another buffer range and decoded with meshoptimizer (0.18, the Debian
// package): ATTRIBUTES with meshopt_decodeVertexBuffer then the view's
// filter, TRIANGLES with meshopt_decodeIndexBuffer, INDICES with
// meshopt_decodeIndexSequence. Choices:
// - The decoded size is count x byteStride; the bufferView's byteLength
//   must not exceed it, and the view reads as its first byteLength bytes.
// - Unknown modes and filters are refused as unsupported (exit 5); wrong
//   strides or counts for a mode are invalid input, checked before calling
//   the decoder (its own checks are debug-build asserts).
#include "lib/dracoio/gltf_meshopt.h"

#include <meshoptimizer.h>

#include <string>

namespace lodbake {
namespace dracoio {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

Status decode_view(GltfDocument* doc, int64_t index, const Json& ext, const std::string& where) {
  if (!ext.is_object()) return invalid_input(where + " is not a JSON object");
  LODBAKE_ASSIGN_OR_RETURN(const int64_t buffer,
                           member_index(ext, "buffer", doc->buffers.size(), "buffer", where));
  if (buffer < 0) return invalid_input(where + " has no buffer");
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t offset,
                           member_uint(ext, "byteOffset", 0, 0xFFFFFFFFFFull, where));
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t length,
                           member_uint(ext, "byteLength", 0, 0xFFFFFFFFFFull, where));
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t stride, member_uint(ext, "byteStride", 0, 256, where));
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t count, member_uint(ext, "count", 0, 0xFFFFFFFFu, where));
  const ByteSpan& source = doc->buffers[static_cast<size_t>(buffer)];
  if (offset + length > source.size) {
    return invalid_input(where + ": bytes " + str(offset) + " to " + str(offset + length) +
                         " lie outside buffer " + str(static_cast<uint64_t>(buffer)) + " of " +
                         str(source.size) + " bytes");
  }
  const auto mode_it = ext.find("mode");
  if (mode_it == ext.end() || !mode_it->is_string()) {
    return invalid_input(where + " has no 'mode' string");
  }
  const std::string mode = mode_it->get<std::string>();
  std::string filter = "NONE";
  const auto filter_it = ext.find("filter");
  if (filter_it != ext.end()) {
    if (!filter_it->is_string()) return invalid_input(where + ": 'filter' is not a string");
    filter = filter_it->get<std::string>();
  }
  if (mode == "ATTRIBUTES") {
    if (stride == 0 || stride % 4 != 0) {
      return invalid_input(where + ": ATTRIBUTES byteStride " + str(stride) +
                           " is not a multiple of 4 from 4 to 256");
    }
  } else if (mode == "TRIANGLES" || mode == "INDICES") {
    if (stride != 2 && stride != 4) {
      return invalid_input(where + ": " + mode + " byteStride " + str(stride) + " is not 2 or 4");
    }
    if (mode == "TRIANGLES" && count % 3 != 0) {
      return invalid_input(where + ": TRIANGLES count " + str(count) + " is not a multiple of 3");
    }
    if (filter != "NONE") return invalid_input(where + ": filter " + filter + " on " + mode);
  } else {
    return unsupported(where + ": mode '" + mode.substr(0, 40) + "' is not supported");
  }
  if (filter == "OCTAHEDRAL"   ? stride != 4 && stride != 8
      : filter == "QUATERNION" ? stride != 8
                               : false) {
    return invalid_input(where + ": filter " + filter + " with byteStride " + str(stride));
  }
  if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" &&
      filter != "EXPONENTIAL") {
    return unsupported(where + ": filter '" + filter.substr(0, 40) + "' is not supported");
  }
  LODBAKE_ASSIGN_OR_RETURN(const Json* views, member_array(doc->root, "bufferViews", "glTF"));
  const Json& view = (*views)[static_cast<size_t>(index)];
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t view_length,
                           member_uint(view, "byteLength", 0, 0xFFFFFFFFFFull, where));
  const uint64_t size = count * stride;
  if (view_length > size) {
    return invalid_input(where + " decodes " + str(size) + " bytes, the bufferView declares " +
                         str(view_length));
  }
  LODBAKE_RETURN_IF_ERROR(doc->budget.charge(size, where));
  Bytes out(static_cast<size_t>(size));
  const unsigned char* in = source.data + offset;
  int rc = 0;
  if (count > 0) {
    if (mode == "ATTRIBUTES") {
      rc = meshopt_decodeVertexBuffer(out.data(), count, stride, in, length);
      if (rc == 0 && filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), count, stride);
      if (rc == 0 && filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), count, stride);
      if (rc == 0 && filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), count, stride);
    } else if (mode == "TRIANGLES") {
      rc = meshopt_decodeIndexBuffer(out.data(), count, stride, in, length);
    } else {
      rc = meshopt_decodeIndexSequence(out.data(), count, stride, in, length);
    }
  }
  if (rc != 0) {
    return invalid_input(where + ": meshoptimizer could not decode the data (error " +
                         std::to_string(rc) + ")");
  }
  out.resize(static_cast<size_t>(view_length));
  doc->decoded_views[index] = std::move(out);
  return Status::ok();
}

}  // namespace

Status decode_meshopt_views(GltfDocument* doc) {
  LODBAKE_ASSIGN_OR_RETURN(const Json* views, member_array(doc->root, "bufferViews", "glTF"));
  if (views == nullptr) return Status::ok();
  for (size_t i = 0; i < views->size(); ++i) {
    const Json& view = (*views)[i];
    if (!view.is_object()) continue;  // reported where the view is used
    const auto extensions = view.find("extensions");
    if (extensions == view.end() || !extensions->is_object()) continue;
    const auto ext = extensions->find("EXT_meshopt_compression");
    if (ext == extensions->end()) continue;
    LODBAKE_RETURN_IF_ERROR(decode_view(doc, static_cast<int64_t>(i), *ext,
                                        "bufferView " + str(i) + " EXT_meshopt_compression"));
  }
  return Status::ok();
}

}  // namespace dracoio
}  // namespace lodbake
