// The buffer layout of written glTF scenes (gltf_buffer_writer.h).
#include "lib/dracoio/gltf_buffer_writer.h"

#include "formats/scene/accessor_values.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace lodbake {
namespace dracoio {
namespace {

constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

// GLB stores lengths as 32-bit numbers; keep the whole buffer below that.
constexpr uint64_t kMaxBufferBytes = (uint64_t{1} << 32) - 64;

const char* type_name(ElementType t) {
  static const char* const kNames[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
  return kNames[static_cast<int>(t)];
}

bool is_matrix(ElementType t) {
  return t == ElementType::kMat2 || t == ElementType::kMat3 || t == ElementType::kMat4;
}

uint32_t round_up4(uint64_t n) {
  return static_cast<uint32_t>((n + 3) & ~uint64_t{3});
}

// Per-component min and max; false when a float component is not finite
// (JSON cannot hold it, and such data is not valid glTF anyway).
bool bounds_of(const AccessorData& data, nlohmann::json* min, nlohmann::json* max) {
  const uint32_t n = data.components();
  std::vector<double> lo(n, std::numeric_limits<double>::infinity());
  std::vector<double> hi(n, -std::numeric_limits<double>::infinity());
  for (uint32_t e = 0; e < data.count; ++e) {
    for (uint32_t c = 0; c < n; ++c) {
      const double v = stored_value(data, e, c);
      if (!std::isfinite(v)) return false;
      lo[c] = std::min(lo[c], v);
      hi[c] = std::max(hi[c], v);
    }
  }
  *min = nlohmann::json::array();
  *max = nlohmann::json::array();
  for (uint32_t c = 0; c < n; ++c) {
    if (data.component_type == ComponentType::kFloat) {
      min->push_back(lo[c]);
      max->push_back(hi[c]);
    } else {
      min->push_back(static_cast<int64_t>(lo[c]));
      max->push_back(static_cast<int64_t>(hi[c]));
    }
  }
  return true;
}

}  // namespace

uint32_t GltfBufferWriter::begin_view() {
  bin_.resize(round_up4(bin_.size()), 0);
  return static_cast<uint32_t>(views_.size());
}

void GltfBufferWriter::end_view(size_t start, uint32_t stride, int target) {
  nlohmann::json view = {{"buffer", 0}, {"byteLength", bin_.size() - start}};
  if (start != 0) view["byteOffset"] = start;
  if (stride != 0) view["byteStride"] = stride;
  if (target != 0) view["target"] = target;
  views_.push_back(std::move(view));
  bin_.resize(round_up4(bin_.size()), 0);
}

Result<uint32_t> GltfBufferWriter::add_accessor(const AccessorData& data, Use use, bool bounds,
                                                const std::string& where) {
  if (data.count == 0)
    return invalid_input(where + " is empty (glTF accessors hold at least one element)");
  if (data.bytes.size() != uint64_t{data.count} * data.element_size()) {
    return invalid_input(where + " holds " + std::to_string(data.bytes.size()) + " bytes for " +
                         std::to_string(data.count) + " elements of " +
                         std::to_string(data.element_size()) + " bytes");
  }
  const uint32_t size = component_size(data.component_type);
  // A matrix is columns of `rows` components, each column padded to 4
  // bytes; anything else is one column of all its components.
  uint32_t columns = 1;
  uint32_t rows = data.components();
  if (is_matrix(data.type)) {
    rows = data.type == ElementType::kMat2 ? 2 : data.type == ElementType::kMat3 ? 3 : 4;
    columns = rows;
  }
  const uint32_t column_bytes = rows * size;
  const uint32_t column_stride = is_matrix(data.type) ? round_up4(column_bytes) : column_bytes;
  const uint32_t element_bytes = columns * column_stride;
  const uint32_t stride = use == Use::kVertices ? round_up4(element_bytes) : element_bytes;
  if (bin_.size() + uint64_t{stride} * data.count + 8 > kMaxBufferBytes)
    return unsupported("the scene's binary data exceeds glTF's 4 GiB buffer limit");

  const uint32_t view = begin_view();
  const size_t start = bin_.size();
  bin_.resize(start + size_t{stride} * data.count, 0);
  const uint8_t* src = data.bytes.data();
  for (uint32_t e = 0; e < data.count; ++e) {
    uint8_t* dst = bin_.data() + start + size_t{e} * stride;
    for (uint32_t c = 0; c < columns; ++c, src += column_bytes)
      std::memcpy(dst + size_t{c} * column_stride, src, column_bytes);
  }
  end_view(start, use == Use::kVertices ? stride : 0, use == Use::kVertices ? kArrayBuffer : 0);

  nlohmann::json accessor = {{"bufferView", view},
                             {"componentType", static_cast<int>(data.component_type)},
                             {"count", data.count},
                             {"type", type_name(data.type)}};
  if (data.normalized) accessor["normalized"] = true;
  if (!data.name.empty()) accessor["name"] = data.name;
  nlohmann::json min, max;
  if (bounds && bounds_of(data, &min, &max)) {
    accessor["min"] = std::move(min);
    accessor["max"] = std::move(max);
  }
  accessors_.push_back(std::move(accessor));
  return static_cast<uint32_t>(accessors_.size() - 1);
}

Result<uint32_t> GltfBufferWriter::add_indices(const std::vector<uint32_t>& indices,
                                               uint32_t vertex_count, const std::string& where) {
  if (indices.empty())
    return invalid_input(where + " is empty (glTF accessors hold at least one element)");
  uint32_t highest = 0;
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertex_count) {
      return invalid_input(where + ": index " + std::to_string(i) + " is " +
                           std::to_string(indices[i]) + ", out of range (" +
                           std::to_string(vertex_count) + " vertices)");
    }
    highest = std::max(highest, indices[i]);
  }
  if (indices.size() > std::numeric_limits<uint32_t>::max() ||
      bin_.size() + indices.size() * 4 + 8 > kMaxBufferBytes) {
    return unsupported("the scene's binary data exceeds glTF's 4 GiB buffer limit");
  }
  // The all-ones value of each type is primitive restart, which glTF forbids
  // in an index buffer.
  ComponentType type = ComponentType::kUnsignedInt;
  if (highest < 0xff) {
    type = ComponentType::kUnsignedByte;
  } else if (highest < 0xffff) {
    type = ComponentType::kUnsignedShort;
  }
  const uint32_t size = component_size(type);
  const uint32_t view = begin_view();
  const size_t start = bin_.size();
  bin_.resize(start + indices.size() * size);
  for (size_t i = 0; i < indices.size(); ++i) {
    for (uint32_t b = 0; b < size; ++b)
      bin_[start + i * size + b] = static_cast<uint8_t>(indices[i] >> (8 * b));
  }
  end_view(start, 0, kElementArrayBuffer);
  accessors_.push_back({{"bufferView", view},
                        {"componentType", static_cast<int>(type)},
                        {"count", indices.size()},
                        {"type", "SCALAR"}});
  return static_cast<uint32_t>(accessors_.size() - 1);
}

Result<uint32_t> GltfBufferWriter::add_view(const std::vector<uint8_t>& bytes,
                                            const std::string& where) {
  if (bytes.empty()) return invalid_input(where + " has no bytes");
  if (bin_.size() + bytes.size() + 8 > kMaxBufferBytes)
    return unsupported("the scene's binary data exceeds glTF's 4 GiB buffer limit");
  const uint32_t view = begin_view();
  const size_t start = bin_.size();
  bin_.insert(bin_.end(), bytes.begin(), bytes.end());
  end_view(start, 0, 0);
  return Result<uint32_t>(view);
}

}  // namespace dracoio
}  // namespace lodbake
