// What --validate asks of the current mesh in every replay mode, as lines:
// the index-structure counts of lib/check (exact, no geometry), shared so
// that every mode names a violation the same way.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/triangle_mesh.h"
#include "lib/check/mesh_check.h"

namespace lodbake {

/// One line per kind of problem that makes `report`'s mesh other than an
/// edge-manifold (at most two faces per edge), consistently oriented
/// triangulation without out-of-range or repeated indices or duplicate
/// triangles, each with its count; empty when there is none. Non-manifold
/// vertices and boundaries are not problems (an input may have them).
std::vector<std::string> triangulation_problems(const MeshCheckReport& report);

/// triangulation_problems() of check_triangulation(mesh): the same lines,
/// without the geometric and vertex-fan checks that do not bear on them.
std::vector<std::string> triangulation_problems(const TriangleMesh& mesh);

/// Each triangle rotated to start at its smallest corner (the cyclic order,
/// so the orientation, kept), then sorted: two triangle lists describe the
/// same oriented triangles exactly when these are equal.
std::vector<Triangle> sorted_canonical(std::vector<Triangle> triangles);

/// What --validate asks of a mesh's corner wedges (`corners`, per
/// triangle): every corner has one (kNoVertex: none) and a face's three
/// belong to one primitive of the asset's mesh. One line per kind of
/// problem, with its count and first face; empty when there is none.
std::vector<std::string> corner_wedge_problems(
    const std::vector<std::array<uint32_t, 3>>& corners, const PmWedges& wedges);

}  // namespace lodbake
