// Codec of the vertex-tree messages (lib/replay/vtrees_records.h; To, Lau &
// Green 2001, section 5.1's RightNode / BaseNode / CLeftNode). Choices where
// the paper is vague or its records do not fit lodbake's trees:
// - every record keeps the paper's VID (the base records could go without,
//   being sent in order; kept so that the bytes per record compare with
//   the paper's), and the left record its PID; ids take bits(B + S) bits
//   instead of 16;
// - a fan is a list of runs (closed bit + length each, widths sent once in
//   the trees message) instead of one closed bit and a 7-bit length, so any
//   vertex degree and non-manifold vertices fit (as VTRE does);
// - the vertex state is the paper's equation (2), 0 or 1: one bit in base
//   and left records (the paper's CLeftNode repeats its BaseNode's byte;
//   lodbake sends it once); the right record has none, as in the paper;
// - coordinates are float32 as their IEEE-754 bits (the paper's are 2-byte
//   values): 96 bits against the paper's 48;
// - the trace-up: for a fan vertex the client does not hold and has no
//   first transmitted parent for, the record carries (entry index, parent
//   id) after its fan, with a count of bits(fan size + 1) bits; the fan
//   itself keeps the vertex's own id, so the client can use the vertex once
//   it arrives (the paper: "its ID is also sent");
// - items of a frame carry a 2-bit kind; a split's left and right records
//   travel as one item (the list moves down at a node to both children);
// - an asset's records name, per fan pair, the progressive mesh's face slot
//   and its wedge at the node's vertex (the client emits triangles from
//   fans, so the slot is what ties a triangle to its corners' wedges); a
//   split adds its wing faces' wing wedges with their carried changes
//   (lib/replay/vtrees_wedges.h gives the rule).
#include "lib/replay/vtrees_records.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <string>

#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

Status bad(const std::string& detail) {
  return invalid_input("vtrees message: " + detail);
}

bool fits(uint64_t value, int bits) {
  return bits >= 64 || value < (uint64_t{1} << bits);
}

Bytes frame(VtreesMessageType type, const Bytes& payload) {
  return frame_message(kVtreesMessages, static_cast<uint8_t>(type), payload);
}

Result<ByteReader> open(const uint8_t* data, size_t size, VtreesMessageType want,
                        const char* name) {
  return open_message(kVtreesMessages, data, size, static_cast<uint8_t>(want), name);
}

bool valid_widths(const VtreesWidths& w) {
  return w.base_count >= 1 && uint64_t{w.base_count} + w.split_count < 0xffffffffull &&
         w.run_count_bits >= 0 && w.run_count_bits <= 32 && w.run_length_bits >= 0 &&
         w.run_length_bits <= 32 && (w.slot_count == 0) == (w.wedge_count == 0);
}

const char* pairs_problem(const VtreesNodeRecord& r, const VtreesWidths& w) {
  if (!w.has_wedges()) return r.pairs.empty() ? nullptr : "wedge data in a mesh's trees";
  if (r.pairs.size() != vtrees_pair_count(r.run_info)) return "not one wedge pair per fan pair";
  for (const VtreesPairWedge& p : r.pairs) {
    if (p.slot >= w.slot_count) return "a fan pair's face slot out of range";
    if (p.wedge >= w.wedge_count) return "a fan pair's wedge out of range";
  }
  return nullptr;
}

const char* wings_problem(const VtreesItem& it, const VtreesWidths& w) {
  for (const VtreesWing& g : it.wings) {
    if (!w.has_wedges() || !g.present) {
      if (!(g == VtreesWing())) return "wing data where there is none";
      continue;
    }
    if (g.slot >= w.slot_count) return "a wing's face slot out of range";
    if (g.wedge >= w.wedge_count) return "a wing's wedge out of range";
    uint32_t above = it.left.vid;
    for (const auto& [vertex, wedge] : g.changes) {
      if (vertex >= above) return "a wing's changes do not climb below the split vertex";
      if (wedge >= w.wedge_count) return "a wing change's wedge out of range";
      above = vertex;
    }
  }
  return nullptr;
}

