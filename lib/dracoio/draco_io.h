// Mesh import and export through Draco: glTF 2.0 / GLB (Draco's glTF
// decoder and encoder, built on tinygltf) and Draco-compressed .drc meshes.
// The only translation unit of the import path that includes Draco headers.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {

// glTF 2.0 (.gltf with embedded buffers or data: URIs) and GLB: all triangle
// primitives of the default scene, node transforms applied, merged into one
// mesh; normals and TEXCOORD_0 carried when present.
Result<TriangleMesh> parse_gltf(const uint8_t* data, size_t size, ImportReport* report);

// A Draco-compressed mesh (.drc).
Result<TriangleMesh> parse_draco(const uint8_t* data, size_t size, ImportReport* report);

// GLB (binary glTF 2.0), uncompressed, with normals and texture coordinates
// when the mesh carries them.
Result<Bytes> write_glb(const TriangleMesh& mesh);

}  // namespace lodbake
