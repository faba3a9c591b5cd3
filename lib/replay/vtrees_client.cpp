// The client of vertex-tree transmission (To, Lau & Green 2001, section
// 5.2). The trees are rebuilt in arrays sized by the trees message (B + S
// vertices, B + 2S nodes); a split's records fill its two nodes, make its
// parent node the one visible for its parent vertex (the list is at the
// server's, so the node being split is the visible one) and move the list
// down there. Triangle selection is VisibleVertexList's rule with the
// paper's trace-up: a fan vertex the client does not hold is read as the
// first transmitted parent the server sent for it, and then, as every
// vertex, as its first visible ancestor. The paper's third step (reusing
// last frame's list) is not done: the list is rebuilt each time. An
// asset's records name each fan pair's face slot, which gives a triangle
// its corners' wedges (lib/replay/vtrees_wedges.h).
#include "lib/replay/vtrees_client.h"

#include <new>
#include <string>

#include "formats/mesh/progressive_mesh.h"

namespace lodbake {
namespace {

Status refuse(const std::string& detail) {
  return invalid_input("vtrees client: " + detail);
}

}  // namespace

Result<VtreesClient> VtreesClient::create(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(VtreesTreesMessage m, decode_vtrees_trees(data, size));
  try {
    VtreesClient c;
    c.widths_ = m.widths;
    const uint32_t b = m.widths.base_count;
    const size_t splits = m.widths.split_count;
    const size_t vertices = b + splits;
    const size_t nodes = b + 2 * splits;
    c.held_.assign(vertices, 0);
    c.hint_.assign(vertices, kNoVertex);
    c.positions_.assign(vertices, Vec3f{});
    c.states_.assign(vertices, 0);
    c.visible_.assign(vertices, kNoVertex);
    c.parent_vertex_.assign(splits, kNoVertex);
    c.parent_node_.assign(splits, kNoVertex);
    c.split_held_.assign(splits, 0);
    c.child_split_.assign(nodes, kNoVertex);
    c.node_run_.assign(nodes, 0);
    c.node_runs_.assign(nodes, 0);
    for (uint32_t v = 0; v < b; ++v)
      c.held_[v] = 1;
    for (uint32_t v = 0; v < b; ++v) {
      const VtreesNodeRecord& r = m.base[v];
      c.positions_[v] = r.position;
      c.states_[v] = r.state;
      c.visible_[v] = v;
      LODBAKE_RETURN_IF_ERROR(c.store_fan(v, r));
      LODBAKE_RETURN_IF_ERROR(c.wedges_.add_record(v, r));
      c.received_.base_bits += vtrees_record_bits(r, VertexTreeNodeKind::kBase, c.widths_);
      c.received_.base_wedge_bits += vtrees_pair_bits(r, c.widths_);
    }
    c.visible_count_ = b;
    c.received_.base_records = b;
    c.received_.messages = 1;
    return c;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory starting the vertex-tree client");
  }
}

size_t VtreesClient::nodes_held() const {
  return widths_.base_count + 2 * splits_held_;
}

Status VtreesClient::store_fan(uint32_t node, const VtreesNodeRecord& r) {
  for (const VtreesTrace& t : r.traces) {
    const uint32_t u = r.fan[t.index];
    if (held_[u]) return refuse("a trace for vertex " + std::to_string(u) + ", which it holds");
    if (!held_[t.parent]) {
      return refuse("vertex " + std::to_string(u) + " traced to " + std::to_string(t.parent) +
                    ", which it does not hold");
    }
    hint_[u] = t.parent;
  }
  for (uint32_t u : r.fan) {
    if (!held_[u] && hint_[u] == kNoVertex) {
      return refuse("node " + std::to_string(node) + " names vertex " + std::to_string(u) +
                    " without a trace-up");
    }
  }
  node_run_[node] = static_cast<uint32_t>(runs_.size());
  node_runs_[node] = static_cast<uint32_t>(r.run_info.size());
  uint32_t at = static_cast<uint32_t>(fan_.size());
  uint32_t pair = static_cast<uint32_t>(pair_slot_.size());
  for (uint32_t info : r.run_info) {
    runs_.push_back(info);
    run_start_.push_back(at);
    at += info >> 1;
    if (widths_.has_wedges()) {
      run_pair_.push_back(pair);
      pair += static_cast<uint32_t>(vtrees_pair_count({info}));
    }
  }
  fan_.insert(fan_.end(), r.fan.begin(), r.fan.end());
  for (const VtreesPairWedge& p : r.pairs)
    pair_slot_.push_back(p.slot);
  return Status::ok();
}

Status VtreesClient::apply(const VtreesItem& it) {
  const uint32_t b = widths_.base_count;
  const uint32_t k = it.split;
  const uint32_t left = b + 2 * k, right = left + 1;
  switch (it.kind) {
    case VtreesItemKind::kSplit: {
      const uint32_t vt = b + k, vs = it.left.pid;
      if (split_held_[k]) return refuse("the records of split " + std::to_string(k) + " twice");
      if (!held_[vs] || visible_[vs] == kNoVertex) {
        return refuse("split " + std::to_string(k) + ": parent vertex " + std::to_string(vs) +
                      " is not on the visible vertex list");
      }
      const uint32_t parent = visible_[vs];
      if (child_split_[parent] != kNoVertex) {
        return refuse("split " + std::to_string(k) + ": node " + std::to_string(parent) +
                      " already has children");
      }
      held_[vt] = 1;
      positions_[vt] = it.left.position;
      states_[vt] = it.left.state;
      parent_vertex_[k] = vs;
      parent_node_[k] = parent;
      child_split_[parent] = k;
      split_held_[k] = 1;
      ++splits_held_;
      LODBAKE_RETURN_IF_ERROR(store_fan(left, it.left));
      LODBAKE_RETURN_IF_ERROR(store_fan(right, it.right));
      LODBAKE_RETURN_IF_ERROR(wedges_.add_record(vt, it.left));
      LODBAKE_RETURN_IF_ERROR(wedges_.add_record(vs, it.right));
      LODBAKE_RETURN_IF_ERROR(wedges_.add_wings(it.wings));
      received_.split_wedge_bits += vtrees_pair_bits(it.left, widths_) +
                                    vtrees_pair_bits(it.right, widths_) +
                                    vtrees_wing_bits(it.wings, widths_);
      visible_[vs] = right;
      visible_[vt] = left;
      ++visible_count_;
      ++received_.left_records;
      ++received_.right_records;
      received_.left_bits += vtrees_record_bits(it.left, VertexTreeNodeKind::kLeft, widths_);
      received_.right_bits += vtrees_record_bits(it.right, VertexTreeNodeKind::kRight, widths_);
      received_.traces += it.left.traces.size() + it.right.traces.size();
      received_.trace_bits +=
          vtrees_trace_bits(it.left, widths_) + vtrees_trace_bits(it.right, widths_);
      return Status::ok();
    }
    case VtreesItemKind::kDown:
      if (!split_held_[k] || visible_[parent_vertex_[k]] != parent_node_[k]) {
        return refuse("cannot move down at split " + std::to_string(k));
      }
      visible_[parent_vertex_[k]] = right;
      visible_[b + k] = left;
      ++visible_count_;
      ++received_.downs;
      return Status::ok();
    case VtreesItemKind::kUp:
      if (!split_held_[k] || visible_[b + k] != left || visible_[parent_vertex_[k]] != right) {
        return refuse("cannot move up at split " + std::to_string(k));
      }
      visible_[parent_vertex_[k]] = parent_node_[k];
      visible_[b + k] = kNoVertex;
      --visible_count_;
      ++received_.ups;
      return Status::ok();
    case VtreesItemKind::kTraceUpdate: {
      const uint32_t u = it.vertex, p = it.parent;
      if (held_[u] || hint_[u] == kNoVertex || !held_[p] || p <= hint_[u]) {
        return refuse("a trace update of vertex " + std::to_string(u) + " to " + std::to_string(p) +
                      " that does not bring it nearer");
      }
      hint_[u] = p;
      ++received_.trace_updates;
      return Status::ok();
    }
  }
  return refuse("unknown item kind");
}

Status VtreesClient::receive(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(std::vector<VtreesItem> items, decode_vtrees_frame(data, size, widths_));
  try {
    for (const VtreesItem& it : items)
      LODBAKE_RETURN_IF_ERROR(apply(it));
    ++received_.messages;
    return Status::ok();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory in the vertex-tree client");
  }
}

uint32_t VtreesClient::resolve(uint32_t vertex) const {
  const uint32_t b = widths_.base_count;
  uint32_t x = held_[vertex] ? vertex : hint_[vertex];
  while (visible_[x] == kNoVertex)
    x = parent_vertex_[x - b];  // a held vertex off the list is a split vertex with its parent held
  return x;
}

uint64_t VtreesClient::selection_key(uint32_t node) const {
  const uint32_t b = widths_.base_count;
  const uint64_t s = widths_.split_count;
  if (node < b) return (s << 33) | (b - 1 - node);
  const uint64_t k = (node - b) / 2;
  return ((s - 1 - k) << 33) | ((node - b) % 2);
}

std::vector<Triangle> VtreesClient::triangles() const {
  return triangles(nullptr);
}

std::vector<Triangle> VtreesClient::triangles(std::vector<uint32_t>* slots) const {
  std::vector<Triangle> out;
  const bool with_slots = slots != nullptr && widths_.has_wedges();
  if (slots != nullptr) slots->clear();
  uint32_t pair = 0;  // the pair being considered, in pair_slot_
  auto consider = [&](uint32_t v, uint64_t key, uint32_t a, uint32_t c) {
    const uint32_t slot = with_slots ? pair_slot_[pair] : 0;
    ++pair;
    a = resolve(a);
    c = resolve(c);
    if (a == v || c == v || a == c) return;  // degenerate
    if (selection_key(visible_[a]) < key || selection_key(visible_[c]) < key) return;
    out.push_back({v, a, c});
    if (with_slots) slots->push_back(slot);
  };
  for (uint32_t v = 0; v < visible_.size(); ++v) {
    const uint32_t node = visible_[v];
    if (node == kNoVertex) continue;
    const uint64_t key = selection_key(node);
    for (uint32_t r = node_run_[node]; r < node_run_[node] + node_runs_[node]; ++r) {
      const uint32_t* fan = fan_.data() + run_start_[r];
      const uint32_t len = runs_[r] >> 1;
      if (with_slots) pair = run_pair_[r];
      // Clockwise neighbours c_j, c_j+1 make the counter-clockwise (v, c_j+1, c_j).
      for (uint32_t j = 0; j + 1 < len; ++j)
        consider(v, key, fan[j + 1], fan[j]);
      if ((runs_[r] & 1) && len > 2) consider(v, key, fan[0], fan[len - 1]);
    }
  }
  return out;
}

Result<std::vector<std::array<uint32_t, 3>>> VtreesClient::corner_wedges() const {
  if (!widths_.has_wedges()) return invalid_input("vtrees client: the trees carry no wedges");
  try {
    std::vector<uint32_t> slots;
    const std::vector<Triangle> tris = triangles(&slots);
    std::vector<std::array<uint32_t, 3>> out(tris.size());
    for (size_t f = 0; f < tris.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        out[f][k] = wedges_.wedge(slots[f], tris[f][k]);
        if (out[f][k] == kNoVertex) {
          return refuse("no wedge for face slot " + std::to_string(slots[f]) + " at vertex " +
                        std::to_string(tris[f][k]) + " (triangle " + std::to_string(f) + ")");
        }
      }
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory finding the client's corner wedges");
  }
}

}  // namespace lodbake
