// The part of applying a vertex split that PmRefiner (lib/simplify) and
// SplitSimulator (lib/dag) share: checking the record against the current
// mesh and finding the faces around vs that move to the new vertex vt.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

/// The face of `v` (an index into `triangles`, listed in `vertex_faces[v]`)
/// whose corner after `v` is `next`; kNoVertex when there is none.
uint32_t face_with_next(const std::vector<Triangle>& triangles,
                        const std::vector<std::vector<uint32_t>>& vertex_faces, uint32_t v,
                        uint32_t next);

/// The face of `v` whose corner before `v` is `prev`; kNoVertex when there is none.
uint32_t face_with_prev(const std::vector<Triangle>& triangles,
                        const std::vector<std::vector<uint32_t>>& vertex_faces, uint32_t v,
                        uint32_t prev);

/// Checks split number `index`, `s`, against a mesh of `vertex_count`
/// vertices (its vt is vertex_count), then appends to `moved` the faces of
/// s.vs that go to vt: counter-clockwise from (vs, vr, .) until (vs, ., vl)
/// or the boundary, then, when vl is set and was not reached, clockwise from
/// (vs, ., vl) to the boundary. On failure (an index out of range, both wings
/// missing, a repeated vertex, a wing not adjacent to vs, a fan that does not
/// end) `moved` is left as it was and the message starts "vertex split
/// INDEX: ".
Status collect_moved_faces(const std::vector<Triangle>& triangles,
                           const std::vector<std::vector<uint32_t>>& vertex_faces,
                           uint32_t vertex_count, const VertexSplit& s, size_t index,
                           std::vector<uint32_t>* moved);

}  // namespace lodbake
