// The client of vertex-tree transmission (To, Lau & Green 2001, section
// 5.2): it rebuilds the vertex trees from the node records it receives,
// keeps its visible vertex list where the server's moves put it, and
// selects the triangles of the visible nodes' fans by vertex states, as
// VisibleVertexList does on the full trees.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/replay/vtrees_records.h"
#include "lib/replay/vtrees_wedges.h"

namespace lodbake {

/// Everything received so far, by kind; bits as vtrees_record_bits() counts
/// them (traces included in left and right), trace_bits the trace-up part.
struct VtreesReceived {
  size_t base_records = 0, left_records = 0, right_records = 0;
  uint64_t base_bits = 0, left_bits = 0, right_bits = 0;
  size_t traces = 0;
  uint64_t trace_bits = 0;
  size_t trace_updates = 0, downs = 0, ups = 0;
  size_t messages = 0;
  /// An asset's trees: the wedge part of the bits above (the base records'
  /// pairs; the split items' pairs and wings).
  uint64_t base_wedge_bits = 0, split_wedge_bits = 0;
};

class VtreesClient {
 public:
  /// Starts from the trees message: the base records, all visible.
  static Result<VtreesClient> create(const uint8_t* data, size_t size);

  /// Applies one frame message, item by item. Refuses (kInvalidInput) a
  /// malformed message, the records of a split twice, a split whose parent
  /// vertex is not on the list or whose parent node already has children, a
  /// fan vertex the client neither holds nor has a first transmitted parent
  /// for, a trace to a vertex it does not hold, a move the list cannot make.
  /// After an error the state is undefined; the session ends.
  Status receive(const uint8_t* data, size_t size);

  /// The triangle list of the visible vertex list, counter-clockwise, in PM
  /// vertex ids: a fan vertex not held is replaced by its first transmitted
  /// parent, any vertex not visible by its first visible ancestor; a
  /// triangle is kept when its own node's state is the lowest of its three
  /// (the resolution level, VisibleVertexList::vertex_state()), degenerate
  /// ones are dropped.
  std::vector<Triangle> triangles() const;
  /// Whether the trees carry wedge data (an asset's).
  bool has_wedges() const { return widths_.has_wedges(); }
  /// The wedge of every corner of triangles(), triangle by triangle: the
  /// wedge its fan pair's face slot has at the corner's resolved vertex.
  /// kInvalidInput naming the first corner the records give none for, or
  /// when the trees carry no wedges.
  Result<std::vector<std::array<uint32_t, 3>>> corner_wedges() const;
  /// triangles() with each one's face slot (an asset's trees; else empty).
  std::vector<Triangle> triangles(std::vector<uint32_t>* slots) const;

  const VtreesWidths& widths() const { return widths_; }
  /// The visible node of vertex v (kNoVertex when not visible).
  uint32_t visible_node(uint32_t vertex) const { return visible_[vertex]; }
  size_t visible_count() const { return visible_count_; }
  bool holds(uint32_t vertex) const { return held_[vertex] != 0; }
  /// Positions of held vertices (others are zero).
  const std::vector<Vec3f>& positions() const { return positions_; }
  const VtreesReceived& received() const { return received_; }
  /// Nodes held (base nodes and both children of every received split).
  size_t nodes_held() const;

 private:
  VtreesClient() = default;
  Status store_fan(uint32_t node, const VtreesNodeRecord& record);
  Status apply(const VtreesItem& item);
  uint32_t resolve(uint32_t vertex) const;
  uint64_t selection_key(uint32_t node) const;

  VtreesWidths widths_;
  std::vector<uint8_t> held_;            // per vertex
  std::vector<uint32_t> hint_;           // per vertex not held: its first transmitted parent
  std::vector<Vec3f> positions_;         // per vertex
  std::vector<uint8_t> states_;          // per vertex: the paper's state (kept, not used to select)
  std::vector<uint32_t> visible_;        // per vertex: its visible node
  std::vector<uint32_t> parent_vertex_;  // per split received
  std::vector<uint32_t> parent_node_;    // per split received
  std::vector<uint8_t> split_held_;      // per split
  std::vector<uint32_t> child_split_;    // per node
  // Fans: node n's runs are runs_[node_run_[n] .. node_run_[n] + node_runs_[n]);
  // run r holds fan_[run_start_[r] .. + (runs_[r] >> 1)), closed when runs_[r] & 1.
  std::vector<uint32_t> node_run_, node_runs_;
  std::vector<uint32_t> runs_, run_start_;
  std::vector<uint32_t> fan_;
  // An asset's trees: run r's fan pairs have face slots pair_slot_[run_pair_[r] ..).
  std::vector<uint32_t> run_pair_, pair_slot_;
  VtreesCornerWedges wedges_;
  size_t visible_count_ = 0;
  size_t splits_held_ = 0;
  VtreesReceived received_;
};

}  // namespace lodbake
