// The server of vertex-tree transmission (To, Lau & Green 2001, section
// 5.1). Choices where the paper is vague:
// - The view criteria are mode vhier's and mode stream's: split k is wanted
//   when qrefine() holds on the refinement data (RFIN) of the hierarchy
//   node it splits, at that node's position: its sphere meets the frustum,
//   its normal cone is not entirely back-facing and its deviation projects
//   over the tolerance (tolerance 0: every split). The trees carry no error
//   of their own; the paper's view clipping (a node's fan sphere in the
//   view region, its normal facing the viewer) is the same test on coarser
//   data.
// - The list moves down only through the trees' parent-child relation (the
//   paper's "minimal dependency"): no neighbour is forced to split. It
//   moves up too, where the view asks for less: the client holds every
//   record it was sent, so moves over held nodes travel as split ids (kDown,
//   kUp) and no record is sent twice.
// - Trace-up: a fan vertex that is not transmitted (below the client's
//   list) is sent with its first transmitted parent the first time a
//   record names it; the server remembers that parent per vertex and, when
//   a nearer parent is transmitted later (a left node on the vertex's path
//   up), sends a trace update so the client always maps the vertex to its
//   nearest held ancestor, as the full trees would.
#include "lib/replay/vtrees_server.h"

#include <algorithm>
#include <iterator>
#include <new>
#include <string>
#include <utility>

#include "formats/sections/vtre.h"
#include "lib/hierarchy/hierarchy_to_pm.h"

namespace lodbake {

Result<VtreesDatabase> VtreesDatabase::create(const VertexTrees& trees, const VertexHierarchy& h,
                                              const std::vector<NodeRefinement>& data) {
  try {
    const std::vector<std::string> findings = validate_vtre(trees);
    if (!findings.empty()) return invalid_input("vertex trees: " + findings.front());
    if (trees.base_vertex_count == 0) return invalid_input("vertex trees without a base vertex");
    if (data.size() != h.node_count()) {
      return invalid_input(std::to_string(data.size()) + " refinement records for " +
                           std::to_string(h.node_count()) + " hierarchy nodes");
    }
    std::vector<uint32_t> node_of_split;
    LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh pm, hierarchy_to_progressive_mesh(h, &node_of_split));
    const uint32_t b = trees.base_vertex_count;
    const size_t splits = trees.split_count();
    bool same = pm.base.vertex_count() == b && pm.splits.size() == splits &&
                trees.positions.size() == b + splits;
    for (uint32_t v = 0; same && v < b; ++v)
      same = pm.base.positions[v] == trees.positions[v];
    for (size_t k = 0; same && k < splits; ++k) {
      same = pm.splits[k].vs == trees.parent_vertex[k] &&
             pm.splits[k].vt_position == trees.positions[b + k];
    }
    if (!same) {
      return invalid_input(
          "the vertex trees are not those of the hierarchy's progressive mesh (VTRE and VHIE "
          "from different builds; rebuild both with lodbake-hierarchy)");
    }
    VtreesDatabase db;
    db.trees = &trees;
    db.widths = vtrees_widths(trees);
    db.sphere = bounding_sphere(h.position);
    db.data.resize(splits);
    db.position.resize(splits);
    for (size_t k = 0; k < splits; ++k) {
      db.data[k] = data[node_of_split[k]];
      db.position[k] = h.position[node_of_split[k]];
    }
    std::vector<uint32_t> current(b + splits, kNoVertex);
    for (uint32_t v = 0; v < b; ++v)
      current[v] = v;
    db.parent_node.resize(splits);
    db.child_split.assign(trees.node_count(), kNoVertex);
    for (uint32_t k = 0; k < splits; ++k) {
      const uint32_t vs = trees.parent_vertex[k];
      db.parent_node[k] = current[vs];
      db.child_split[current[vs]] = k;
      current[vs] = b + 2 * k + 1;
      current[b + k] = b + 2 * k;
    }
    return db;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory setting up the vertex-tree server");
  }
}