void write_wings(BitWriter* b, const VtreesItem& it, const VtreesWidths& w) {
  if (!w.has_wedges()) return;
  for (const VtreesWing& g : it.wings) {
    b->write(g.present ? 1 : 0, 1);
    if (!g.present) continue;
    b->write(g.slot, w.slot_bits());
    b->write(g.wedge, w.wedge_bits());
    b->write(static_cast<uint32_t>(g.changes.size()), w.id_bits());
    for (const auto& [vertex, wedge] : g.changes) {
      b->write(vertex, w.id_bits());
      b->write(wedge, w.wedge_bits());
    }
  }
}

bool read_wings(BitReader* b, uint64_t total_bits, VtreesItem* it, const VtreesWidths& w) {
  if (!w.has_wedges()) return true;
  for (VtreesWing& g : it->wings) {
    uint32_t present = 0;
    if (!b->read(1, &present)) return false;
    g.present = present != 0;
    if (!g.present) continue;
    uint32_t count = 0;
    if (!b->read(w.slot_bits(), &g.slot) || !b->read(w.wedge_bits(), &g.wedge) ||
        !b->read(w.id_bits(), &count)) {
      return false;
    }
    // A change takes at least one bit (its vertex when ids have none): bounds the allocation.
    const uint64_t each = std::max(1, w.id_bits() + w.wedge_bits());
    if (uint64_t{count} * each > total_bits - b->bits_consumed()) return false;
    g.changes.resize(count);
    for (auto& [vertex, wedge] : g.changes) {
      if (!b->read(w.id_bits(), &vertex) || !b->read(w.wedge_bits(), &wedge)) return false;
    }
  }
  return true;
}

size_t fan_size(const VtreesNodeRecord& r) {
  return r.fan.size();
}

int trace_count_bits(const VtreesNodeRecord& r) {
  return bits_for_count(uint64_t{fan_size(r)} + 1);
}

int trace_index_bits(const VtreesNodeRecord& r) {
  return bits_for_count(fan_size(r));
}

// What one record must satisfy, wherever it comes from. `existing` bounds
// its fan vertices (the vertices that exist at its node).
const char* record_problem(const VtreesNodeRecord& r, VertexTreeNodeKind kind,
                           const VtreesWidths& w, uint64_t existing) {
  const uint64_t vertices = uint64_t{w.base_count} + w.split_count;
  if (r.vid >= vertices) return "vid out of range";
  if (kind == VertexTreeNodeKind::kLeft && (r.vid < w.base_count || r.pid >= r.vid)) {
    return "a left record's vid is not a split vertex above its pid";
  }
  if (kind != VertexTreeNodeKind::kLeft && r.pid != 0) return "a pid outside a left record";
  if (kind == VertexTreeNodeKind::kRight && r.position != Vec3f{}) {
    return "a right record with a coordinate";
  }
  if (kind == VertexTreeNodeKind::kRight && r.state != 0) return "a right record with a state";
  if (kind != VertexTreeNodeKind::kRight) {
    for (float c : r.position) {
      if (!std::isfinite(c)) return "a coordinate is not finite";
    }
  }
  if (r.state > 1) return "a state other than 0 or 1";
  if (!fits(r.run_info.size(), w.run_count_bits)) return "more runs than the run count bits hold";
  uint64_t total = 0;
  for (uint32_t info : r.run_info) {
    const uint32_t length = info >> 1;
    if (!fits(length, w.run_length_bits)) return "a run longer than the run length bits hold";
    if (length < ((info & 1) ? 3u : 2u)) return "an open run under 2 or a closed run under 3";
    total += length;
  }
  if (total != r.fan.size()) return "run lengths do not add up to the fan";
  if (const char* p = pairs_problem(r, w)) return p;
  for (uint32_t v : r.fan) {
    if (v >= existing) return "a fan vertex that does not exist at the node";
    if (v == r.vid) return "a fan vertex is the node's own";
  }
  if (kind == VertexTreeNodeKind::kBase && !r.traces.empty()) return "a base record with traces";
  for (size_t i = 0; i < r.traces.size(); ++i) {
    const VtreesTrace& t = r.traces[i];
    if (t.index >= r.fan.size() || (i > 0 && t.index <= r.traces[i - 1].index)) {
      return "trace indices do not increase within the fan";
    }
    const uint32_t v = r.fan[t.index];
    if (v < w.base_count || t.parent >= v) return "a trace parent that is not above its vertex";
  }
  return nullptr;
}

