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
// creates vertex vt = base vertex count + (index of this split). Orientation,
// exactly as lib/simplify records and replays it:
// - the faces (vs, vt, vl) and (vt, vs, vr) reappear, in that vertex order
//   (counter-clockwise seen from outside); on a boundary edge only one of
//   them existed, and the other wing is kNoVertex (never both);
// - the faces around vs counter-clockwise from the edge vs-vr to the edge
//   vs-vl (i.e. starting at the face (vs, vr, x) and ending at (vs, y, vl))
//   move to vt: vs is replaced by vt in them. When vs is on a boundary the
//   walk may meet it before reaching vl: then the faces from (vs, vr, x) to
//   the boundary and those from the other end of the boundary to (vs, y, vl)
//   move. With vl == kNoVertex they are the faces from (vs, vr, x) to the
//   boundary; with vr == kNoVertex, those from the boundary to (vs, y, vl).
//   There may be none on a boundary.
struct VertexSplit {
  uint32_t vs = kNoVertex;  // the vertex being split; exists before the split
  uint32_t vl = kNoVertex;  // third vertex of the new face (vs, vt, vl), or kNoVertex
  uint32_t vr = kNoVertex;  // third vertex of the new face (vt, vs, vr), or kNoVertex
  Vec3f vt_position{};      // position of the new vertex vt
  Vec3f vs_position{};      // position of vs after the split (differs from its
                            // position before only with optimal placement)
  float error = 0;          // the collapse's error when it was made: the square root of
                            // the quadric's weighted mean squared distance, in model
                            // units (not monotone along the sequence)

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
  // Per-vertex attributes of all full_vertex_count() vertices in PM order
  // (binding kNone when the input has none): a vertex keeps its value at
  // every LoD. base.normals / base.texcoords hold the first
  // base.vertex_count() of them. Per-corner attributes cannot be recorded.
  MeshAttribute normals;
  MeshAttribute texcoords;

  size_t full_vertex_count() const { return base.vertex_count() + splits.size(); }
  bool operator==(const ProgressiveMesh& o) const {
    return base == o.base && splits == o.splits && input_vertex == o.input_vertex &&
           normals == o.normals && texcoords == o.texcoords;
  }
};

}  // namespace lodbake