Status VtreesDatabase::set_wedges(VtreesWedgeTable table) {
  if (table.pairs.size() != trees->node_count() || table.wings.size() != trees->split_count() ||
      table.slot_count == 0 || table.wedge_count == 0) {
    return invalid_input("the wedge data is not that of these vertex trees");
  }
  widths.slot_count = table.slot_count;
  widths.wedge_count = table.wedge_count;
  wedges = std::move(table);
  return Status::ok();
}

VtreesNodeRecord VtreesDatabase::record(uint32_t node) const {
  VtreesNodeRecord r = vtrees_node_record(*trees, node);
  if (wedges) r.pairs = wedges->pairs[node];
  return r;
}

Result<Bytes> VtreesDatabase::trees_message() const {
  try {
    VtreesTreesMessage m;
    m.widths = widths;
    m.base.reserve(trees->base_vertex_count);
    for (uint32_t v = 0; v < trees->base_vertex_count; ++v)
      m.base.push_back(record(v));
    return encode_vtrees_trees(m);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory encoding the base records");
  }
}

VtreesServerSession::VtreesServerSession(const VtreesDatabase& db, VisibleVertexList list,
                                         size_t max_items)
    : db_(&db), list_(std::move(list)), max_items_(max_items) {}

Result<VtreesServerSession> VtreesServerSession::create(const VtreesDatabase& db,
                                                        size_t max_items_per_message) {
  if (max_items_per_message == 0 || max_items_per_message > kMaxVtreesItems) {
    return invalid_input("items per vtrees message outside 1 .. " +
                         std::to_string(kMaxVtreesItems));
  }
  try {
    LODBAKE_ASSIGN_OR_RETURN(VisibleVertexList list, VisibleVertexList::create(*db.trees));
    VtreesServerSession s(db, std::move(list), max_items_per_message);
    const size_t b = db.trees->base_vertex_count;
    const size_t vertices = b + db.trees->split_count();
    s.transmitted_.assign(vertices, 0);
    s.node_sent_.assign(db.trees->node_count(), 0);
    s.hint_.assign(vertices, kNoVertex);
    s.users_.resize(vertices);
    for (uint32_t v = 0; v < b; ++v) {
      s.transmitted_[v] = 1;
      s.node_sent_[v] = 1;
      s.sent_nodes_.push_back(v);
    }
    return s;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory starting a vertex-tree session");
  }
}

uint32_t VtreesServerSession::first_transmitted(uint32_t vertex) const {
  const uint32_t b = db_->trees->base_vertex_count;
  while (!transmitted_[vertex])
    vertex = db_->trees->parent_vertex[vertex - b];  // base vertices are always transmitted
  return vertex;
}

void VtreesServerSession::add_traces(VtreesNodeRecord* record) {
  for (uint32_t i = 0; i < record->fan.size(); ++i) {
    const uint32_t u = record->fan[i];
    if (transmitted_[u] || hint_[u] != kNoVertex) continue;
    const uint32_t p = first_transmitted(u);
    hint_[u] = p;
    users_[p].push_back(u);
    record->traces.push_back({i, p});
  }
  last_.traces += record->traces.size();
}

void VtreesServerSession::send_split(uint32_t k, std::vector<VtreesItem>* items) {
  const VertexTrees& t = *db_->trees;
  const uint32_t b = t.base_vertex_count;
  const uint32_t vt = b + k, vs = t.parent_vertex[k];
  const uint32_t left = b + 2 * k, right = left + 1;
  transmitted_[vt] = 1;
  node_sent_[left] = node_sent_[right] = 1;
  sent_nodes_.push_back(left);
  sent_nodes_.push_back(right);
  // The vertices whose first transmitted parent was vs and that lie below
  // vt now have vt (only vs's users can: vt's parent is vs).
  std::vector<VtreesItem> updates;
  std::vector<uint32_t>& users = users_[vs];
  size_t keep = 0;
  for (uint32_t u : users) {
    if (transmitted_[u] || hint_[u] != vs) continue;
    uint32_t x = u;
    while (x > vt)
      x = t.parent_vertex[x - b];  // ancestors have smaller ids
    if (x == vt) {
      hint_[u] = vt;
      users_[vt].push_back(u);
      VtreesItem update;
      update.kind = VtreesItemKind::kTraceUpdate;
      update.vertex = u;
      update.parent = vt;
      updates.push_back(std::move(update));
    } else {
      users[keep++] = u;
    }
  }
  users.resize(keep);
  VtreesItem item;
  item.kind = VtreesItemKind::kSplit;
  item.split = k;
  item.left = db_->record(left);
  item.right = db_->record(right);
  if (db_->wedges) {
    item.wings[0] = db_->wedges->wings[k][0];
    item.wings[1] = db_->wedges->wings[k][1];
  }
  add_traces(&item.left);
  add_traces(&item.right);
  items->push_back(std::move(item));
  last_.trace_updates += updates.size();
  for (VtreesItem& u : updates)
    items->push_back(std::move(u));
  ++last_.splits;
}

