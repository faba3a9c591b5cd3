// The streaming server (Kim, Lee and Kobbelt 2005, sections 5.2, 5.3, 6.1).
// Choices where the paper is vague:
// - active tags: 1 for a node on the server's vertex front (sent to the
//   client, not yet split) that is internal in the complete hierarchy. A
//   real leaf is never split (qrefine() is false for it), so once sent its
//   tag would only pin win_min near the start of the array for ever; it is
//   left 0 (StreamServerOptions::tag_real_leaves keeps it). So, as Figure
//   4(b) shows, the bits left of win_min and right of win_max are all 0;
//   the front is the tagged nodes plus the sent leaves, and ActiveAncestor
//   of a fundamental cut vertex (a leaf) is the first tagged node on its
//   path to the root, or the leaf itself when none is tagged (then every
//   ancestor was split, so the leaf was sent);
// - the buffer holds the 64-bit words from win_min's word on; it slides
//   right when a bit beyond it is set and the window still fits, and
//   doubles when it does not (section 8's allocation policy);
// - SelectiveStreaming sweeps the tags from win_min to win_max once, as
//   section 6.1 says; children of a split come after their parent and are
//   visited in the same sweep. A split forced by the partial order can lie
//   behind the sweep (its children too): the sweep then runs again from
//   the first such child, so an answer is complete for its view and a
//   client asks at most once per view;
// - the memory of a stored vertex front is counted as 4 bytes (a node
//   index) per front node;
// - resume (not in the paper, the reconnecting client): the server
//   keeps nothing of a closed connection; the client's leaves say exactly
//   what it holds (a partial hierarchy is the ancestors of its leaves, and
//   each prefix of an answer is a state the server's own sweep went
//   through), so the new session is rebuilt from them and a split the
//   client holds is never sent again. Packets lost in flight when the
//   connection died are not held by the client, so they are sent again.
#include "lib/replay/stream_server.h"

#include <algorithm>
#include <limits>
#include <new>
#include <utility>

#include "formats/sections/vhie.h"
#include "formats/support/bit_packing.h"

