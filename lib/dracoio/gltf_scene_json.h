// Internal to lib/dracoio: a Scene as glTF 2.0 JSON plus the bytes of its one
// buffer, shared by the GLB and .gltf writers (gltf_scene_export.cpp), which
// differ only in where the buffer and the images go.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/scene/scene.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/scene/scene_io.h"

namespace lodbake {
namespace dracoio {

struct SceneGltf {
  // Every top-level member but "buffers", which the caller adds (GLB: no
  // uri; .gltf: the .bin's) when `bin` is not empty.
  nlohmann::json root;
  Bytes bin;  // length a multiple of 4; empty when the scene has no data
};

// The scene as glTF. `image_uris` null: every image with bytes is embedded
// in the buffer through a bufferView with its mimeType (GLB); otherwise one
// percent-encoded URI per image (.gltf). A missing image keeps its input URI
// either way, with a warning. Carried accessors (Scene::accessors) are
// written first, as accessors 0..n-1, so the carried JSON's references into
// them (skins, animation samplers, EXT_mesh_gpu_instancing) keep their
// values; they are checked to be in range. KHR_mesh_quantization is declared
// used and required when a stream's type needs it; extensions whose data
// lodbake writes decoded (compression) are dropped with a warning; every
// extension the JSON uses is declared. Fails with kInvalidInput, naming the
// object, when the scene cannot be valid glTF (an empty stream, an index out
// of range, a mesh without primitives, a dangling accessor reference).
Result<SceneGltf> build_scene_gltf(const Scene& scene, const std::vector<std::string>* image_uris,
                                   SceneWriteReport* report);

}  // namespace dracoio
}  // namespace lodbake
