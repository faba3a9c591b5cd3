// The server of truly selective view-dependent streaming (Kim, Lee and
// Kobbelt 2005, sections 5.2, 5.3 and 6.1): a static database entry (the
// hierarchy with its RFIN records, shared by every session) and a session
// per client holding only the client's active tags, windowed over the
// breadth-first node array. A view request is answered by qrefine() over the
// active nodes (SelectiveStreaming), each split preceded by the splits
// SelStreamVSplit's partial order asks for, and never a node twice.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/vertex_hierarchy.h"
#include "formats/sections/rfin.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/stream_packets.h"
#include "lib/replay/stream_transport.h"
#include "lib/replay/stream_view.h"
#include "lib/replay/stream_wedges.h"

namespace lodbake {

/// Active tags as a bit array over node indices with a window (section 6.1,
/// Figure 4(b)): every bit below win_min() and from win_max() on is 0, and
/// only the words that cover the window are allocated. The buffer slides
/// right as the window does and doubles when the window outgrows it (the
/// paper's allocation policy).
class ActiveTagWindow {
 public:
  bool test(size_t i) const;
  void set(size_t i);
  void clear(size_t i);
  /// The lowest set bit and one past the highest (equal when none is set):
  /// always tight.
  size_t win_min() const { return win_min_; }
  size_t win_max() const { return win_max_; }
  /// The first set bit at or after `from`, win_max() when none.
  size_t next(size_t from) const;
  size_t set_count() const { return set_count_; }
  /// ceil((win_max - win_min) / 8): the window itself, the paper's "ideal".
  size_t window_bytes() const { return (win_max_ - win_min_ + 7) / 8; }
  /// The allocated buffer (whole 64-bit words).
  size_t buffer_bytes() const { return words_.size() * 8; }

 private:
  std::vector<uint64_t> words_;
  size_t first_word_ = 0;  // node index / 64 of words_[0]
  size_t win_min_ = 0;
  size_t win_max_ = 0;
  size_t set_count_ = 0;
};

/// The database entry: a hierarchy (validate_hierarchy() clean) and its RFIN
/// records, with the derived ids, id widths and dequantized data.
struct StreamHierarchy {
  const VertexHierarchy* h = nullptr;
  std::vector<RfinRecord> records;   ///< one per node, leaves zero
  std::vector<NodeRefinement> data;  ///< dequantize_refinement(records[i])
  std::vector<HierarchyNodeId> ids;  ///< <tree-id, node-id> of every node
  StreamIdWidths widths;
  /// bounding_sphere() of every node's position: the scene message.
  BoundingSphere sphere;
  /// An asset's stream (set_wedges()): the wedges the base message and the
  /// packets carry; empty otherwise.
  StreamWedgeTable wedges;

  /// `h` must outlive the result. \return kInvalidInput when `h` does not
  /// validate or `records` does not have one entry per node.
  static Result<StreamHierarchy> create(const VertexHierarchy& h, std::vector<RfinRecord> records);
  /// The same from RFIN's float values (quantize_refinement() per node).
  static Result<StreamHierarchy> create(const VertexHierarchy& h,
                                        const std::vector<NodeRefinement>& data);
  /// Makes the stream an asset's: the base message and every packet carry
  /// `table`'s wedge data, and the widths say so. kInvalidInput when the
  /// table does not have an entry per node and per base triangle.
  Status set_wedges(StreamWedgeTable table);
  StreamNodeData node_data(uint32_t node) const;
  /// The base message: the base mesh, the depth and the roots' data.
  Result<Bytes> base_message() const;
  /// The packet of node s's split (its children's data, its cut vertices).
  VsplitPacket packet(uint32_t s) const;
  /// The node of an id (the root's children chosen by the heap id's bits
  /// after its leading 1), kNoNode when the hierarchy has no such node.
  uint32_t node_of(const HierarchyNodeId& id) const;
  /// The largest uplink payload a client can need: a resume message naming
  /// every node (and at least a view request). Servers bound their
  /// transports' reads with it.
  uint32_t uplink_payload_limit() const;
};

struct StreamServerOptions {
  /// Keep the tags of real leaves set once they are sent (the server front
  /// taken literally). Off by default: a real leaf is never split, so its
  /// tag would only pin win_min; the front is the tagged nodes plus the sent
  /// leaves, and ActiveAncestor still finds every front node (docs/replay.md).
  bool tag_real_leaves = false;
  /// Packets per vsplit message (an answer is several messages, then an
  /// end-of-answer).
  size_t max_packets_per_message = 4096;
};

/// Server memory for one session.
struct StreamServerMemory {
  size_t window_bytes = 0;  ///< the tag window, ceil(span / 8)
  size_t buffer_bytes = 0;  ///< the allocated tag buffer
  size_t front_nodes = 0;   ///< the server's vertex front (sent leaves of the client's tree)
  size_t front_bytes = 0;   ///< a stored vertex front: 4 bytes (a node index) per front node
};

class StreamServerSession {
 public:
  /// A session at the base mesh: the roots' tags set. `db` must outlive it.
  StreamServerSession(const StreamHierarchy& db, const StreamServerOptions& options);

