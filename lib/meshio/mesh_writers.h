// Writers for the mesh formats lodbake exports (inspect --extract and later
// tools). Each returns the file's bytes; the caller writes them atomically.
// Normals and texture coordinates are written when present.
#pragma once

#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

// OBJ with v/vt/vn; floats printed with the shortest exact representation
// (std::to_chars) so that reading the file back gives identical floats.
Result<Bytes> write_obj(const TriangleMesh& mesh);
// OFF (positions and triangles only: OFF has no standard corner attributes;
// callers warn when the mesh carries some, see drops_attributes()).
Result<Bytes> write_off(const TriangleMesh& mesh);
// True when writing `mesh` to `path` would lose normals or texture coordinates.
bool drops_attributes(const std::string& path, const TriangleMesh& mesh);
// Binary little-endian PLY with per-vertex normals and texture coordinates
// (per-corner attributes are split into per-vertex ones by duplicating vertices).
Result<Bytes> write_ply(const TriangleMesh& mesh);
// GLB output is lib/dracoio/draco_io.h's write_glb().

// Picks the writer by `path`'s extension (.obj, .off, .ply, .glb).
Result<Bytes> write_mesh_for_path(const std::string& path, const TriangleMesh& mesh);

}  // namespace lodbake