namespace lodbake {

bool ActiveTagWindow::test(size_t i) const {
  if (i < win_min_ || i >= win_max_) return false;
  return (words_[i / 64 - first_word_] >> (i % 64)) & 1;
}

void ActiveTagWindow::set(size_t i) {
  if (test(i)) return;
  const size_t w = i / 64;
  if (set_count_ == 0) {
    if (words_.empty()) words_.assign(1, 0);
    std::fill(words_.begin(), words_.end(), 0);
    first_word_ = w;
  } else if (w < first_word_) {
    words_.insert(words_.begin(), first_word_ - w, 0);
    first_word_ = w;
  } else if (w >= first_word_ + words_.size()) {
    // The words left of the window are free: slide, or double if it does
    // not fit.
    const size_t live = win_min_ / 64;
    const size_t need = w - live + 1;
    const size_t capacity =
        need > words_.size() ? std::max(words_.size() * 2, need) : words_.size();
    std::vector<uint64_t> moved(capacity, 0);
    for (size_t k = live; k < first_word_ + words_.size(); ++k)
      moved[k - live] = words_[k - first_word_];
    words_.swap(moved);
    first_word_ = live;
  }
  words_[w - first_word_] |= uint64_t{1} << (i % 64);
  if (set_count_ == 0) {
    win_min_ = i;
    win_max_ = i + 1;
  } else {
    win_min_ = std::min(win_min_, i);
    win_max_ = std::max(win_max_, i + 1);
  }
  ++set_count_;
}

void ActiveTagWindow::clear(size_t i) {
  if (!test(i)) return;
  words_[i / 64 - first_word_] &= ~(uint64_t{1} << (i % 64));
  if (--set_count_ == 0) {
    win_min_ = win_max_ = i;
    return;
  }
  if (i == win_min_) win_min_ = next(i + 1);
  if (i + 1 == win_max_) {
    size_t j = i;
    while (!test(j))
      --j;  // set_count_ > 0 and win_min_ <= j: ends
    win_max_ = j + 1;
  }
}

size_t ActiveTagWindow::next(size_t from) const {
  size_t i = std::max(from, win_min_);
  while (i < win_max_) {
    const uint64_t word = words_[i / 64 - first_word_] >> (i % 64);
    if (word != 0) {
      const size_t found = i + static_cast<size_t>(__builtin_ctzll(word));
      return std::min(found, win_max_);
    }
    i = (i / 64 + 1) * 64;
  }
  return win_max_;
}

Result<StreamHierarchy> StreamHierarchy::create(const VertexHierarchy& h,
                                                std::vector<RfinRecord> records) {
  const std::vector<std::string> problems = validate_hierarchy(h);
  if (!problems.empty()) return invalid_input("vertex hierarchy: " + problems.front());
  if (records.size() != h.node_count()) {
    return invalid_input("refinement data has " + std::to_string(records.size()) + " entries for " +
                         std::to_string(h.node_count()) + " nodes");
  }
  try {
    StreamHierarchy db;
    db.h = &h;
    db.data.resize(h.node_count());
    for (uint32_t i = 0; i < h.node_count(); ++i) {
      if (h.is_leaf(i)) {
        records[i] = RfinRecord();
        continue;
      }
      if (!rfin_record_is_valid(records[i])) {
        return invalid_input("refinement data of node " + std::to_string(i) +
                             " is negative or not finite");
      }
      db.data[i] = dequantize_refinement(records[i]);
    }
    db.records = std::move(records);
    db.ids = hierarchy_node_ids(h);
    db.widths.tree_bits = bits_for_count(h.root_count());
    db.widths.node_bits = static_cast<int>(hierarchy_shape(h).depth);
    db.sphere = bounding_sphere(h.position);
    return db;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the hierarchy for streaming");
  }
}

Result<StreamHierarchy> StreamHierarchy::create(const VertexHierarchy& h,
                                                const std::vector<NodeRefinement>& data) {
  if (data.size() != h.node_count()) {
    return invalid_input("refinement data has " + std::to_string(data.size()) + " entries for " +
                         std::to_string(h.node_count()) + " nodes");
  }
  std::vector<RfinRecord> records(data.size());
  for (size_t i = 0; i < data.size(); ++i) {
    if (h.first_child[i] == kNoNode) continue;
    Result<RfinRecord> q = quantize_refinement(data[i]);
    if (!q.is_ok()) {
      return invalid_input("refinement data of node " + std::to_string(i) + ": " +
                           q.status().message());
    }
    records[i] = q.value();
  }
  return create(h, std::move(records));
}

Status StreamHierarchy::set_wedges(StreamWedgeTable table) {
  if (table.splits.size() != h->node_count() || table.base.size() != h->base.triangles.size() ||
      table.wedge_count == 0) {
    return invalid_input("the stream's wedges do not match its hierarchy");
  }
  wedges = std::move(table);
  widths.wedges = wedges.wedge_count;
  widths.base_faces = static_cast<uint32_t>(h->base.triangles.size());
  return Status::ok();
}

StreamNodeData StreamHierarchy::node_data(uint32_t node) const {
  StreamNodeData d;
  d.internal = !h->is_leaf(node);
  if (d.internal) d.record = records[node];
  return d;
}

Result<Bytes> StreamHierarchy::base_message() const {
  BaseMessage base;
  base.mesh.positions = h->base.positions;
  base.mesh.triangles = h->base.triangles;
  base.node_bits = widths.node_bits;
  for (uint32_t r = 0; r < h->root_count(); ++r)
    base.roots.push_back(node_data(r));
  base.wedge_count = widths.wedges;
  base.corners = wedges.base;
  return encode_base_message(base);
}

VsplitPacket StreamHierarchy::packet(uint32_t s) const {
  VsplitPacket p;
  p.vs = ids[s];
  if (h->cut_left[s] != kNoNode) p.cut_left = ids[h->cut_left[s]];
  if (h->cut_right[s] != kNoNode) p.cut_right = ids[h->cut_right[s]];
  const uint32_t left = h->first_child[s];
  p.position = h->position[left + 1];
  p.left = node_data(left);
  p.right = node_data(left + 1);
  if (widths.wedges != 0) p.wedges = wedges.splits[s];
  return p;
}

uint32_t StreamHierarchy::node_of(const HierarchyNodeId& id) const {
  if (id.tree >= h->root_count() || id.heap == 0) return kNoNode;
  int top = 63;
  while (((id.heap >> top) & 1) == 0)
    --top;
  uint32_t v = id.tree;
  for (int bit = top - 1; bit >= 0; --bit) {
    if (h->is_leaf(v)) return kNoNode;
    v = h->first_child[v] + static_cast<uint32_t>((id.heap >> bit) & 1);
  }
  return v;
}

uint32_t StreamHierarchy::uplink_payload_limit() const {
  const uint64_t resume = 4 + (uint64_t{h->node_count()} * widths.id_bits() + 7) / 8;
  return static_cast<uint32_t>(std::min<uint64_t>(
      kMaxStreamPayloadBytes, std::max<uint64_t>(resume, kViewRequestPayloadBytes)));
}

StreamServerSession::StreamServerSession(const StreamHierarchy& db,
                                         const StreamServerOptions& options)
    : db_(&db), options_(options) {
  const VertexHierarchy& h = *db.h;
  for (uint32_t r = 0; r < h.root_count(); ++r) {
    if (!h.is_leaf(r) || options_.tag_real_leaves) tags_.set(r);
  }
  front_nodes_ = h.root_count();
}

uint32_t StreamServerSession::active_ancestor(uint32_t leaf) const {
  for (uint32_t v = leaf; v != kNoNode; v = db_->h->parent[v]) {
    if (tags_.test(v)) return v;
  }
  return leaf;
}

Status StreamServerSession::sel_stream_vsplit(uint32_t node, std::vector<VsplitPacket>* out,
                                              size_t* behind, size_t cursor) {
  const VertexHierarchy& h = *db_->h;
  std::vector<uint32_t> stack{node};
  size_t steps = 0;
  // The hierarchy's cut vertices (VHIE) decide the order; when they send the
  // order round in circles or to a node that cannot split, the data is
  // damaged: invalid input, not a failure of the algorithm.
  while (!stack.empty()) {
    if (++steps > 4 * h.node_count() + 4) {
      return invalid_input("the split order of node " + std::to_string(node) + " does not end");
    }
    const uint32_t s = stack.back();
    if (h.is_leaf(s) || !tags_.test(s)) {
      return invalid_input("the partial order of node " + std::to_string(node) + " asks for node " +
                           std::to_string(s) + ", which is not splittable");
    }
    const uint32_t l = h.cut_left[s];
    const uint32_t r = h.cut_right[s];
    const uint32_t al = l == kNoNode ? kNoNode : active_ancestor(l);
    const uint32_t ar = r == kNoNode ? kNoNode : active_ancestor(r);
    if (al == ar && al != kNoNode) {
      stack.push_back(al);
      continue;
    }
    out->push_back(db_->packet(s));
    const uint32_t left = h.first_child[s];
    for (uint32_t c : {left, left + 1}) {
      if (!h.is_leaf(c) || options_.tag_real_leaves) tags_.set(c);
    }
    tags_.clear(s);
    ++front_nodes_;
    sent_.push_back(s);
    if (left <= cursor) *behind = std::min<size_t>(*behind, left);
    stack.pop_back();
  }
  return Status::ok();
}

Result<std::vector<Bytes>> StreamServerSession::answer(const uint8_t* request, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ViewRequest req, decode_view_request(request, size));
  ++answers_;
  const StreamView view = stream_view(req);
  const VertexHierarchy& h = *db_->h;
  try {
    std::vector<VsplitPacket> packets;
    constexpr size_t kNone = std::numeric_limits<size_t>::max();
    size_t from = tags_.win_min();
    for (;;) {
      size_t behind = kNone;
      for (size_t v = tags_.next(from); v < tags_.win_max(); v = tags_.next(v + 1)) {
        const auto node = static_cast<uint32_t>(v);
        if (h.is_leaf(node)) continue;
        if (!stream_qrefine(view, db_->data[node], h.position[node])) continue;
        LODBAKE_RETURN_IF_ERROR(sel_stream_vsplit(node, &packets, &behind, v));
      }
      if (behind == kNone) break;
      from = behind;
    }
    std::vector<Bytes> messages;
    const size_t per = std::max<size_t>(1, options_.max_packets_per_message);
    for (size_t i = 0; i < packets.size(); i += per) {
      const std::vector<VsplitPacket> chunk(
          packets.begin() + static_cast<ptrdiff_t>(i),
          packets.begin() + static_cast<ptrdiff_t>(std::min(i + per, packets.size())));
      LODBAKE_ASSIGN_OR_RETURN(
          Bytes m,
          encode_vsplit_message(chunk, db_->widths, static_cast<uint32_t>(h.root_count())));
      messages.push_back(std::move(m));
    }
    messages.push_back(encode_end_of_answer(static_cast<uint32_t>(packets.size())));
    return messages;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory answering a view request");
  }
}

