// Parsers for each mesh file format. All parse from memory (so files, tests
// and fuzzers share one path), bound every count by the bytes that remain
// before they allocate, and fail with a one-line kInvalidInput Status that
// does not name the file (the caller does). None of them checks topology:
// that is lib/check's job; they only guarantee that every index is in range
// and every face has at least 3 corners.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {

// Wavefront OBJ: v, vt, vn, f (v, v/t, v//n, v/t/n, negative = relative);
// polygons triangulated; other statements noted and ignored.
Result<TriangleMesh> parse_obj(const uint8_t* data, size_t size, ImportReport* report);

// OFF / COFF / NOFF / STOFF ASCII (comments allowed before the keyword).
Result<TriangleMesh> parse_off(const uint8_t* data, size_t size, ImportReport* report);

// PLY ascii, binary_little_endian, binary_big_endian; `vertex` x y z
// (+ nx ny nz, u v / s t / texture_u texture_v), `face` vertex_indices or
// vertex_index lists; other properties noted and skipped.
Result<TriangleMesh> parse_ply(const uint8_t* data, size_t size, ImportReport* report);

// STL ascii or binary (a binary file is recognised by its size matching the
// 84 + 50 * count layout even when its header starts with "solid"); corners
// with exactly equal positions are welded into one vertex.
Result<TriangleMesh> parse_stl(const uint8_t* data, size_t size, ImportReport* report);

// glTF, GLB and Draco (.drc) are read by lib/dracoio/draco_io.h.

}  // namespace lodbake