  /// Base mesh transmission (the session's first message).
  Result<Bytes> base_message() const { return db_->base_message(); }

  /// Continues a client's session on a new connection from the leaves of
  /// its partial hierarchy (decode_resume_message()): every ancestor of a
  /// leaf counts as held by the client (resumed()), the leaves are the
  /// server's front, and the tags are set for those that are internal.
  /// \pre a fresh session (nothing answered yet).
  /// \return kInvalidInput, state unchanged, when the ids are not a front
  ///         of the hierarchy: an id that names no node, a leaf above
  ///         another, a tree without one, a held split whose child is
  ///         neither a leaf nor held.
  Status resume(const std::vector<HierarchyNodeId>& leaves);
  /// Splits the client held when the session resumed (0 when it started
  /// from the base mesh); sent() holds only what this session sent.
  size_t resumed() const { return resumed_; }

  /// Answers one view request (a whole uplink message): the vsplit messages
  /// of every split qrefine() asks for on the active nodes, in an order that
  /// respects SelStreamVSplit's partial order, then an end-of-answer (alone
  /// when nothing is needed). A split that the partial order forces behind
  /// the sweep's position makes the sweep run again from its children, so
  /// one answer holds everything the view needs. Refuses a malformed request
  /// with the decoder's status, state unchanged; kInvalidInput when the
  /// hierarchy's cut vertices are damaged (the partial order asks for a node
  /// that cannot split, or goes round in circles).
  Result<std::vector<Bytes>> answer(const uint8_t* request, size_t size);

  const ActiveTagWindow& tags() const { return tags_; }
  /// Nodes whose split was sent, in sending order.
  const std::vector<uint32_t>& sent() const { return sent_; }
  StreamServerMemory memory() const;

 private:
  uint32_t active_ancestor(uint32_t leaf) const;
  Status sel_stream_vsplit(uint32_t node, std::vector<VsplitPacket>* out, size_t* behind,
                           size_t cursor);

  const StreamHierarchy* db_;
  StreamServerOptions options_;
  ActiveTagWindow tags_;
  std::vector<uint32_t> sent_;
  size_t front_nodes_ = 0;
  size_t resumed_ = 0;
  size_t answers_ = 0;
};

/// One client's connection on the server. The first message is a resume
/// message: without leaves (a hello) the server sends the base and scene
/// messages; with leaves the session resumes from them and nothing is sent.
/// Every later message must be a view request, answered with vsplit
/// messages and an end-of-answer. Anything else ends the connection with
/// the decoder's kInvalidInput status.
class StreamServerConnection {
 public:
  /// `db` must outlive the connection.
  StreamServerConnection(const StreamHierarchy& db, const StreamServerOptions& options);

  /// Handles one whole uplink message, sending its answer through `out`.
  Status handle(const Bytes& message, StreamTransport* out);
  /// Bounds `t`'s reads by db.uplink_payload_limit(), then receives and
  /// handles messages until the client closes between two of them (ok) or
  /// anything fails (that status).
  Status serve(StreamTransport* t);

  /// True after the first message was accepted.
  bool started() const { return started_; }
  /// \pre started().
  const StreamServerSession& session() const { return session_; }
  size_t requests() const { return requests_; }

 private:
  const StreamHierarchy* db_;
  StreamServerSession session_;
  bool started_ = false;
  size_t requests_ = 0;
};

}  // namespace lodbake
