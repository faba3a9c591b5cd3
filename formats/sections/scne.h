// The SCNE section: the whole asset a container was baked from (a glTF 2.0
// scene: nodes, meshes, primitives, materials, textures with their images,
// skins, animations, extensions), so that one .lbk per asset gives the
// asset back, and the map from each scene mesh to the group whose BASE is
// that mesh's welded topology. Byte layout: docs/format.md "SCNE".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// One scene mesh with triangles: the group holding its BASE (and whatever
/// the tools built on it), and how BASE's triangles divide among the mesh's
/// primitives (primitive p owns the next triangles[p] triangles, in
/// primitive order; points and lines primitives own none).
struct SceneMeshGroup {
  uint32_t mesh = 0;
  uint32_t group = 0;
  std::vector<uint64_t> triangles;

  bool operator==(const SceneMeshGroup& o) const {
    return mesh == o.mesh && group == o.group && triangles == o.triangles;
  }
};

struct SceneSection {
  std::vector<SceneMeshGroup> meshes;  ///< increasing mesh, each group at most once
  /// The file name each image had beside the input's .gltf ("" for an
  /// embedded one), which the GLB cannot say: an extracted .gltf uses them.
  std::vector<std::string> image_uris;
  Bytes glb;  ///< the asset as a GLB 2.0 document

  bool operator==(const SceneSection& o) const {
    return meshes == o.meshes && image_uris == o.image_uris && glb == o.glb;
  }
};

/// Largest map a reader accepts (the JSON before the GLB).
inline constexpr size_t kMaxSceneMapBytes = size_t{1} << 24;

/// The SCNE payload. Deterministic.
/// \return kInvalidInput when the map breaks decode_scne()'s rules.
Result<Bytes> encode_scne(const SceneSection& section);

/// Parses a SCNE payload: the map (meshes increasing, groups unique) and a
/// GLB whose 12-byte header says magic "glTF", version 2 and the length that
/// remains. The GLB's contents are read by lib/scene, not here.
/// \return LBK-E023 ("section SCNE: ...") when malformed.
Result<SceneSection> decode_scne(const uint8_t* data, size_t size);

}  // namespace lodbake