Result<std::vector<Bytes>> VtreesServerSession::answer(const uint8_t* request, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(ViewRequest decoded, decode_view_request(request, size));
  try {
    const StreamView view = stream_view(decoded);
    const VertexTrees& t = *db_->trees;
    const uint32_t b = t.base_vertex_count;
    const uint32_t splits = static_cast<uint32_t>(t.split_count());
    auto wanted = [&](uint32_t k) { return stream_qrefine(view, db_->data[k], db_->position[k]); };
    last_ = VtreesAnswerStats();
    std::vector<VtreesItem> items;

    // Up: splits whose children are both on the list and not wanted; a
    // collapse may make its parent's split collapsible.
    std::vector<uint32_t> work;
    for (uint32_t k = splits; k-- > 0;) {
      if (list_.can_collapse(k)) work.push_back(k);
    }
    while (!work.empty()) {
      const uint32_t k = work.back();
      work.pop_back();
      if (!list_.can_collapse(k) || wanted(k)) continue;
      LODBAKE_RETURN_IF_ERROR(list_.collapse(k));
      VtreesItem up;
      up.kind = VtreesItemKind::kUp;
      up.split = k;
      items.push_back(std::move(up));
      ++last_.ups;
      const uint32_t parent = db_->parent_node[k];
      if (parent >= b && list_.can_collapse((parent - b) / 2)) work.push_back((parent - b) / 2);
    }

    // Down: visible nodes whose split is wanted, then their children.
    for (uint32_t v = static_cast<uint32_t>(b + splits); v-- > 0;) {
      const uint32_t node = list_.visible_node(v);
      if (node != kNoVertex) work.push_back(node);
    }
    while (!work.empty()) {
      const uint32_t node = work.back();
      work.pop_back();
      const uint32_t k = db_->child_split[node];
      if (k == kNoVertex || !wanted(k)) continue;
      LODBAKE_RETURN_IF_ERROR(list_.split(k));
      if (!node_sent_[b + 2 * k]) {
        send_split(k, &items);
      } else {
        VtreesItem down;
        down.kind = VtreesItemKind::kDown;
        down.split = k;
        items.push_back(std::move(down));
        ++last_.downs;
      }
      work.push_back(b + 2 * k + 1);
      work.push_back(b + 2 * k);
    }

    std::vector<Bytes> out;
    size_t first = 0;
    do {
      const size_t last = std::min(items.size(), first + max_items_);
      const std::vector<VtreesItem> chunk(std::make_move_iterator(items.begin() + first),
                                          std::make_move_iterator(items.begin() + last));
      LODBAKE_ASSIGN_OR_RETURN(Bytes message, encode_vtrees_frame(chunk, db_->widths));
      out.push_back(std::move(message));
      first = last;
    } while (first < items.size());
    last_.messages = out.size();
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory answering a view");
  }
}

size_t VtreesServerSession::state_bytes() const {
  const size_t vertices = transmitted_.size();
  size_t users = 0;
  for (const std::vector<uint32_t>& u : users_)
    users += u.capacity();
  // The list: a visible node per vertex and a parent node per split.
  return vertices * 4 + db_->trees->split_count() * 4 + transmitted_.size() + node_sent_.size() +
         hint_.size() * 4 + users_.size() * sizeof(std::vector<uint32_t>) + users * 4;
}

}  // namespace lodbake
