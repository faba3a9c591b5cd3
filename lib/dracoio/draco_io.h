// Mesh import and export for glTF 2.0 / GLB and Draco-compressed .drc
// meshes. glTF is parsed by lodbake's own bounded reader (nlohmann-json;
// Draco 1.5.5's glTF decoder is unsafe on hostile input and ignores the
// default scene, see gltf_import.cpp); Draco decodes .drc files and
// KHR_draco_mesh_compression primitives, and its glTF encoder writes GLB.
// Draco headers stay inside lib/dracoio. No function throws; all parse from
// memory and never touch the file system.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"
#include "lib/scene/scene_io.h"

namespace lodbake {

// glTF 2.0 (.gltf with embedded buffers or data: URIs) and GLB: the scene
// read_gltf_scene() reads, flattened by flatten_scene()
// (lib/scene/scene_flatten.h): all triangle primitives of the default scene,
// node transforms applied, merged into one mesh; normals and TEXCOORD_0
// carried when present. Vertices with exactly
// equal positions are welded (report->welded_vertices), except that a file
// lodbake wrote is welded as its asset.extras.lodbake_weld says, so that it
// reads back as written; attributes that then disagree become per-corner.
// Texture v is flipped to a bottom-left origin.
// Points and lines primitives, other attributes, materials and the like are
// skipped with one note each. External (non data:) buffer URIs are read
// through `resources` (read_resource(), confined to its folder); with the
// default, memory only, they are refused (kUnsupported).
// KHR_draco_mesh_compression, EXT_meshopt_compression, KHR_mesh_quantization
// and sparse accessors are decoded as the scene reader decodes them.
// report->format is "gltf" or "glb".
Result<TriangleMesh> parse_gltf(const uint8_t* data, size_t size, ImportReport* report,
                                const SceneResources& resources = SceneResources());

// A Draco-compressed mesh (.drc): one vertex per Draco POSITION value (not
// welded further), the first NORMAL and TEX_COORD per vertex or per corner
// (texture coordinates as stored). Point clouds and bitstream versions other
// than 2.2 are refused (kUnsupported). report->format is "draco".
Result<TriangleMesh> parse_draco(const uint8_t* data, size_t size, ImportReport* report);

// GLB (binary glTF 2.0), uncompressed, with normals and texture coordinates
// when the mesh carries them; asset.generator names lodbake and its version.
// Deterministic: equal meshes give equal bytes. Per-corner attributes become
// one glTF vertex per distinct (vertex, normal, texcoord) corner, ordered by
// vertex. asset.extras.lodbake_weld tells parse_gltf how to weld: not at all
// without per-corner attributes (the mesh comes back exactly, vertices that
// share a position included), across manifold edges only with them (the
// same positions and triangles come back unless the mesh has both seams and
// split or non-manifold vertices there). Refuses meshes without triangles,
// with out-of-range indices, inconsistent attributes or non-finite positions.
Result<Bytes> write_glb(const TriangleMesh& mesh);

}  // namespace lodbake
