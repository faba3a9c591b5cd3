// Dropping vertices no triangle uses. They carry no geometry, yet they would
// widen a bounding box (and with it a quantization box), so tools that store
// a mesh drop them and say how many.
#pragma once

#include <cstdint>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

// Removes the vertices no triangle references, keeping the order of the
// rest; per-vertex attributes follow their vertices, per-corner attributes
// are untouched. Returns how many were removed.
// \pre every triangle index is < mesh.positions.size().
uint64_t remove_unreferenced_vertices(TriangleMesh& mesh);

}  // namespace lodbake