uint64_t existing_at(const VtreesWidths& w, VertexTreeNodeKind kind, const VtreesNodeRecord& left) {
  if (kind == VertexTreeNodeKind::kBase) return w.base_count;
  return uint64_t{left.vid} + 1;  // split k's nodes: vertices < B + k + 1
}

void write_record(BitWriter* b, const VtreesNodeRecord& r, VertexTreeNodeKind kind,
                  const VtreesWidths& w) {
  const int id = w.id_bits();
  b->write(r.vid, id);
  if (kind == VertexTreeNodeKind::kLeft) b->write(r.pid, id);
  if (kind != VertexTreeNodeKind::kRight) {
    for (float c : r.position)
      b->write(float_bits(c), 32);
    b->write(r.state, 1);
  }
  b->write(static_cast<uint32_t>(r.run_info.size()), w.run_count_bits);
  size_t at = 0;
  for (uint32_t info : r.run_info) {
    b->write(info & 1, 1);
    b->write(info >> 1, w.run_length_bits);
    for (uint32_t k = 0; k < (info >> 1); ++k)
      b->write(r.fan[at++], id);
  }
  if (w.has_wedges()) {
    for (const VtreesPairWedge& p : r.pairs) {
      b->write(p.slot, w.slot_bits());
      b->write(p.wedge, w.wedge_bits());
    }
  }
  if (kind == VertexTreeNodeKind::kBase) return;
  b->write(static_cast<uint32_t>(r.traces.size()), trace_count_bits(r));
  for (const VtreesTrace& t : r.traces) {
    b->write(t.index, trace_index_bits(r));
    b->write(t.parent, id);
  }
}

// False when the bits run out (`total_bits`: the stream's size); what the
// fields mean is checked afterwards (record_problem()).
bool read_record(BitReader* b, uint64_t total_bits, VtreesNodeRecord* r, VertexTreeNodeKind kind,
                 const VtreesWidths& w) {
  auto remaining = [&] { return total_bits - b->bits_consumed(); };
  const int id = w.id_bits();
  if (!b->read(id, &r->vid)) return false;
  if (kind == VertexTreeNodeKind::kLeft && !b->read(id, &r->pid)) return false;
  if (kind != VertexTreeNodeKind::kRight) {
    for (float& c : r->position) {
      uint32_t u = 0;
      if (!b->read(32, &u)) return false;
      c = bits_float(u);
    }
    uint32_t state = 0;
    if (!b->read(1, &state)) return false;
    r->state = static_cast<uint8_t>(state);
  }
  uint32_t runs = 0;
  if (!b->read(w.run_count_bits, &runs)) return false;
  // Each run takes at least its closed bit: bounds the allocation.
  if (runs > remaining()) return false;
  r->run_info.resize(runs);
  for (uint32_t& info : r->run_info) {
    uint32_t closed = 0, length = 0;
    if (!b->read(1, &closed) || !b->read(w.run_length_bits, &length)) return false;
    if (length > 0x7fffffffu) return false;
    info = length << 1 | closed;
    if (id == 0 ? length != 0 : uint64_t{length} * id > remaining()) return false;
    for (uint32_t k = 0; k < length; ++k) {
      uint32_t v = 0;
      if (!b->read(id, &v)) return false;
      r->fan.push_back(v);
    }
  }
  if (w.has_wedges()) {
    const size_t pairs = vtrees_pair_count(r->run_info);
    // A pair takes at least a bit when the counts are over 1; else none to read.
    if (w.slot_bits() + w.wedge_bits() > 0 && pairs > remaining()) return false;
    r->pairs.resize(pairs);
    for (VtreesPairWedge& p : r->pairs) {
      if (!b->read(w.slot_bits(), &p.slot) || !b->read(w.wedge_bits(), &p.wedge)) return false;
    }
  }
  if (kind == VertexTreeNodeKind::kBase) return true;
  uint32_t traces = 0;
  if (!b->read(trace_count_bits(*r), &traces)) return false;
  if (traces > r->fan.size()) return false;  // refused later as non-increasing
  r->traces.resize(traces);
  for (VtreesTrace& t : r->traces) {
    if (!b->read(trace_index_bits(*r), &t.index) || !b->read(id, &t.parent)) return false;
  }
  return true;
}

}  // namespace