Status StreamServerSession::resume(const std::vector<HierarchyNodeId>& leaves) {
  const VertexHierarchy& h = *db_->h;
  if (answers_ != 0 || resumed_ != 0 || !sent_.empty()) {
    return runtime_error("resume: the session has already started");
  }
  try {
    // 1: on the path above a leaf (held split), 2: a leaf.
    std::vector<uint8_t> state(h.node_count(), 0);
    std::vector<uint32_t> front;
    front.reserve(leaves.size());
    for (const HierarchyNodeId& id : leaves) {
      const std::string at =
          "resume: leaf <" + std::to_string(id.tree) + "," + std::to_string(id.heap) + ">: ";
      const uint32_t v = db_->node_of(id);
      if (v == kNoNode) return invalid_input(at + "no such node in the hierarchy");
      if (state[v] != 0) return invalid_input(at + "repeated or above another leaf");
      state[v] = 2;
      front.push_back(v);
      for (uint32_t p = h.parent[v]; p != kNoNode && state[p] != 1; p = h.parent[p]) {
        if (state[p] == 2) return invalid_input(at + "below another leaf");
        state[p] = 1;
      }
    }
    size_t held = 0;
    for (uint32_t r = 0; r < h.root_count(); ++r) {
      if (state[r] == 0) {
        return invalid_input("resume: tree " + std::to_string(r) + " has no leaf");
      }
    }
    for (uint32_t v = 0; v < h.node_count(); ++v) {
      if (state[v] != 1) continue;
      ++held;
      const uint32_t c = h.first_child[v];
      if (state[c] == 0 || state[c + 1] == 0) {
        return invalid_input("resume: node <" + std::to_string(db_->ids[v].tree) + "," +
                             std::to_string(db_->ids[v].heap) +
                             "> is split but a child is neither a leaf nor split");
      }
    }
    ActiveTagWindow tags;
    std::sort(front.begin(), front.end());
    for (uint32_t v : front) {
      if (!h.is_leaf(v) || options_.tag_real_leaves) tags.set(v);
    }
    tags_ = std::move(tags);
    front_nodes_ = front.size();
    resumed_ = held;
    return Status::ok();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory resuming a streaming session");
  }
}

