// The wedges of a progressive mesh (Hoppe 1996): which attribute set each
// corner of each level uses. Beside a ProgressiveMesh (positions and
// connectivity), a wedge is a vertex of one primitive of a scene mesh (its
// attribute values live in the scene), and the splits say which wedges the
// corners they create or move take, so that every level is a textured mesh
// and full refinement gives back every corner's wedge. Produced by
// lib/simplify/wedge_pm.h, replayed by lib/simplify/wedge_replay.h, stored
// as the WEDG section (formats/sections/wedg.h). Plain data.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace lodbake {

struct PmWedges {
  // Per wedge: the primitive of the scene mesh and the vertex of that
  // primitive whose attribute values it has.
  std::vector<uint32_t> wedge_primitive;
  std::vector<uint32_t> wedge_vertex;
  // Per wedge, the PM vertex it belongs to: a corner of a coarser level at
  // another vertex uses the wedge's values at that vertex's position (a
  // seam moved by a permissive collapse).
  std::vector<uint32_t> wedge_home;
  // Per base triangle, its corners' wedges.
  std::vector<std::array<uint32_t, 3>> base;
  // Per split, the corners of the faces it adds, (vs, vt, vl) then
  // (vt, vs, vr) as VertexSplit orders them; a missing wing's three are
  // kNoVertex.
  std::vector<std::array<uint32_t, 6>> added;
  // Per split, the wedges the faces it moves from vs to vt take at vt, in
  // the order the split's walk meets them (PmRefiner::last_moved_faces):
  // moved[moved_offset[i] .. moved_offset[i + 1]).
  std::vector<uint32_t> moved_offset;  // splits + 1 entries, from 0
  std::vector<uint32_t> moved;

  size_t wedge_count() const { return wedge_primitive.size(); }
  bool operator==(const PmWedges& o) const {
    return wedge_primitive == o.wedge_primitive && wedge_vertex == o.wedge_vertex &&
           wedge_home == o.wedge_home && base == o.base && added == o.added &&
           moved_offset == o.moved_offset && moved == o.moved;
  }
};

}  // namespace lodbake
