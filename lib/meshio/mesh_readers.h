// Parsers for each mesh file format. All parse from memory (so files, tests
// and fuzzers share one path), bound every count by the bytes that remain
// before they allocate, and fail with a one-line kInvalidInput Status that
// does not name the file (the caller does). None of them checks topology:
// that is lib/check's job; they only guarantee that every index is in range
// and every face has at least 3 corners.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {

// Wavefront OBJ: v, vt, vn, f (v, v/t, v//n, v/t/n, negative = relative);
// polygons triangulated; texture coordinates and normals become per-corner
// attributes (per-vertex when their indices equal the vertex indices); other
// statements noted and ignored. UTF-16 with a byte-order mark is decoded.
// Rejects (kInvalidInput, with the line number where there is one): no
// faces, NUL bytes, non-finite numbers, index 0 or out of range, faces with
// fewer than 3 corners, faces mixing corner forms. `report` may be null.
// Details and choices: obj_reader.cpp.
Result<TriangleMesh> parse_obj(const uint8_t* data, size_t size, ImportReport* report);

// A corner index of ObjMaterialGroups' partial attributes on faces without one.
constexpr uint32_t kObjNoIndex = std::numeric_limits<uint32_t>::max();

// What an OBJ file says besides its geometry, for readers that keep
// materials (lib/scene): its material libraries and which material each
// triangle uses.
struct ObjMaterialGroups {
  // The 'mtllib' file names in file order (one statement may name several,
  // separated by blanks, as the spec says).
  std::vector<std::string> libraries;
  // The 'usemtl' names in order of first use (a name is the rest of its line).
  std::vector<std::string> materials;
  // Per triangle: index into `materials`, or -1 before any 'usemtl'.
  std::vector<int32_t> triangle_material;
  // Texture coordinates or normals that only some faces have, which the
  // mesh drops: here they stay per corner (corners parallel to the
  // triangles), with kObjNoIndex corners on the faces without, so that a
  // caller can keep them for the groups whose faces all have them.
  MeshAttribute partial_texcoords;
  MeshAttribute partial_normals;
};

// parse_obj() that also fills `groups` (not null); 'mtllib' and 'usemtl'
// are then read rather than noted as ignored.
Result<TriangleMesh> parse_obj(const uint8_t* data, size_t size, ImportReport* report,
                               ObjMaterialGroups* groups);

// OFF and its [ST][C][N][4][n]OFF variants (comments anywhere, also before
// the keyword), as text or binary ("OFF BINARY": Geomview's big-endian
// layout with face colour counts and pmp-library's little-endian one without,
// told apart by which of them describes the file exactly; report->format
// "off-binary"); N and ST give per-vertex normals and texture coordinates,
// colours are noted and skipped. Counts are checked against the file size
// before allocating; malformed input is kInvalidInput. `report` may be null.
// Details: off_reader.cpp.
Result<TriangleMesh> parse_off(const uint8_t* data, size_t size, ImportReport* report);

// PLY ascii, binary_little_endian, binary_big_endian; `vertex` x y z
// (+ nx ny nz, u v / s t / texture_u texture_v as per-vertex attributes),
// `face` vertex_indices or vertex_index lists (polygons triangulated),
// `tristrips` (-1 restarts); elements in any order; other elements and
// properties noted and skipped. Rejects (kInvalidInput, with the line or
// byte): bad magic or header, counts the body cannot hold (checked before
// allocating), truncation, out-of-range indices, faces with fewer than 3
// corners, non-finite values, a file without faces or strips; kUnsupported
// for a version other than 1.0. `report` may be null. Details: ply_reader.cpp.
Result<TriangleMesh> parse_ply(const uint8_t* data, size_t size, ImportReport* report);

// Per-vertex colours as a PLY file stores them.
struct VertexColours {
  uint32_t components = 0;  // 0 (none), 3 (red green blue) or 4 (with alpha)
  // 255 (uchar) or 65535 (ushort): the values are those integers; 1: floats
  // as stored (float or double).
  uint32_t max_value = 0;
  std::vector<float> values;  // components per vertex
};

// parse_ply() that also reads vertex red green blue [alpha] of type uchar,
// ushort, float or double into `colours` (not null; components 0 when the
// file has none).
Result<TriangleMesh> parse_ply(const uint8_t* data, size_t size, ImportReport* report,
                               VertexColours* colours);

// STL ascii or binary (a binary file is recognised by its size matching the
// 84 + 50 * count layout even when its header starts with "solid"; a file
// that matches neither is rejected, never guessed at); corners with exactly
// equal positions are welded into one vertex, numbered by first appearance
// (report->welded_vertices counts the merged corners); facet normals are
// noted and ignored; non-finite coordinates are rejected. `report` may be
// null. Details: stl_reader.cpp.
Result<TriangleMesh> parse_stl(const uint8_t* data, size_t size, ImportReport* report);

// glTF, GLB and Draco (.drc) are read by lib/dracoio/draco_io.h.

}  // namespace lodbake
