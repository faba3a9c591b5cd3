// glTF 2.0 accessors as dense streams (specification sections "Accessors",
// "Sparse Accessors", "Data Alignment"). Choices:
// - Matrices of 1- and 2-byte components have each column padded to 4
//   bytes in the buffer, as the specification's alignment rule requires;
//   the padding is dropped from the dense form.
// - An accessor without bufferView is zeros (then sparse values); its size
//   is charged to the budget like any other, which is what stops a tiny
//   file from asking for 2^32 zero elements.
// - Sparse indices must be strictly increasing and below count (the
//   specification requires it; readers that accept otherwise disagree on
//   which value wins).
// - min/max are not kept: they describe the stream, and a writer
//   recomputes them from it.
#include "lib/dracoio/gltf_accessor_data.h"

#include <cstring>
#include <vector>

#include "lib/dracoio/gltf_accessors.h"

namespace lodbake {
namespace dracoio {
namespace {

std::string str(uint64_t v) {
  return std::to_string(v);
}

bool valid_component_type(uint64_t t) {
  return t == 5120 || t == 5121 || t == 5122 || t == 5123 || t == 5125 || t == 5126;
}

// Bytes one element takes in a buffer: matrix columns padded to 4 bytes.
uint64_t stored_element_size(const AccessorData& a, uint32_t* column_bytes,
                             uint32_t* padded_column) {
  const uint32_t rows = a.type == ElementType::kMat2   ? 2
                        : a.type == ElementType::kMat3 ? 3
                        : a.type == ElementType::kMat4 ? 4
                                                       : 0;
  if (rows == 0) {
    *column_bytes = *padded_column = a.element_size();
    return a.element_size();
  }
  *column_bytes = rows * component_size(a.component_type);
  *padded_column = (*column_bytes + 3) / 4 * 4;
  return uint64_t{*padded_column} * rows;
}

// Copies `count` elements from `src` (elements `stride` apart, stored with
// padded columns) into dense `dst`.
void copy_elements(const AccessorData& a, const uint8_t* src, uint64_t stride, uint64_t count,
                   uint8_t* dst) {
  uint32_t column = 0, padded = 0;
  stored_element_size(a, &column, &padded);
  const uint32_t columns = a.element_size() / column;
  for (uint64_t i = 0; i < count; ++i) {
    const uint8_t* element = src + i * stride;
    for (uint32_t c = 0; c < columns; ++c) {
      std::memcpy(dst, element + size_t{c} * padded, column);
      dst += column;
    }
  }
}

// The bytes `count` elements of `element_size` need from `offset` in `view`
// at `stride` apart; an error naming `where` when they do not fit.
Result<const uint8_t*> element_range(const ByteSpan& view, uint64_t offset, uint64_t stride,
                                     uint64_t count, uint64_t element_size,
                                     const std::string& where) {
  if (count == 0) return view.data;
  // count < 2^32, stride <= 252, offset < 2^40: no overflow.
  const uint64_t needed = offset + stride * (count - 1) + element_size;
  if (needed > view.size) {
    return invalid_input(where + ": " + str(count) + " elements from byte " + str(offset) +
                         " need " + str(needed) + " bytes, its bufferView holds " + str(view.size));
  }
  return view.data + offset;
}

Status apply_sparse(GltfDocument* doc, const Json& sparse, const std::string& where,
                    AccessorData* out) {
  const std::string sw = where + " sparse";
  if (!sparse.is_object()) return invalid_input(sw + " is not a JSON object");
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t count, member_uint(sparse, "count", 0, out->count, sw));
  if (count == 0) return invalid_input(sw + ": 'count' is missing, zero or above the accessor's");
  LODBAKE_ASSIGN_OR_RETURN(const Json* indices, member_object(sparse, "indices", sw));
  LODBAKE_ASSIGN_OR_RETURN(const Json* values, member_object(sparse, "values", sw));
  if (indices == nullptr || values == nullptr)
    return invalid_input(sw + " lacks indices or values");
  const size_t view_count = top_level_count(doc->root, "bufferViews");
  LODBAKE_ASSIGN_OR_RETURN(const int64_t index_view,
                           member_index(*indices, "bufferView", view_count, "bufferView", sw));
  LODBAKE_ASSIGN_OR_RETURN(const int64_t value_view,
                           member_index(*values, "bufferView", view_count, "bufferView", sw));
  if (index_view < 0 || value_view < 0) return invalid_input(sw + " lacks a bufferView");
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t index_type,
                           member_uint(*indices, "componentType", 0, 0xFFFF, sw));
  if (index_type != 5121 && index_type != 5123 && index_type != 5125) {
    return invalid_input(sw + ": index componentType " + str(index_type) +
                         " is not unsigned byte, short or int");
  }
  const uint32_t index_size = index_type == 5121 ? 1 : index_type == 5123 ? 2 : 4;
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t index_offset,
                           member_uint(*indices, "byteOffset", 0, 0xFFFFFFFFFFull, sw));
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t value_offset,
                           member_uint(*values, "byteOffset", 0, 0xFFFFFFFFFFull, sw));
  LODBAKE_ASSIGN_OR_RETURN(const ByteSpan iv, buffer_view_bytes(*doc, index_view, sw + " indices"));
  LODBAKE_ASSIGN_OR_RETURN(const ByteSpan vv, buffer_view_bytes(*doc, value_view, sw + " values"));
  LODBAKE_ASSIGN_OR_RETURN(const uint8_t* ip,
                           element_range(iv, index_offset, index_size, count, index_size, sw));
  uint32_t column = 0, padded = 0;
  const uint64_t stored = stored_element_size(*out, &column, &padded);
  LODBAKE_ASSIGN_OR_RETURN(const uint8_t* vp,
                           element_range(vv, value_offset, stored, count, stored, sw));
  const uint32_t element = out->element_size();
  int64_t previous = -1;
  for (uint64_t i = 0; i < count; ++i) {
    uint32_t target = 0;
    if (index_size == 1) {
      target = ip[i];
    } else if (index_size == 2) {
      uint16_t v;
      std::memcpy(&v, ip + 2 * i, 2);
      target = v;
    } else {
      std::memcpy(&target, ip + 4 * i, 4);
    }
    if (static_cast<int64_t>(target) <= previous || target >= out->count) {
      return invalid_input(sw + ": index " + str(target) + " at position " + str(i) +
                           " is not increasing or not below " + str(out->count));
    }
    previous = target;
    copy_elements(*out, vp + i * stored, stored, 1, out->bytes.data() + uint64_t{target} * element);
  }
  return Status::ok();
}

}  // namespace

