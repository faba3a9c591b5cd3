// A progressive mesh (Hoppe 1996) as lodbake records it: the coarsest mesh
// plus the vertex splits that refine it back to the input. Produced by the
// QEM engine (lib/simplify), stored as BASE + VSPL (formats/sections/vspl.h),
// replayed by lib/simplify/pm_replay.h. Plain data shared by formats/ and lib/.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

inline constexpr uint32_t kNoVertex = std::numeric_limits<uint32_t>::max();

// The inverse of one half-edge collapse (vt collapsed into vs). Splitting vs
// creates vertex vt = base vertex count + (index of this split): the faces
// around vs from vl to vr (counter-clockwise seen from outside) move to vt,
// and the two faces (vs, vt, vl) and (vt, vs, vr) reappear (one face when
// vr == kNoVertex, a boundary edge).
struct VertexSplit {
  uint32_t vs = kNoVertex;  // the vertex being split; exists before the split
  uint32_t vl = kNoVertex;  // the left wing vertex (always present)
  uint32_t vr = kNoVertex;  // the right wing vertex, or kNoVertex on a boundary
  Vec3f vt_position{};      // position of the new vertex vt
  Vec3f vs_position{};      // position of vs after the split (differs from its
                            // position before only with optimal placement)
  float error = 0;          // the collapse's cost when it was made

  bool operator==(const VertexSplit& o) const {
    return vs == o.vs && vl == o.vl && vr == o.vr && vt_position == o.vt_position &&
           vs_position == o.vs_position && error == o.error;
  }
};

struct ProgressiveMesh {
  TriangleMesh base;                // the coarsest mesh: vertices 0 .. base.vertex_count()-1
  std::vector<VertexSplit> splits;  // in refinement order (the reverse of the collapses)
  // input_vertex[v]: which vertex of the input mesh PM vertex v is (a
  // permutation of 0 .. base.vertex_count() + splits.size() - 1), so full
  // refinement can be compared with, and mapped back to, the input.
  std::vector<uint32_t> input_vertex;

  size_t full_vertex_count() const { return base.vertex_count() + splits.size(); }
  bool operator==(const ProgressiveMesh& o) const {
    return base == o.base && splits == o.splits && input_vertex == o.input_vertex;
  }
};

}  // namespace lodbake
