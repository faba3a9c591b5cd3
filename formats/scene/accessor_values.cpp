#include "formats/scene/accessor_values.h"

#include <algorithm>
#include <cstring>

namespace lodbake {
namespace {

template <typename T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

}  // namespace

double stored_value(const AccessorData& data, size_t i, uint32_t c) {
  const uint32_t size = component_size(data.component_type);
  const uint8_t* p = data.bytes.data() + i * data.element_size() + size_t{c} * size;
  switch (data.component_type) {
    case ComponentType::kByte:
      return load<int8_t>(p);
    case ComponentType::kUnsignedByte:
      return load<uint8_t>(p);
    case ComponentType::kShort:
      return load<int16_t>(p);
    case ComponentType::kUnsignedShort:
      return load<uint16_t>(p);
    case ComponentType::kUnsignedInt:
      return load<uint32_t>(p);
    case ComponentType::kFloat:
      return load<float>(p);
  }
  return 0.0;
}

float float_value(const AccessorData& data, size_t i, uint32_t c) {
  const double v = stored_value(data, i, c);
  if (!data.normalized) return static_cast<float>(v);
  switch (data.component_type) {
    case ComponentType::kByte:
      return static_cast<float>(std::max(v / 127.0, -1.0));
    case ComponentType::kUnsignedByte:
      return static_cast<float>(v / 255.0);
    case ComponentType::kShort:
      return static_cast<float>(std::max(v / 32767.0, -1.0));
    case ComponentType::kUnsignedShort:
      return static_cast<float>(v / 65535.0);
    default:
      return static_cast<float>(v);
  }
}

std::vector<float> float_values(const AccessorData& data) {
  const uint32_t n = data.components();
  std::vector<float> out;
  out.reserve(size_t{data.count} * n);
  for (size_t i = 0; i < data.count; ++i)
    for (uint32_t c = 0; c < n; ++c)
      out.push_back(float_value(data, i, c));
  return out;
}

std::vector<uint32_t> vertex_sequence(const ScenePrimitive& primitive) {
  if (primitive.indices) return *primitive.indices;
  std::vector<uint32_t> sequence(primitive.vertex_count());
  for (uint32_t v = 0; v < sequence.size(); ++v)
    sequence[v] = v;
  return sequence;
}

std::vector<std::array<uint32_t, 3>> primitive_triangles(const ScenePrimitive& primitive) {
  const std::vector<uint32_t> s = vertex_sequence(primitive);
  std::vector<std::array<uint32_t, 3>> triangles;
  const size_t n = s.size();
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    if (primitive.mode != PrimitiveMode::kTriangles && (a == b || b == c || a == c)) return;
    triangles.push_back({a, b, c});
  };
  switch (primitive.mode) {
    case PrimitiveMode::kTriangles:
      triangles.reserve(n / 3);
      for (size_t i = 0; i + 2 < n; i += 3)
        add(s[i], s[i + 1], s[i + 2]);
      break;
    case PrimitiveMode::kTriangleStrip:
      // glTF 2.0 §3.7.2.1: triangle i is (i, i+1+i%2, i+2-i%2).
      for (size_t i = 0; i + 2 < n; ++i)
        add(s[i], s[i + 1 + i % 2], s[i + 2 - i % 2]);
      break;
    case PrimitiveMode::kTriangleFan:
      for (size_t i = 1; i + 1 < n; ++i)
        add(s[i], s[i + 1], s[0]);
      break;
    default:
      break;
  }
  return triangles;
}

}  // namespace lodbake
