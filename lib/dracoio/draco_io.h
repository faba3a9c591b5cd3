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
// mesh; normals and TEXCOORD_0 carried when present. Vertices with exactly
// equal positions are welded (report->welded_vertices); attributes that then
// disagree become per-corner. Texture v is flipped to a bottom-left origin.
// Points and lines primitives, other attributes, materials and the like are
// skipped with one note each. External (non data:) buffer URIs are refused.
Result<TriangleMesh> parse_gltf(const uint8_t* data, size_t size, ImportReport* report);

// A Draco-compressed mesh (.drc): one vertex per Draco POSITION value (not
// welded further), the first NORMAL and TEX_COORD per vertex or per corner.
// Point clouds are refused (kUnsupported).
Result<TriangleMesh> parse_draco(const uint8_t* data, size_t size, ImportReport* report);

// GLB (binary glTF 2.0), uncompressed, with normals and texture coordinates
// when the mesh carries them. Deterministic: equal meshes give equal bytes.
// Per-corner attributes become one glTF vertex per distinct (vertex, normal,
// texcoord) corner, ordered by vertex, so parse_gltf (which welds equal
// positions) returns the same positions and triangles in the same order when
// no two vertices share a position. Refuses meshes without triangles, with
// out-of-range indices, inconsistent attributes or non-finite positions.
Result<Bytes> write_glb(const TriangleMesh& mesh);

}  // namespace lodbake
