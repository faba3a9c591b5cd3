// The server of vertex-tree transmission (To, Lau & Green 2001, section
// 5.1): the trees of a balanced hierarchy's progressive mesh with the
// hierarchy's refinement data (shared by every session), and per client a
// visible vertex list that moves down the trees where the client's view
// asks for more resolution and up where it asks for less; the records of
// nodes newly on the list are sent with the trace-up of the fan vertices
// the client does not hold, never a record twice.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "formats/mesh/vertex_hierarchy.h"
#include "formats/mesh/vertex_trees.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/stream_view.h"
#include "lib/replay/vtrees_records.h"
#include "lib/replay/vtrees_wedges.h"
#include "lib/vtrees/visible_vertex_list.h"

namespace lodbake {

/// The database entry: vertex trees built from
/// hierarchy_to_progressive_mesh(h) (what `lodbake-hierarchy` stores as
/// VTRE), with each split's view criteria taken from its hierarchy node.
struct VtreesDatabase {
  const VertexTrees* trees = nullptr;
  VtreesWidths widths;
  /// bounding_sphere() of every hierarchy node's position: what a client
  /// places its camera path around (the scene message over a connection).
  BoundingSphere sphere;
  /// Per split k: the refinement data of the hierarchy node split k splits
  /// and that node's position (the split vertex vs): qrefine()'s inputs.
  std::vector<NodeRefinement> data;
  std::vector<Vec3f> position;
  /// Per split: the node it splits; per node: the split under it (kNoVertex
  /// for a leaf of the trees).
  std::vector<uint32_t> parent_node;
  std::vector<uint32_t> child_split;
  /// An asset's trees: every record's wedge data (set_wedges()); empty for
  /// a mesh's, whose messages then carry none.
  std::optional<VtreesWedgeTable> wedges;

  /// `trees` must outlive the result. \return kInvalidInput when the trees
  /// do not validate, `data` has not one entry per node of `h`, or the
  /// trees are not those of hierarchy_to_progressive_mesh(h) (other base
  /// count, split order, parent vertices or positions).
  static Result<VtreesDatabase> create(const VertexTrees& trees, const VertexHierarchy& h,
                                       const std::vector<NodeRefinement>& data);
  /// Makes every message carry `table`'s wedge data (widths included).
  /// kInvalidInput when it is not sized for these trees.
  Status set_wedges(VtreesWedgeTable table);
  /// Node `node`'s record as sent (without traces): with its pairs when
  /// the database has wedges.
  VtreesNodeRecord record(uint32_t node) const;
  /// The first message of every session: the widths and the base records.
  Result<Bytes> trees_message() const;
};

/// What one answer sent.
struct VtreesAnswerStats {
  size_t splits = 0;         ///< kSplit items (a left and a right record each)
  size_t downs = 0;          ///< kDown items
  size_t ups = 0;            ///< kUp items
  size_t traces = 0;         ///< trace-ups inside the records
  size_t trace_updates = 0;  ///< kTraceUpdate items
  size_t messages = 0;
};

class VtreesServerSession {
 public:
  /// A session at the base mesh: the base nodes visible and sent (by
  /// trees_message()). `db` must outlive it. \pre 1 <= max_items_per_message
  /// <= kMaxVtreesItems.
  static Result<VtreesServerSession> create(const VtreesDatabase& db,
                                            size_t max_items_per_message = kMaxVtreesItems);

  /// Answers one view request (mode stream's view message): first the
  /// visible vertex list moves up where qrefine() is false on a split whose
  /// children are both on the list, then down where it is true on a visible
  /// node's split (tolerance 0: every split); the items in that order, as
  /// one or more frame messages (one empty message when nothing moved).
  /// Refuses a malformed request with the decoder's status, state unchanged.
  Result<std::vector<Bytes>> answer(const uint8_t* request, size_t size);

  /// The server's visible vertex list (what the client's must equal).
  const VisibleVertexList& list() const { return list_; }
  /// Nodes whose record was sent, in sending order (base nodes first).
  const std::vector<uint32_t>& sent_nodes() const { return sent_nodes_; }
  const VtreesAnswerStats& last_answer() const { return last_; }
  /// Per-client state: the list, sent flags, held first transmitted parents.
  size_t state_bytes() const;

 private:
  VtreesServerSession(const VtreesDatabase& db, VisibleVertexList list, size_t max_items);
  uint32_t first_transmitted(uint32_t vertex) const;
  void add_traces(VtreesNodeRecord* record);
  void send_split(uint32_t split, std::vector<VtreesItem>* items);

  const VtreesDatabase* db_;
  VisibleVertexList list_;
  size_t max_items_;
  std::vector<uint8_t> transmitted_;  // per vertex: its base or left record was sent
  std::vector<uint8_t> node_sent_;    // per node
  // Per vertex not transmitted: the first transmitted parent the client
  // holds for it (kNoVertex: none); per vertex: the vertices it is that of.
  std::vector<uint32_t> hint_;
  std::vector<std::vector<uint32_t>> users_;
  std::vector<uint32_t> sent_nodes_;
  VtreesAnswerStats last_;
};

}  // namespace lodbake
