// Internal to lib/dracoio: conversions between draco::Mesh and lodbake's
// meshes. Includes Draco headers, so only this module's sources (and its
// unit test) include it.
#pragma once

#include <memory>

#include "draco/mesh/mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {
namespace dracoio {

// A decoded .drc mesh as a TriangleMesh: one vertex per POSITION value (the
// vertices Draco stores, not welded further), triangles through the point ->
// position mapping. The first NORMAL and TEX_COORD attributes are per vertex
// when each position value maps to a single attribute value, per corner
// otherwise. Other attributes and metadata are listed in `report->notes`.
// Every face and mapping index is range-checked.
Result<TriangleMesh> mesh_from_draco(const draco::Mesh& mesh, ImportReport* report);

// A TriangleMesh as a draco::Mesh for the glTF encoder. Per-vertex
// attributes map one to one; per-corner ones make one Draco point per
// distinct (vertex, normal, texcoord) combination, sorted by vertex so that
// point order follows vertex order. The mesh must be valid (see
// check_mesh_for_export).
Result<std::unique_ptr<draco::Mesh>> to_draco_mesh(const TriangleMesh& mesh);

// The attribute holds numbers (DT_BOOL is refused: Draco loads it as a C++
// bool), and every point's mapping leads to a stored value.
Status check_mapping(const draco::PointAttribute& att, uint32_t num_points);

// Every face corner names a point below num_points().
Status check_faces(const draco::Mesh& mesh);

// Index ranges and attribute sizes of a TriangleMesh about to be exported.
Status check_mesh_for_export(const TriangleMesh& mesh);

}  // namespace dracoio
}  // namespace lodbake
