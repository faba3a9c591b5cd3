// The wedges of an asset's stream: what the server sends with the base mesh
// and with each split so that the client's mesh has a wedge (an attribute
// set of the asset's WEDG) at every corner, and how the client finds them.
// The rule is FrontWedges' (lib/hierarchy/front_wedges.h), split between
// the two ends: a corner's wedge is the one its face slot took at the
// progressive-mesh vertex the corner's node sits at, and a wing corner
// coarser than the PM ever had it takes the wing's wedge carried up the
// collapses. The server knows the whole PM; the client holds only what
// arrived, so each split brings the entries keyed at the vertices it
// creates (the added faces' corners, the moved faces' wedges at the right
// child) and each wing its carried wedges for every level up to its root.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"
#include "lib/replay/stream_packets.h"

namespace lodbake {

/// The server's wedge data: the base triangles' corners and each internal
/// node's split (VsplitWedges; leaves' entries stay empty).
struct StreamWedgeTable {
  uint32_t wedge_count = 0;
  std::vector<std::array<uint32_t, 3>> base;
  std::vector<VsplitWedges> splits;  ///< per node
};

/// From `h`, its own progressive mesh `pm` (the VSPL lodbake-hierarchy
/// writes beside VHIE) and that PM's WEDG. kInvalidInput when `pm` is not
/// `h`'s own or `wedges` does not replay with it (either may come from a file).
Result<StreamWedgeTable> stream_wedge_table(const VertexHierarchy& h, const ProgressiveMesh& pm,
                                            const PmWedges& wedges);

/// The client's side: the entries of the messages received so far, and
/// each corner's wedge from them.
class StreamCornerWedges {
 public:
  /// The base triangles' corners (their vertices are the roots).
  Status add_base(const std::vector<Triangle>& triangles,
                  const std::vector<std::array<uint32_t, 3>>& corners);
  /// One received split's wedge data. kInvalidInput, nothing kept, when it
  /// gives a pair (face, vertex) another wedge than an earlier message did
  /// or than itself.
  Status add_split(const VsplitPacket& p);
  /// The wedge of the corner of `face` at node `at` (complete hierarchy
  /// ids), kNoVertex when the messages received give none.
  uint32_t wedge(const WedgeFace& face, const HierarchyNodeId& at) const;
  size_t size() const { return lookup_.size(); }

 private:
  struct Wing {
    HierarchyNodeId w;
    uint32_t wedge = kNoVertex;
    std::vector<std::pair<uint32_t, uint32_t>> changes;
  };
  using Key = std::pair<WedgeFace, HierarchyNodeId>;  // the face, the corner's canonical node
  using Entry = std::pair<Key, uint32_t>;
  Status put_all(const std::vector<Entry>& entries);

  std::map<Key, uint32_t> lookup_;
  std::map<WedgeFace, Wing> wings_;
};

}  // namespace lodbake