int VtreesWidths::id_bits() const {
  return bits_for_count(uint64_t{base_count} + split_count);
}

int VtreesWidths::split_bits() const {
  return bits_for_count(split_count);
}

int VtreesWidths::slot_bits() const {
  return bits_for_count(slot_count);
}

int VtreesWidths::wedge_bits() const {
  return bits_for_count(wedge_count);
}

size_t vtrees_pair_count(const std::vector<uint32_t>& run_info) {
  size_t pairs = 0;
  for (uint32_t info : run_info) {
    const uint32_t length = info >> 1;
    if (length >= 2) pairs += length - 1;
    if ((info & 1) && length > 2) ++pairs;
  }
  return pairs;
}

bool VtreesWidths::operator==(const VtreesWidths& o) const {
  return base_count == o.base_count && split_count == o.split_count &&
         run_count_bits == o.run_count_bits && run_length_bits == o.run_length_bits &&
         slot_count == o.slot_count && wedge_count == o.wedge_count;
}

bool VtreesNodeRecord::operator==(const VtreesNodeRecord& o) const {
  for (int k = 0; k < 3; ++k) {
    if (float_bits(position[k]) != float_bits(o.position[k])) return false;
  }
  return vid == o.vid && pid == o.pid && state == o.state && run_info == o.run_info &&
         fan == o.fan && traces == o.traces && pairs == o.pairs;
}

bool VtreesItem::operator==(const VtreesItem& o) const {
  return kind == o.kind && split == o.split && vertex == o.vertex && parent == o.parent &&
         left == o.left && right == o.right && wings[0] == o.wings[0] && wings[1] == o.wings[1];
}

VtreesWidths vtrees_widths(const VertexTrees& t) {
  VtreesWidths w;
  w.base_count = t.base_vertex_count;
  w.split_count = static_cast<uint32_t>(t.split_count());
  uint32_t max_runs = 0, max_length = 0;
  for (size_t n = 0; n < t.node_count(); ++n)
    max_runs = std::max(max_runs, t.run_offsets[n + 1] - t.run_offsets[n]);
  for (size_t r = 0; r < t.run_count(); ++r)
    max_length = std::max(max_length, t.vertex_offsets[r + 1] - t.vertex_offsets[r]);
  w.run_count_bits = bits_for_count(uint64_t{max_runs} + 1);
  w.run_length_bits = bits_for_count(uint64_t{max_length} + 1);
  return w;
}

VtreesNodeRecord vtrees_node_record(const VertexTrees& t, uint32_t node) {
  VtreesNodeRecord r;
  const VertexTreeNodeKind kind = t.kind(node);
  r.vid = t.node_vertex(node);
  const uint32_t b = t.base_vertex_count;
  if (kind != VertexTreeNodeKind::kRight) {
    r.position = t.positions[r.vid];
    r.state = t.vertex_states[r.vid];
  }
  if (kind == VertexTreeNodeKind::kLeft) r.pid = t.parent_vertex[(node - b) / 2];
  for (uint32_t run = t.run_offsets[node]; run < t.run_offsets[node + 1]; ++run) {
    const uint32_t first = t.vertex_offsets[run], last = t.vertex_offsets[run + 1];
    r.run_info.push_back((last - first) << 1 | (t.run_closed[run] ? 1u : 0u));
    r.fan.insert(r.fan.end(), t.fan_vertices.begin() + first, t.fan_vertices.begin() + last);
  }
  return r;
}

uint64_t vtrees_trace_bits(const VtreesNodeRecord& r, const VtreesWidths& w) {
  return trace_count_bits(r) +
         r.traces.size() * (uint64_t{static_cast<uint32_t>(trace_index_bits(r))} +
                            static_cast<uint32_t>(w.id_bits()));
}

uint64_t vtrees_pair_bits(const VtreesNodeRecord& r, const VtreesWidths& w) {
  if (!w.has_wedges()) return 0;
  return r.pairs.size() * static_cast<uint64_t>(w.slot_bits() + w.wedge_bits());
}

