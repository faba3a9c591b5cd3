// Hand-built Scenes that use every part of the scene model (TRS and matrix
// nodes, a mesh used by two nodes, EXT_mesh_gpu_instancing, morph targets,
// KHR_mesh_quantization types, a skin and an animation with carried
// accessors, embedded and named images, a missing image), for the writer's
// unit test and for Khronos's validator on the writer's output.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "formats/scene/scene.h"

namespace lodbake {
namespace sample_scenes {

struct NamedScene {
  std::string name;
  Scene scene;
  // URIs of missing images: the validator's missing-resource error for
  // these, and only these, is expected.
  std::vector<std::string> missing_uris;
};

// "full", "large_indices" (indices past 65,535), "missing_image", "empty".
std::vector<NamedScene> all();

Scene full_scene();
Scene large_indices_scene();
Scene missing_image_scene();

// Packs `values` as an accessor's bytes (little-endian hosts).
template <typename T>
AccessorData accessor(ComponentType component, ElementType type, const std::vector<T>& values,
                      bool normalized = false) {
  AccessorData data;
  data.component_type = component;
  data.type = type;
  data.normalized = normalized;
  data.count = static_cast<uint32_t>(values.size() / component_count(type));
  data.bytes.resize(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(data.bytes.data(), values.data(), data.bytes.size());
  return data;
}

// Two small valid PNG files (1x1 and 2x2).
std::vector<uint8_t> png_1x1();
std::vector<uint8_t> png_2x2();

}  // namespace sample_scenes
}  // namespace lodbake