bool parse_element_type(const std::string& name, ElementType* out) {
  static constexpr const char* kNames[] = {"SCALAR", "VEC2", "VEC3", "VEC4",
                                           "MAT2",   "MAT3", "MAT4"};
  for (int i = 0; i < 7; ++i) {
    if (name == kNames[i]) {
      *out = static_cast<ElementType>(i);
      return true;
    }
  }
  return false;
}

Result<AccessorData> accessor_declaration(const GltfDocument& doc, int64_t index) {
  const std::string where = "accessor " + str(static_cast<uint64_t>(index));
  LODBAKE_ASSIGN_OR_RETURN(const Json* object, accessor_object(doc, index, where));
  const Json& a = *object;
  AccessorData out;
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t component_type,
                           member_uint(a, "componentType", 0, 0xFFFF, where));
  if (!valid_component_type(component_type)) {
    return invalid_input(where + ": unsupported componentType " + str(component_type));
  }
  out.component_type = static_cast<ComponentType>(component_type);
  const auto type = a.find("type");
  if (type == a.end() || !type->is_string() ||
      !parse_element_type(type->get_ref<const std::string&>(), &out.type)) {
    return invalid_input(where + ": 'type' is missing or not a glTF accessor type");
  }
  const auto normalized = a.find("normalized");
  if (normalized != a.end()) {
    if (!normalized->is_boolean()) return invalid_input(where + ": 'normalized' is not a boolean");
    out.normalized = normalized->get<bool>();
    if (out.normalized && (component_type == 5125 || component_type == 5126)) {
      return invalid_input(where + ": normalized is not allowed for componentType " +
                           str(component_type));
    }
  }
  LODBAKE_ASSIGN_OR_RETURN(const uint64_t count, member_uint(a, "count", 0, 0xFFFFFFFFull, where));
  if (count == 0) return invalid_input(where + ": 'count' is missing or zero");
  out.count = static_cast<uint32_t>(count);
  const auto name = a.find("name");
  if (name != a.end() && name->is_string()) out.name = name->get<std::string>();
  return out;
}

Result<AccessorData> read_accessor_data(GltfDocument* doc, int64_t index) {
  const std::string where = "accessor " + str(static_cast<uint64_t>(index));
  LODBAKE_ASSIGN_OR_RETURN(AccessorData out, accessor_declaration(*doc, index));
  const Json& a = doc->root["accessors"][static_cast<size_t>(index)];
  const uint64_t total = uint64_t{out.count} * out.element_size();
  LODBAKE_RETURN_IF_ERROR(doc->budget.charge(total, where));
  uint32_t column = 0, padded = 0;
  const uint64_t stored = stored_element_size(out, &column, &padded);
  LODBAKE_ASSIGN_OR_RETURN(const int64_t view_index,
                           member_index(a, "bufferView", top_level_count(doc->root, "bufferViews"),
                                        "bufferView", where));
  if (view_index >= 0) {
    LODBAKE_ASSIGN_OR_RETURN(const ByteSpan view, buffer_view_bytes(*doc, view_index, where));
    const Json& v = doc->root["bufferViews"][static_cast<size_t>(view_index)];
    LODBAKE_ASSIGN_OR_RETURN(const uint64_t byte_stride,
                             member_uint(v, "byteStride", 0, 252, where));
    const uint64_t stride = byte_stride == 0 ? stored : byte_stride;
    LODBAKE_ASSIGN_OR_RETURN(const uint64_t offset,
                             member_uint(a, "byteOffset", 0, 0xFFFFFFFFFFull, where));
    LODBAKE_ASSIGN_OR_RETURN(const uint8_t* first,
                             element_range(view, offset, stride, out.count, stored, where));
    out.bytes.resize(static_cast<size_t>(total));
    copy_elements(out, first, stride, out.count, out.bytes.data());
  } else {
    out.bytes.assign(static_cast<size_t>(total), 0);
  }
  const auto sparse = a.find("sparse");
  if (sparse != a.end()) LODBAKE_RETURN_IF_ERROR(apply_sparse(doc, *sparse, where, &out));
  return out;
}

}  // namespace dracoio
}  // namespace lodbake