uint64_t vtrees_wing_bits(const VtreesWing (&wings)[2], const VtreesWidths& w) {
  if (!w.has_wedges()) return 0;
  const auto id = static_cast<uint64_t>(w.id_bits());
  const auto wedge = static_cast<uint64_t>(w.wedge_bits());
  uint64_t bits = 0;
  for (const VtreesWing& g : wings) {
    bits += 1;
    if (g.present) {
      bits += static_cast<uint64_t>(w.slot_bits()) + wedge + id + g.changes.size() * (id + wedge);
    }
  }
  return bits;
}

uint64_t vtrees_record_bits(const VtreesNodeRecord& r, VertexTreeNodeKind kind,
                            const VtreesWidths& w) {
  const uint64_t id = static_cast<uint32_t>(w.id_bits());
  uint64_t bits = id + static_cast<uint32_t>(w.run_count_bits);
  if (kind == VertexTreeNodeKind::kLeft) bits += id;
  if (kind != VertexTreeNodeKind::kRight) bits += 96 + 1;
  bits += r.run_info.size() * (1 + uint64_t{static_cast<uint32_t>(w.run_length_bits)}) +
          r.fan.size() * id;
  if (kind != VertexTreeNodeKind::kBase) bits += vtrees_trace_bits(r, w);
  return bits + vtrees_pair_bits(r, w);
}

Result<VtreesMessageType> vtrees_message_type(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(uint8_t type, message_type(kVtreesMessages, data, size));
  return static_cast<VtreesMessageType>(type);
}

Result<Bytes> encode_vtrees_trees(const VtreesTreesMessage& m) {
  const VtreesWidths& w = m.widths;
  if (!valid_widths(w)) return invalid_input("vtrees trees message: bad widths");
  if (m.base.size() != w.base_count) {
    return invalid_input("vtrees trees message: " + std::to_string(m.base.size()) +
                         " base records for " + std::to_string(w.base_count) + " base vertices");
  }
  try {
    Bytes payload;
    ByteWriter bw(&payload);
    bw.write(w.base_count);
    bw.write(w.split_count);
    bw.write(static_cast<uint8_t>(w.run_count_bits));
    bw.write(static_cast<uint8_t>(w.run_length_bits));
    bw.write(static_cast<uint8_t>(w.has_wedges() ? 1 : 0));
    bw.write(uint8_t{0});
    if (w.has_wedges()) {
      bw.write(w.slot_count);
      bw.write(w.wedge_count);
    }
    BitWriter b(&payload);
    for (uint32_t v = 0; v < m.base.size(); ++v) {
      const VtreesNodeRecord& r = m.base[v];
      if (const char* p = record_problem(r, VertexTreeNodeKind::kBase, w, w.base_count)) {
        return invalid_input("vtrees trees message: base record " + std::to_string(v) + ": " + p);
      }
      if (r.vid != v) return invalid_input("vtrees trees message: base records out of order");
      write_record(&b, r, VertexTreeNodeKind::kBase, w);
    }
    b.finish();
    if (payload.size() > kMaxVtreesPayloadBytes) {
      return invalid_input("vtrees trees message: payload over the limit");
    }
    return frame(VtreesMessageType::kTrees, payload);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding the vtrees trees message");
  }
}

