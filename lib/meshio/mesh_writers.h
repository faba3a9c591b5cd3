// Writers for the mesh formats lodbake exports (inspect --extract and later
// tools). Each returns the file's bytes; the caller writes them atomically.
// Normals and texture coordinates are written when present.
#pragma once

#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

// Every writer first checks that the mesh is consistent (indices in range,
// attribute sizes matching their binding) and fails with kInvalidInput
// otherwise. Output is deterministic: the same mesh gives the same bytes.

// OBJ with v/vt/vn, keeping per-vertex and per-corner bindings; floats
// printed with the shortest exact representation (std::to_chars) so that
// parse_obj() gives back the identical mesh.
Result<Bytes> write_obj(const TriangleMesh& mesh);
// OFF, or NOFF / STOFF / STNOFF when the mesh has per-vertex normals or
// texture coordinates; per-corner attributes have no OFF form and are left
// out (callers warn, see drops_attributes()). Floats as in write_obj().
Result<Bytes> write_off(const TriangleMesh& mesh);
// True when writing `mesh` to `path` would lose normals or texture
// coordinates (so far only .off with per-corner attributes).
bool drops_attributes(const std::string& path, const TriangleMesh& mesh);
// Binary little-endian PLY: float x y z, nx ny nz, s t; per-corner
// attributes are split into per-vertex ones by duplicating vertices (see
// corner_split.h).
Result<Bytes> write_ply(const TriangleMesh& mesh);
// GLB output is lib/dracoio/draco_io.h's write_glb().

// Picks the writer by `path`'s extension (.obj, .off, .ply, .glb).
Result<Bytes> write_mesh_for_path(const std::string& path, const TriangleMesh& mesh);

}  // namespace lodbake
