// Reading and writing whole assets as Scenes (formats/scene/scene.h): glTF
// 2.0 (.gltf with its buffers and images beside it, data: URIs, .glb), OBJ
// with its .mtl, PLY, OFF, STL and Draco .drc. Every reader parses from
// memory; external resources come through a SceneResources, so tests and
// fuzzers never touch the file system unless they ask to.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "formats/scene/scene.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {

// Where a reader finds the files an asset refers to (glTF buffers and
// images, an OBJ's .mtl and textures).
struct SceneResources {
  // The folder of the file being read; empty: the asset is in memory only,
  // and any reference to an external file is refused (kUnsupported).
  std::string folder;
  // URIs resolve inside `folder`'s tree: no absolute path, no ".." out of
  // it, no scheme but data:. True lifts the confinement (--allow-outside).
  bool allow_outside = false;
  // Called with the path of every file read through these resources and its
  // bytes (null when it cannot be read), so that a caller can tell what an
  // asset depends on (lodbake-bake's content cache); may be empty.
  std::function<void(const std::string& path, const Bytes* bytes)> on_read;
};

// The file `uri` (a glTF URI, percent-encoded; or an OBJ/MTL file name) names,
// read through `resources`. Fails with kUnsupported for a scheme other than
// data: or for an absolute path or a path leaving the folder (unless
// allowed), kIo when the file cannot be read. Defined in lib/dracoio.
Result<Bytes> read_resource(const SceneResources& resources, const std::string& uri,
                            std::string* resolved_path = nullptr);

// glTF 2.0 (JSON with buffers by URI, or GLB) into a Scene: every node,
// mesh, primitive and attribute stream as the file has it (never welded),
// KHR_draco_mesh_compression and EXT_meshopt_compression decoded,
// KHR_mesh_quantization types kept, sparse accessors made dense, images read
// (a missing image is a warning in report->warnings, a missing buffer
// an error), the rest carried. A required extension lodbake cannot read fails
// with kUnsupported naming it. report->format is "gltf" or "glb".
// Defined in lib/dracoio.
Result<Scene> read_gltf_scene(const uint8_t* data, size_t size, const SceneResources& resources,
                              ImportReport* report);

// One file of a written asset: its name relative to the main file's folder.
struct SceneOutputFile {
  std::string name;
  Bytes bytes;
};

struct SceneWriteReport {
  std::vector<std::string> warnings;  // e.g. an extension that could not be kept
};

// The scene as one GLB: every node, mesh, primitive, attribute, material,
// texture, image (embedded), skin, animation and carried extension, with
// asset.generator naming lodbake. Deterministic: equal scenes give equal
// bytes. Defined in lib/dracoio.
Result<Bytes> write_scene_glb(const Scene& scene, SceneWriteReport* report);

// The scene as a .gltf named `gltf_name` with one .bin and its images beside
// it: files[0] is the .gltf; the others are named relative to it.
Result<std::vector<SceneOutputFile>> write_scene_gltf(const Scene& scene,
                                                      const std::string& gltf_name,
                                                      SceneWriteReport* report);

// Writes the scene to `path`: a .glb, or a .gltf with its .bin and images
// beside it (all files or none: staged, then renamed together). Another
// extension fails with kUsage naming the two. Defined in lib/scene.
Status write_scene_file(const std::string& path, const Scene& scene, SceneWriteReport* report);

// The same, staged with the caller's other outputs (committed by the caller).
Status stage_scene_file(StagedOutputs* staged, const std::string& path, const Scene& scene,
                        SceneWriteReport* report);

// True when `path` names a file write_scene_file() writes (.glb, .gltf).
bool is_scene_output(const std::string& path);

// Any asset or mesh file into a Scene, by content (as import_mesh() detects
// it): glTF and GLB as read_gltf_scene(); OBJ with its .mtl (each usemtl
// group a primitive, materials as glTF PBR materials, map_Kd as a texture);
// PLY with normals, colours and texture coordinates; OFF, STL and .drc as one
// mesh with one primitive. A mesh file's vertices are split only where the
// file gives a corner different attributes. Defined in lib/scene.
// Every mesh's point_of_vertex is filled (weld_mesh_points()).
Result<Scene> read_scene_file(const std::string& path, const SceneResources& resources,
                              ImportReport* report);

// The same for a file the caller has already read; references resolve from
// `path`'s folder.
Result<Scene> read_scene_bytes(const std::string& path, const Bytes& bytes,
                               const SceneResources& resources, ImportReport* report);

}  // namespace lodbake