Result<VtreesTreesMessage> decode_vtrees_trees(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, VtreesMessageType::kTrees, "trees"));
  VtreesTreesMessage m;
  uint8_t count_bits = 0, length_bits = 0, flags = 0, reserved = 0;
  if (!r.read(&m.widths.base_count) || !r.read(&m.widths.split_count) || !r.read(&count_bits) ||
      !r.read(&length_bits) || !r.read(&flags) || !r.read(&reserved)) {
    return bad("trees message shorter than its 12 fixed bytes");
  }
  if (reserved != 0 || (flags & ~1u) != 0) {
    return bad("unknown flags or nonzero reserved byte in the trees message");
  }
  if (flags & 1) {
    if (!r.read(&m.widths.slot_count) || !r.read(&m.widths.wedge_count)) {
      return bad("trees message with wedges shorter than its 20 fixed bytes");
    }
    if (m.widths.slot_count == 0 || m.widths.wedge_count == 0) {
      return bad("trees message with wedges but no face slot or no wedge");
    }
  }
  m.widths.run_count_bits = count_bits;
  m.widths.run_length_bits = length_bits;
  if (!valid_widths(m.widths)) return bad("bad counts or widths in the trees message");
  const VtreesWidths& w = m.widths;
  // A base record takes at least its vid, 97 bits and its run count.
  const uint64_t min_bits =
      static_cast<uint64_t>(w.id_bits()) + 97 + static_cast<uint64_t>(w.run_count_bits);
  if (uint64_t{w.base_count} * min_bits > uint64_t{r.remaining()} * 8) {
    return bad(std::to_string(w.base_count) + " base records need more bytes than remain");
  }
  try {
    m.base.resize(w.base_count);
    BitReader b(r.current(), r.remaining());
    const uint64_t total_bits = uint64_t{r.remaining()} * 8;
    for (uint32_t v = 0; v < w.base_count; ++v) {
      VtreesNodeRecord& rec = m.base[v];
      const std::string at = "base record " + std::to_string(v) + ": ";
      if (!read_record(&b, total_bits, &rec, VertexTreeNodeKind::kBase, w))
        return bad(at + "truncated");
      if (rec.vid != v) return bad(at + "vid " + std::to_string(rec.vid) + " out of order");
      if (const char* p = record_problem(rec, VertexTreeNodeKind::kBase, w, w.base_count)) {
        return bad(at + p);
      }
    }
    if (b.bytes_consumed() != r.remaining()) return bad("trailing bytes after the base records");
    if (!b.padding_is_zero()) return bad("nonzero padding bits in the trees message");
    return m;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding the vtrees trees message");
  }
}

Result<Bytes> encode_vtrees_frame(const std::vector<VtreesItem>& items, const VtreesWidths& w) {
  if (!valid_widths(w)) return invalid_input("vtrees frame message: bad widths");
  if (items.size() > kMaxVtreesItems) return invalid_input("vtrees frame message: too many items");
  try {
    Bytes payload;
    ByteWriter bw(&payload);
    bw.write(static_cast<uint32_t>(items.size()));
    BitWriter b(&payload);
    const uint64_t vertices = uint64_t{w.base_count} + w.split_count;
    for (size_t i = 0; i < items.size(); ++i) {
      const VtreesItem& it = items[i];
      const std::string at = "vtrees frame message: item " + std::to_string(i) + ": ";
      b.write(static_cast<uint32_t>(it.kind), kVtreesItemTagBits);
      switch (it.kind) {
        case VtreesItemKind::kSplit: {
          if (const char* p = record_problem(it.left, VertexTreeNodeKind::kLeft, w,
                                             existing_at(w, VertexTreeNodeKind::kLeft, it.left))) {
            return invalid_input(at + "left record: " + p);
          }
          if (it.right.vid != it.left.pid) {
            return invalid_input(at + "the right record's vid is not the left's pid");
          }
          if (const char* p = record_problem(it.right, VertexTreeNodeKind::kRight, w,
                                             existing_at(w, VertexTreeNodeKind::kRight, it.left))) {
            return invalid_input(at + "right record: " + p);
          }
          if (const char* p = wings_problem(it, w)) return invalid_input(at + p);
          write_record(&b, it.left, VertexTreeNodeKind::kLeft, w);
          write_record(&b, it.right, VertexTreeNodeKind::kRight, w);
          write_wings(&b, it, w);
          break;
        }
        case VtreesItemKind::kDown:
        case VtreesItemKind::kUp:
          if (it.split >= w.split_count) return invalid_input(at + "split id out of range");
          b.write(it.split, w.split_bits());
          break;
        case VtreesItemKind::kTraceUpdate:
          if (it.vertex >= vertices || it.vertex < w.base_count || it.parent >= it.vertex) {
            return invalid_input(at + "a trace update that is not a split vertex and a parent");
          }
          b.write(it.vertex, w.id_bits());
          b.write(it.parent, w.id_bits());
          break;
        default:
          return invalid_input(at + "unknown kind");
      }
    }
    b.finish();
    if (payload.size() > kMaxVtreesPayloadBytes) {
      return invalid_input("vtrees frame message: payload over the limit");
    }
    return frame(VtreesMessageType::kFrame, payload);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding a vtrees frame message");
  }
}

