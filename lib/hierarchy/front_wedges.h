// The wedges of a selective front of a balanced vertex hierarchy: which
// attribute set (a wedge of the hierarchy's progressive mesh, WEDG) each
// corner of the SelectiveRefiner's current mesh uses, whatever the view
// made of it. A front's face is a face slot of the hierarchy's own
// progressive mesh (hierarchy_to_progressive_mesh); where its corner sits
// at a vertex it also has in some level of that PM, the wedge is that
// level's (CornerWedges). A wing corner can sit coarser than any level
// gives it (the view left the wing's side coarser than the PM order did):
// its wedge is then the wing's wedge at creation carried up the collapses
// by the rule that assigned the PM's wedges (pm_wedge_assignment.h): at
// each collapse of a right child into its sibling, vt's wedge becomes its
// partner at vs across the collapsed edge, or stays.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"
#include "lib/hierarchy/selective_refiner.h"
#include "lib/simplify/wedge_replay.h"

namespace lodbake {

// The hierarchy's split order (hierarchy_to_progressive_mesh()'s) once `pm`
// is checked to be the hierarchy's own progressive mesh (its base triangles
// and every split's vs, vl and vr): what a WEDG beside VHIE is made for.
Result<std::vector<uint32_t>> hierarchy_split_order(const VertexHierarchy& h,
                                                    const ProgressiveMesh& pm);

class FrontWedges {
 public:
  /// `pm` must be `h`'s own progressive mesh (the VSPL lodbake-hierarchy
  /// writes beside VHIE) and `wedges` its WEDG: kInvalidInput otherwise
  /// (either may come from a file). `h` must outlive the result.
  static Result<FrontWedges> create(const VertexHierarchy& h, const ProgressiveMesh& pm,
                                    const PmWedges& wedges);

  /// The wedge of the corner at `node` of the face SelectiveRefiner calls
  /// `origin` (face_origins()); kNoVertex when no front can have that pair.
  uint32_t wedge(uint32_t origin, uint32_t node) const;

  /// The progressive-mesh vertex `node` sits at (a left child shares its
  /// parent's).
  uint32_t pm_vertex(uint32_t node) const { return pm_vertex_[node]; }

  /// Every corner's wedge of `refiner`'s current mesh, triangle by triangle
  /// as triangles() lists them. kInvalidInput naming the first corner
  /// without one.
  Result<std::vector<std::array<uint32_t, 3>>> corners(const SelectiveRefiner& refiner) const;

 private:
  FrontWedges(const VertexHierarchy& h, CornerWedges lookup) : h_(&h), lookup_(std::move(lookup)) {}
  uint32_t slot_of(uint32_t origin, uint32_t* split, int* side) const;

  const VertexHierarchy* h_;
  CornerWedges lookup_;
  uint32_t base_faces_ = 0;
  std::vector<uint32_t> pm_vertex_;      // per node
  std::vector<uint32_t> split_of_node_;  // per node: its split in the PM, or kNoVertex
  std::vector<uint32_t> first_slot_;     // per split: the face slot of its first added face
  std::vector<uint32_t> wing_node_;      // per split and side: the wing corner's node then
  std::vector<std::array<uint32_t, 6>> added_;
};

}  // namespace lodbake
