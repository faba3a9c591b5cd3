#include "lib/simplify/pm_wedge_assignment.h"

#include <algorithm>
#include <new>
#include <string>
#include <utility>

#include "formats/mesh/canonical_triangles.h"
#include "lib/simplify/pm_replay.h"

namespace lodbake {
namespace {

// A triangle's canonical rotation, how far it is rotated, and its index:
// sorting these pairs the full mesh's face slots with the input's faces.
struct Keyed {
  Triangle key;
  int rotation;
  uint32_t index;
  bool operator<(const Keyed& o) const { return key != o.key ? key < o.key : index < o.index; }
};

Keyed keyed(const Triangle& t, uint32_t index) {
  const Triangle key = canonical_triangle(t);
  int rotation = 0;
  while (rotation < 2 && t[rotation] != key[0])
    ++rotation;
  return {key, rotation, index};
}

int corner_of(const Triangle& t, uint32_t v) {
  return t[0] == v ? 0 : t[1] == v ? 1 : 2;
}

// The corner wedges of every face slot of the fully refined mesh, from the
// input triangle each slot is.
Result<std::vector<std::array<uint32_t, 3>>> full_corners(
    const ProgressiveMesh& pm, const TriangleMesh& full, const std::vector<Triangle>& triangles,
    const std::vector<std::array<uint32_t, 3>>& corner_wedge) {
  if (full.triangles.size() != triangles.size())
    return runtime_error("the progressive mesh refines to " +
                         std::to_string(full.triangles.size()) + " triangles, the mesh has " +
                         std::to_string(triangles.size()));
  std::vector<Keyed> slots, inputs;
  slots.reserve(triangles.size());
  inputs.reserve(triangles.size());
  for (uint32_t f = 0; f < full.triangles.size(); ++f) {
    const Triangle& t = full.triangles[f];
    slots.push_back(
        keyed({pm.input_vertex[t[0]], pm.input_vertex[t[1]], pm.input_vertex[t[2]]}, f));
  }
  for (uint32_t f = 0; f < triangles.size(); ++f)
    inputs.push_back(keyed(triangles[f], f));
  std::sort(slots.begin(), slots.end());
  std::sort(inputs.begin(), inputs.end());
  std::vector<std::array<uint32_t, 3>> corners(triangles.size());
  for (size_t i = 0; i < slots.size(); ++i) {
    if (slots[i].key != inputs[i].key)
      return runtime_error("the progressive mesh's full mesh is not the mesh: face slot " +
                           std::to_string(slots[i].index) + " has no triangle of its own");
    // Slot corner k is the canonical corner (k - slot rotation), which is
    // input corner (k - slot rotation + input rotation).
    for (int k = 0; k < 3; ++k)
      corners[slots[i].index][k] =
          corner_wedge[inputs[i].index][(k - slots[i].rotation + inputs[i].rotation + 3) % 3];
  }
  return corners;
}

}  // namespace

Result<PmWedges> assign_pm_wedges(const ProgressiveMesh& pm, const std::vector<Triangle>& triangles,
                                  const std::vector<std::array<uint32_t, 3>>& corner_wedge,
                                  const std::vector<uint32_t>& wedge_point) {
  try {
    if (corner_wedge.size() != triangles.size())
      return runtime_error("corner wedges for " + std::to_string(corner_wedge.size()) +
                           " triangles, the mesh has " + std::to_string(triangles.size()));
    LODBAKE_ASSIGN_OR_RETURN(PmRefiner refiner, PmRefiner::create(pm));
    LODBAKE_RETURN_IF_ERROR(refiner.refine_to(pm.full_vertex_count()));
    const size_t points = pm.full_vertex_count();
    for (const std::array<uint32_t, 3>& c : corner_wedge)
      for (uint32_t w : c)
        if (w >= wedge_point.size() || wedge_point[w] >= points)
          return runtime_error("wedge " + std::to_string(w) + " is out of range");
    using Corners = std::vector<std::array<uint32_t, 3>>;
    LODBAKE_ASSIGN_OR_RETURN(Corners corners,
                             full_corners(pm, refiner.mesh(), triangles, corner_wedge));

    PmWedges out;
    std::vector<uint32_t> pm_vertex(points, kNoVertex);
    for (uint32_t v = 0; v < points; ++v)
      pm_vertex[pm.input_vertex[v]] = v;
    for (uint32_t point : wedge_point)
      out.wedge_home.push_back(pm_vertex[point]);

    // From the full mesh down: each split's records are read off the mesh
    // it made, then the split is undone.
    const size_t splits = pm.splits.size();
    out.added.resize(splits);
    std::vector<std::vector<uint32_t>> moved(splits);
    const std::vector<Triangle>& faces = refiner.mesh().triangles;
    for (size_t i = splits; i-- > 0;) {
      const VertexSplit& s = pm.splits[i];
      const uint32_t vs = s.vs;
      const uint32_t vt = static_cast<uint32_t>(pm.base.positions.size() + i);
      // The added faces are the last slots: (vs, vt, vl), then (vt, vs, vr).
      const uint32_t added = (s.vl != kNoVertex ? 1 : 0) + (s.vr != kNoVertex ? 1 : 0);
      uint32_t slot = static_cast<uint32_t>(faces.size()) - added;
      std::array<uint32_t, 6>& record = out.added[i];
      record.fill(kNoVertex);
      // Across the collapsed edge, vt's wedge in a wing face pairs with vs's.
      std::vector<std::pair<uint32_t, uint32_t>> partner;
      for (int wing = 0; wing < 2; ++wing) {
        if ((wing == 0 ? s.vl : s.vr) == kNoVertex) continue;
        for (int k = 0; k < 3; ++k)
          record[3 * wing + k] = corners[slot][k];
        partner.emplace_back(corners[slot][corner_of(faces[slot], vt)],
                             corners[slot][corner_of(faces[slot], vs)]);
        ++slot;
      }
      const auto [begin, end] = refiner.last_moved_faces();
      for (const uint32_t* f = begin; f != end; ++f) {
        uint32_t& wedge = corners[*f][corner_of(faces[*f], vt)];
        moved[i].push_back(wedge);
        for (const auto& [at_vt, at_vs] : partner) {
          if (at_vt == wedge) {
            wedge = at_vs;
            break;
          }
        }
      }
      LODBAKE_RETURN_IF_ERROR(refiner.collapse_last());
    }
    out.base.assign(corners.begin(), corners.begin() + pm.base.triangles.size());
    out.moved_offset.push_back(0);
    for (const std::vector<uint32_t>& m : moved) {
      out.moved.insert(out.moved.end(), m.begin(), m.end());
      out.moved_offset.push_back(static_cast<uint32_t>(out.moved.size()));
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory assigning the progressive mesh's wedges");
  }
}

}  // namespace lodbake