Result<std::vector<VtreesItem>> decode_vtrees_frame(const uint8_t* data, size_t size,
                                                    const VtreesWidths& w) {
  if (!valid_widths(w)) return invalid_input("vtrees frame message: bad widths");
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, VtreesMessageType::kFrame, "frame"));
  uint32_t count = 0;
  if (!r.read(&count)) return bad("frame message without its item count");
  if (count > kMaxVtreesItems) return bad(std::to_string(count) + " items, over the limit");
  if (uint64_t{count} * kVtreesItemTagBits > uint64_t{r.remaining()} * 8) {
    return bad(std::to_string(count) + " items need more bytes than remain");
  }
  const uint64_t vertices = uint64_t{w.base_count} + w.split_count;
  try {
    std::vector<VtreesItem> items(count);
    BitReader b(r.current(), r.remaining());
    const uint64_t total_bits = uint64_t{r.remaining()} * 8;
    for (size_t i = 0; i < items.size(); ++i) {
      VtreesItem& it = items[i];
      const std::string at = "item " + std::to_string(i) + ": ";
      uint32_t kind = 0;
      if (!b.read(kVtreesItemTagBits, &kind)) return bad(at + "truncated");
      it.kind = static_cast<VtreesItemKind>(kind);
      switch (it.kind) {
        case VtreesItemKind::kSplit: {
          if (!read_record(&b, total_bits, &it.left, VertexTreeNodeKind::kLeft, w)) {
            return bad(at + "truncated left record");
          }
          if (it.left.vid < w.base_count || it.left.vid >= vertices) {
            return bad(at + "a left record's vid is not a split vertex");
          }
          const uint64_t existing = existing_at(w, VertexTreeNodeKind::kLeft, it.left);
          if (const char* p = record_problem(it.left, VertexTreeNodeKind::kLeft, w, existing)) {
            return bad(at + "left record: " + p);
          }
          if (!read_record(&b, total_bits, &it.right, VertexTreeNodeKind::kRight, w)) {
            return bad(at + "truncated right record");
          }
          if (it.right.vid != it.left.pid) return bad(at + "the right vid is not the left's pid");
          if (const char* p = record_problem(it.right, VertexTreeNodeKind::kRight, w, existing)) {
            return bad(at + "right record: " + p);
          }
          if (!read_wings(&b, total_bits, &it, w)) return bad(at + "truncated wings");
          if (const char* p = wings_problem(it, w)) return bad(at + p);
          it.split = it.left.vid - w.base_count;
          break;
        }
        case VtreesItemKind::kDown:
        case VtreesItemKind::kUp:
          if (!b.read(w.split_bits(), &it.split)) return bad(at + "truncated");
          if (it.split >= w.split_count) return bad(at + "split id out of range");
          break;
        case VtreesItemKind::kTraceUpdate:
          if (!b.read(w.id_bits(), &it.vertex) || !b.read(w.id_bits(), &it.parent)) {
            return bad(at + "truncated");
          }
          if (it.vertex >= vertices || it.vertex < w.base_count || it.parent >= it.vertex) {
            return bad(at + "a trace update that is not a split vertex and a parent above it");
          }
          break;
      }
    }
    if (b.bytes_consumed() != r.remaining()) return bad("trailing bytes after the frame items");
    if (!b.padding_is_zero()) return bad("nonzero padding bits in a frame message");
    return items;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory decoding a vtrees frame message");
  }
}

Bytes encode_vtrees_scene(const BoundingSphere& sphere) {
  return frame(VtreesMessageType::kScene, sphere_payload(sphere));
}

Result<BoundingSphere> decode_vtrees_scene(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r, open(data, size, VtreesMessageType::kScene, "scene"));
  return decode_sphere_payload(kVtreesMessages, r);
}

Bytes encode_vtrees_end_of_answer(uint32_t messages) {
  Bytes payload;
  ByteWriter w(&payload);
  w.write(messages);
  return frame(VtreesMessageType::kEndOfAnswer, payload);
}

Result<uint32_t> decode_vtrees_end_of_answer(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ByteReader r,
                           open(data, size, VtreesMessageType::kEndOfAnswer, "end of answer"));
  uint32_t messages = 0;
  if (r.remaining() != 4 || !r.read(&messages)) return bad("end of answer is not 4 payload bytes");
  return messages;
}

}  // namespace lodbake