StreamServerMemory StreamServerSession::memory() const {
  StreamServerMemory m;
  m.window_bytes = tags_.window_bytes();
  m.buffer_bytes = tags_.buffer_bytes();
  m.front_nodes = front_nodes_;
  m.front_bytes = 4 * front_nodes_;
  return m;
}

StreamServerConnection::StreamServerConnection(const StreamHierarchy& db,
                                               const StreamServerOptions& options)
    : db_(&db), session_(db, options) {}

Status StreamServerConnection::handle(const Bytes& message, StreamTransport* out) {
  LODBAKE_ASSIGN_OR_RETURN(StreamMessageType type,
                           stream_message_type(message.data(), message.size()));
  if (!started_) {
    if (type != StreamMessageType::kResume) {
      return invalid_input("stream message: type " + std::to_string(static_cast<int>(type)) +
                           " where a connection's first message (hello or resume) was expected");
    }
    LODBAKE_ASSIGN_OR_RETURN(uint32_t count, resume_leaf_count(message.data(), message.size()));
    if (count == 0) {
      LODBAKE_ASSIGN_OR_RETURN(
          std::vector<HierarchyNodeId> none,
          decode_resume_message(message.data(), message.size(), db_->widths,
                                static_cast<uint32_t>(db_->h->root_count()), 0));
      (void)none;
      LODBAKE_ASSIGN_OR_RETURN(Bytes base, db_->base_message());
      started_ = true;
      LODBAKE_RETURN_IF_ERROR(out->send(base));
      return out->send(encode_scene_message(db_->sphere));
    }
    LODBAKE_ASSIGN_OR_RETURN(
        std::vector<HierarchyNodeId> leaves,
        decode_resume_message(message.data(), message.size(), db_->widths,
                              static_cast<uint32_t>(db_->h->root_count()), db_->h->node_count()));
    LODBAKE_RETURN_IF_ERROR(session_.resume(leaves));
    started_ = true;
    return Status::ok();
  }
  if (type != StreamMessageType::kView) {
    return invalid_input("stream message: type " + std::to_string(static_cast<int>(type)) +
                         " where a view request was expected");
  }
  LODBAKE_ASSIGN_OR_RETURN(std::vector<Bytes> answer,
                           session_.answer(message.data(), message.size()));
  ++requests_;
  for (const Bytes& m : answer)
    LODBAKE_RETURN_IF_ERROR(out->send(m));
  return Status::ok();
}

Status StreamServerConnection::serve(StreamTransport* t) {
  t->set_max_payload(db_->uplink_payload_limit());
  for (;;) {
    bool closed = false;
    LODBAKE_ASSIGN_OR_RETURN(Bytes message, t->receive(&closed));
    if (closed) return Status::ok();
    LODBAKE_RETURN_IF_ERROR(handle(message, t));
  }
}

}  // namespace lodbake
