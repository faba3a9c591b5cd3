// glTF 2.0 accessors and buffer views (specification sections "Accessors",
// "Buffers and Buffer Views", "Accessor Data Types"). Choices:
// - Sparse accessors and accessors without a buffer view (implicitly zero)
//   are refused as unsupported: they are rare in meshes, and a zero accessor
//   could ask for any count without holding any bytes.
// - Alignment rules are not enforced: elements are copied with memcpy.
// - A byteStride smaller than the element is accepted (elements overlap);
//   only the bounds matter for safety.
#include "lib/dracoio/gltf_accessors.h"

#include <algorithm>
#include <cstring>

namespace lodbake {
namespace dracoio {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

struct Accessor {
  uint64_t count = 0;
  uint32_t components = 0;
  int component_type = 0;
  uint32_t component_size = 0;
  bool normalized = false;
  const uint8_t* data = nullptr;  // first element
  uint64_t stride = 0;
};

uint32_t components_of(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  if (type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

uint32_t component_size_of(int component_type) {
  switch (component_type) {
    case 5120:  // BYTE
    case 5121:  // UNSIGNED_BYTE
      return 1;
    case 5122:  // SHORT
    case 5123:  // UNSIGNED_SHORT
      return 2;
    case 5125:  // UNSIGNED_INT
    case 5126:  // FLOAT
      return 4;
    default:
      return 0;
  }
}

std::string accessor_name(int64_t index) {
  return "accessor " + str(static_cast<uint64_t>(index));
}

Result<Accessor> resolve(const GltfDocument& doc, int64_t index) {
  const std::string where = accessor_name(index);
  LODBAKE_ASSIGN_OR_RETURN(const Json* object, accessor_object(doc, index, where));
  const Json& a = *object;
  Accessor out;
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t component_type,
                           member_uint(a, "componentType", 0, 0xFFFF, where));
  out.component_type = static_cast<int>(component_type);
  out.component_size = component_size_of(out.component_type);
  if (out.component_size == 0) {
    return invalid_input(where + ": unsupported componentType " + str(component_type));
  }
  const auto type = a.find("type");
  if (type == a.end() || !type->is_string() ||
      (out.components = components_of(type->get_ref<const std::string&>())) == 0) {
    return invalid_input(where + ": 'type' is missing or not a glTF accessor type");
  }
  const auto normalized = a.find("normalized");
  out.normalized = normalized != a.end() && normalized->is_boolean() && normalized->get<bool>();
  LODBAKE_ASSIGN_OR_RETURN(out.count, member_uint(a, "count", 0, 0xFFFFFFFFull, where));
  if (out.count == 0) return invalid_input(where + ": 'count' is missing or zero");
  if (a.contains("sparse")) return unsupported(where + ": sparse accessors are not supported");
  LODBAKE_ASSIGN_OR_RETURN(const Json* views, member_array(doc.root, "bufferViews", "glTF"));
  LODBAKE_ASSIGN_OR_RETURN(
      const int64_t view_index,
      member_index(a, "bufferView", views == nullptr ? 0 : views->size(), "bufferView", where));
  if (view_index < 0) {
    return unsupported(where + " has no bufferView (implicit zeros are not supported)");
  }
  LODBAKE_ASSIGN_OR_RETURN(const ByteSpan view, buffer_view_bytes(doc, view_index, where));
  const Json& v = (*views)[static_cast<size_t>(view_index)];
  const uint64_t element_size = uint64_t{out.components} * out.component_size;
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t byte_stride, member_uint(v, "byteStride", 0, 252, where));
  out.stride = byte_stride == 0 ? element_size : byte_stride;
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t offset,
                           member_uint(a, "byteOffset", 0, 0xFFFFFFFFFFull, where));
  // count < 2^32 and stride <= 252, so none of this overflows 64 bits.
  const uint64_t needed = offset + out.stride * (out.count - 1) + element_size;
  if (needed > view.size) {
    return invalid_input(where + ": " + str(out.count) + " elements from byte " + str(offset) +
                         " need " + str(needed) + " bytes, its bufferView holds " + str(view.size));
  }
  out.data = view.data + offset;
  return out;
}

template <typename T>
T load(const uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

float component_as_float(const Accessor& a, const uint8_t* p) {
  switch (a.component_type) {
    case 5120: {
      const float v = load<int8_t>(p);
      return a.normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case 5121: {
      const float v = load<uint8_t>(p);
      return a.normalized ? v / 255.0f : v;
    }
    case 5122: {
      const float v = load<int16_t>(p);
      return a.normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case 5123: {
      const float v = load<uint16_t>(p);
      return a.normalized ? v / 65535.0f : v;
    }
    case 5125:
      return static_cast<float>(load<uint32_t>(p));
    default:
      return load<float>(p);
  }
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

Result<std::vector<float>> read_float_accessor(const GltfDocument& doc, int64_t index,
                                               uint32_t components) {
  LODBAKE_ASSIGN_OR_RETURN(const Accessor a, resolve(doc, index));
  if (a.components != components) {
    return invalid_input(accessor_name(index) + " has " + str(a.components) +
                         " components per element, " + str(components) + " expected");
  }
  if (a.component_type == 5125 && a.normalized) {
    return invalid_input(accessor_name(index) + ": normalized unsigned int is not allowed");
  }
  std::vector<float> values(a.count * components);
  const uint8_t* element = a.data;
  size_t out = 0;
  for (uint64_t i = 0; i < a.count; ++i, element += a.stride) {
    for (uint32_t c = 0; c < components; ++c) {
      values[out++] = component_as_float(a, element + size_t{c} * a.component_size);
    }
  }
  return values;
}

Result<std::vector<uint32_t>> read_index_accessor(const GltfDocument& doc, int64_t index) {
  LODBAKE_ASSIGN_OR_RETURN(const Accessor a, resolve(doc, index));
  if (a.components != 1 || a.component_type == 5120 || a.component_type == 5122 ||
      a.component_type == 5126) {
    return invalid_input(accessor_name(index) +
                         " is not a SCALAR unsigned byte, short or int index accessor");
  }
  std::vector<uint32_t> indices(a.count);
  const uint8_t* element = a.data;
  for (uint64_t i = 0; i < a.count; ++i, element += a.stride) {
    switch (a.component_type) {
      case 5121:
        indices[i] = load<uint8_t>(element);
        break;
      case 5123:
        indices[i] = load<uint16_t>(element);
        break;
      default:
        indices[i] = load<uint32_t>(element);
        break;
    }
  }
  return indices;
}

}  // namespace dracoio
}  // namespace lodbake
