// The wedges of an asset's vertex trees in transmission: what the server
// adds to the node records so that the client's triangles have a wedge (an
// attribute set of the asset's WEDG) at every corner, and how the client
// finds them. The client emits a triangle per fan pair of a visible node,
// so each pair names its face slot of the progressive mesh and that face's
// wedge at the node's vertex; a corner's wedge is then the one its face
// slot has at the PM vertex the corner resolves to (the rule of
// CornerWedges and FrontWedges). A wing corner can resolve coarser than
// the PM ever had it; its wedge is the wing's at creation carried up the
// collapses (FrontWedges' rule), which each split sends for its wing faces
// as the vertices where the carried wedge changes.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/mesh/vertex_trees.h"
#include "formats/support/status.h"
#include "lib/hierarchy/front_wedges.h"
#include "lib/replay/vtrees_records.h"

namespace lodbake {

/// The server's wedge data for every node and split of the trees.
struct VtreesWedgeTable {
  uint32_t slot_count = 0;
  uint32_t wedge_count = 0;
  std::vector<std::vector<VtreesPairWedge>> pairs;  ///< per node, per fan pair
  std::vector<std::array<VtreesWing, 2>> wings;     ///< per split
  /// Per face slot: the split that adds it and its side (kNoVertex, 0 for
  /// a base face), for checks against FrontWedges.
  std::vector<uint32_t> slot_split;
  std::vector<uint8_t> slot_side;
};

/// From the trees, the progressive mesh they were built from (the VSPL
/// lodbake-hierarchy writes beside VHIE and VTRE) and that PM's WEDG.
/// kInvalidInput when `pm` is not the trees' (a fan pair without its face
/// slot, other split vertices) or `wedges` does not replay with it.
Result<VtreesWedgeTable> vtrees_wedge_table(const VertexTrees& trees, const ProgressiveMesh& pm,
                                            const PmWedges& wedges);

/// The client's side: the entries of the records received so far.
class VtreesCornerWedges {
 public:
  /// One received record of the node whose vertex is `vertex`: its pairs'
  /// wedges at that vertex. kInvalidInput when a pair gives a (slot,
  /// vertex) another wedge than an earlier record did.
  Status add_record(uint32_t vertex, const VtreesNodeRecord& record);
  /// A received split's wings. kInvalidInput when a slot had a wing already.
  Status add_wings(const VtreesWing (&wings)[2]);
  /// The wedge of face slot `slot`'s corner at PM vertex `vertex`,
  /// kNoVertex when the records received give none. A wing corner's
  /// `vertex` must be the wing vertex or an ancestor of it (what a client's
  /// resolved corner is); the rule needs only vertex ids (ancestors are
  /// smaller).
  uint32_t wedge(uint32_t slot, uint32_t vertex) const;
  size_t size() const { return lookup_.size(); }

 private:
  std::map<uint64_t, uint32_t> lookup_;  // slot << 32 | vertex
  std::map<uint32_t, VtreesWing> wings_;
};

/// The independent reference of --validate and the tests: each corner's
/// wedge by FrontWedges over the complete hierarchy `h` whose progressive
/// mesh the trees are.
class VtreesFrontReference {
 public:
  /// `h`, `table` and `front` must outlive the result; `front` is
  /// FrontWedges::create(h, pm, wedges) for the trees' `pm`.
  static Result<VtreesFrontReference> create(const VertexHierarchy& h, const VertexTrees& trees,
                                             const VtreesWedgeTable& table,
                                             const FrontWedges& front);
  /// The wedge FrontWedges gives face slot `slot` at trees node `node`.
  uint32_t wedge(uint32_t slot, uint32_t node) const;

 private:
  VtreesFrontReference() = default;
  const VtreesWedgeTable* table_ = nullptr;
  const FrontWedges* front_ = nullptr;
  uint32_t base_faces_ = 0;
  std::vector<uint32_t> node_of_split_;  // per split: the hierarchy node it splits
  std::vector<uint32_t> hier_node_;      // per trees node: its hierarchy node
};

}  // namespace lodbake
