// The client of truly selective view-dependent streaming (Kim, Lee and
// Kobbelt 2005, sections 4 and 5.3): it starts from the base message, keeps
// the partial vertex hierarchy the vsplit packets build (UpdateVHierarchy),
// refines and coarsens on it with lib/hierarchy's SelectiveRefiner (the cut
// vertices found as ActiveAncestor of the received fundamental cut
// vertices) and reports when its SelectiveRefinement loop needs a split it
// has not received, which is when it sends its view.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"
#include "lib/hierarchy/selective_refiner.h"
#include "lib/replay/stream_packets.h"
#include "lib/replay/stream_view.h"
#include "lib/replay/stream_wedges.h"

namespace lodbake {

struct StreamClientAdapt {
  size_t splits = 0;
  size_t collapses = 0;
  size_t passes = 0;
  /// Active nodes for which qrefine() holds but whose split has not been
  /// received (the client must send its view).
  size_t missing = 0;
};

class StreamClient {
 public:
  /// From the session's first message (decode_base_message()).
  static Result<StreamClient> create(const uint8_t* base_message, size_t size);

  /// One downlink message after the base: a vsplit message (each packet
  /// becomes two children of its node in the partial hierarchy) or an
  /// end-of-answer (its count must be the packets received since the last
  /// one). Refuses, with kInvalidInput, a packet for a node the client does
  /// not hold, has already received, or knows to be a leaf, and cut vertices
  /// in the node's own subtree or above it; packets before the bad one stay
  /// applied.
  Status receive(const uint8_t* data, size_t size);
  /// True after an end-of-answer, until the next vsplit message.
  bool answer_complete() const { return pending_ == 0 && complete_; }

  /// For a new connection after a lost one: forgets the count of an answer
  /// cut short (the packets that arrived stay applied) and returns the
  /// resume message, the ids of the partial hierarchy's leaves.
  Result<Bytes> reconnect();

  /// One pass of section 5.3's SelectiveRefinement over the client's front
  /// (local node order: parents before children), repeated until nothing
  /// changes or `max_passes`: split (with SelStreamVSplit's order) an active
  /// node qrefine() asks for when its split has been received, count it as
  /// missing otherwise; collapse a pair whose parent qrefine() rejects when
  /// the collapse is legal. No message is needed for either.
  Result<StreamClientAdapt> adapt(const StreamView& view, size_t max_passes = 64);

  /// The partial hierarchy: local nodes in arrival order (roots first, then
  /// the two children of each packet), positions, parents, children; cut
  /// vertices are the deepest received node on the way to the fundamental
  /// cut vertex.
  const VertexHierarchy& partial() const { return *h_; }
  const SelectiveRefiner& refiner() const { return *refiner_; }
  /// <tree-id, node-id> of a local node.
  HierarchyNodeId id_of(uint32_t node) const { return ids_[node]; }
  /// The ids of the nodes whose split was received, in arrival order.
  const std::vector<HierarchyNodeId>& received() const { return received_; }
  const StreamIdWidths& widths() const { return widths_; }

  /// An asset's stream (the base message carries wedges).
  bool has_wedges() const { return widths_.wedges != 0; }
  /// The hierarchy's name of the face refiner() gives `origin`
  /// (SelectiveRefiner::face_origins()).
  WedgeFace face_of(uint32_t origin) const;
  /// The wedge of every corner of refiner()'s current mesh, triangle by
  /// triangle as triangles() lists them, from the wedge data received.
  /// kInvalidInput naming the first corner without one (or a stream
  /// without wedges).
  Result<std::vector<std::array<uint32_t, 3>>> corner_wedges() const;

 private:
  StreamClient() = default;
  Status apply(const VsplitPacket& p);
  uint32_t find(const HierarchyNodeId& id) const;
  uint32_t deepest_known(const HierarchyNodeId& id) const;
  void watch(uint32_t node, int side);

  struct IdHash {
    size_t operator()(const HierarchyNodeId& id) const {
      return std::hash<uint64_t>()(id.heap * 0x9E3779B97F4A7C15ull ^ id.tree);
    }
  };

  std::unique_ptr<VertexHierarchy> h_;
  std::unique_ptr<SelectiveRefiner> refiner_;
  StreamIdWidths widths_;
  uint32_t roots_ = 0;
  std::vector<HierarchyNodeId> ids_;
  std::unordered_map<HierarchyNodeId, uint32_t, IdHash> index_;
  std::vector<NodeRefinement> data_;
  std::vector<uint8_t> internal_;  // internal in the complete hierarchy
  /// The fundamental cut vertices of received splits, [node][side].
  std::vector<std::array<HierarchyNodeId, 2>> cut_ids_;
  /// (node, side) whose cut reference is this partial leaf.
  std::vector<std::vector<std::pair<uint32_t, int>>> watchers_;
  std::vector<HierarchyNodeId> received_;
  StreamCornerWedges corner_wedges_;
  size_t pending_ = 0;  // packets since the last end-of-answer
  bool complete_ = true;
};

}  // namespace lodbake
