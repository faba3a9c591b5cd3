// The streaming client (Kim, Lee and Kobbelt 2005, sections 4 and 5.3).
// Choices where the paper is vague:
// - the partial hierarchy is a VertexHierarchy in arrival order (roots,
//   then each packet's two children, left first), so parents come before
//   children and lib/hierarchy's SelectiveRefiner runs on it unchanged
//   (SelectiveRefiner::create_growing);
// - a fundamental cut vertex is a leaf the client usually does not hold.
//   ActiveAncestor is "right-shift the heap id until the node is active";
//   the client keeps, for each cut vertex, the deepest node it holds on
//   that path (found by right shifts in a hash map of ids) and moves the
//   reference one level down whenever that node's children arrive. That
//   node is always a leaf of the partial hierarchy, so the front crosses
//   the path at it or above, and climbing parents from it is ActiveAncestor
//   (each reference moves at most depth times in a session);
// - the adapt loop is lib/hierarchy's adapt_to_view with one difference:
//   an active node qrefine() wants split whose children have not arrived
//   is counted as missing (the paper's StreamViewingInfo()); the caller
//   then sends its view once and adapts again;
// - a node is a real leaf when its parent's packet (or the base message)
//   says so; qrefine() is never asked about it, so the client never asks
//   for it.
#include "lib/replay/stream_client.h"

#include <new>
#include <string>

#include "formats/support/bit_packing.h"

namespace lodbake {
namespace {

// a is b or an ancestor of b (same tree, a's heap id a prefix of b's).
bool is_prefix(const HierarchyNodeId& a, const HierarchyNodeId& b) {
  const int wa = bit_width(a.heap), wb = bit_width(b.heap);
  return a.tree == b.tree && wa <= wb && (b.heap >> (wb - wa)) == a.heap;
}

NodeRefinement node_refinement(const StreamNodeData& d) {
  return d.internal ? dequantize_refinement(d.record) : NodeRefinement();
}

}  // namespace

Result<StreamClient> StreamClient::create(const uint8_t* base_message, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(BaseMessage base, decode_base_message(base_message, size));
  try {
    StreamClient c;
    const auto roots = static_cast<uint32_t>(base.mesh.positions.size());
    c.roots_ = roots;
    c.widths_.tree_bits = bits_for_count(roots);
    c.widths_.node_bits = base.node_bits;
    if (base.wedge_count != 0) {
      c.widths_.wedges = base.wedge_count;
      c.widths_.base_faces = static_cast<uint32_t>(base.mesh.triangles.size());
      LODBAKE_RETURN_IF_ERROR(c.corner_wedges_.add_base(base.mesh.triangles, base.corners));
    }
    c.h_ = std::make_unique<VertexHierarchy>();
    VertexHierarchy& h = *c.h_;
    h.position = base.mesh.positions;
    h.base.positions = std::move(base.mesh.positions);
    h.base.triangles = std::move(base.mesh.triangles);
    h.parent.assign(roots, kNoNode);
    h.first_child.assign(roots, kNoNode);
    h.cut_left.assign(roots, kNoNode);
    h.cut_right.assign(roots, kNoNode);
    h.input_vertex.assign(roots, kNoVertex);
    h.error.assign(roots, 0.0f);
    for (uint32_t r = 0; r < roots; ++r) {
      c.ids_.push_back({r, 1});
      c.index_.emplace(HierarchyNodeId{r, 1}, r);
      c.data_.push_back(node_refinement(base.roots[r]));
      c.internal_.push_back(base.roots[r].internal ? 1 : 0);
    }
    c.cut_ids_.resize(roots);
    c.watchers_.resize(roots);
    LODBAKE_ASSIGN_OR_RETURN(SelectiveRefiner refiner, SelectiveRefiner::create_growing(h));
    c.refiner_ = std::make_unique<SelectiveRefiner>(std::move(refiner));
    return c;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory creating the streaming client");
  }
}

uint32_t StreamClient::find(const HierarchyNodeId& id) const {
  auto it = index_.find(id);
  return it == index_.end() ? kNoNode : it->second;
}

uint32_t StreamClient::deepest_known(const HierarchyNodeId& id) const {
  for (HierarchyNodeId up = id; up.heap != 0; up.heap >>= 1) {
    const uint32_t node = find(up);
    if (node != kNoNode) return node;
  }
  return kNoNode;  // the tree's root is always held: only for a bad tree id
}

void StreamClient::watch(uint32_t node, int side) {
  const uint32_t k = deepest_known(cut_ids_[node][side]);
  (side == 0 ? h_->cut_left : h_->cut_right)[node] = k;
  if (k != kNoNode) watchers_[k].emplace_back(node, side);
}

Status StreamClient::apply(const VsplitPacket& p) {
  const uint32_t s = find(p.vs);
  const std::string at =
      "vsplit packet <" + std::to_string(p.vs.tree) + "," + std::to_string(p.vs.heap) + ">: ";
  if (s == kNoNode) return invalid_input(at + "the client does not hold this node");
  if (h_->first_child[s] != kNoNode) return invalid_input(at + "received twice");
  if (!internal_[s]) return invalid_input(at + "the node is a leaf of the hierarchy");
  if (bit_width(p.vs.heap) >= widths_.node_bits) {
    return invalid_input(at + "its children would be deeper than the hierarchy");
  }
  for (const HierarchyNodeId* cut : {&p.cut_left, &p.cut_right}) {
    if (cut->heap != 0 && (is_prefix(*cut, p.vs) || is_prefix(p.vs, *cut))) {
      return invalid_input(at + "a cut vertex in the node's own subtree or above it");
    }
  }
  if (has_wedges()) {
    Status wedges = corner_wedges_.add_split(p);
    if (!wedges.is_ok()) return invalid_input(at + wedges.message());
  }
  VertexHierarchy& h = *h_;
  const auto left = static_cast<uint32_t>(h.node_count());
  const HierarchyNodeId child_ids[2] = {{p.vs.tree, p.vs.heap * 2}, {p.vs.tree, p.vs.heap * 2 + 1}};
  const Vec3f positions[2] = {h.position[s], p.position};
  const StreamNodeData* child_data[2] = {&p.left, &p.right};
  for (int k = 0; k < 2; ++k) {
    h.parent.push_back(s);
    h.first_child.push_back(kNoNode);
    h.position.push_back(positions[k]);
    h.cut_left.push_back(kNoNode);
    h.cut_right.push_back(kNoNode);
    h.input_vertex.push_back(kNoVertex);
    h.error.push_back(0.0f);
    ids_.push_back(child_ids[k]);
    index_.emplace(child_ids[k], left + k);
    data_.push_back(node_refinement(*child_data[k]));
    internal_.push_back(child_data[k]->internal ? 1 : 0);
    cut_ids_.emplace_back();
    watchers_.emplace_back();
  }
  h.first_child[s] = left;
  cut_ids_[s] = {p.cut_left, p.cut_right};
  for (int side = 0; side < 2; ++side) {
    if (cut_ids_[s][side].heap != 0) watch(s, side);
  }
  // References that stopped at s move to the child on their path.
  std::vector<std::pair<uint32_t, int>> moving;
  moving.swap(watchers_[s]);
  const int ws = bit_width(p.vs.heap);
  for (const auto& [node, side] : moving) {
    const HierarchyNodeId& target = cut_ids_[node][side];
    const int wt = bit_width(target.heap);
    if (wt <= ws) {  // the cut vertex is s itself: only from a lying server
      watchers_[s].emplace_back(node, side);
      continue;
    }
    const uint32_t child = left + static_cast<uint32_t>((target.heap >> (wt - ws - 1)) & 1);
    (side == 0 ? h.cut_left : h.cut_right)[node] = child;
    watchers_[child].emplace_back(node, side);
  }
  refiner_->grow();
  received_.push_back(p.vs);
  return Status::ok();
}

Status StreamClient::receive(const uint8_t* data, size_t size) {
  LODBAKE_ASSIGN_OR_RETURN(StreamMessageType type, stream_message_type(data, size));
  try {
    if (type == StreamMessageType::kVsplits) {
      LODBAKE_ASSIGN_OR_RETURN(std::vector<VsplitPacket> packets,
                               decode_vsplit_message(data, size, widths_, roots_));
      complete_ = false;
      for (const VsplitPacket& p : packets) {
        LODBAKE_RETURN_IF_ERROR(apply(p));
        ++pending_;
      }
      return Status::ok();
    }
    if (type == StreamMessageType::kEndOfAnswer) {
      LODBAKE_ASSIGN_OR_RETURN(uint32_t count, decode_end_of_answer(data, size));
      if (count != pending_) {
        return invalid_input("end of answer counts " + std::to_string(count) + " packets, " +
                             std::to_string(pending_) + " arrived");
      }
      pending_ = 0;
      complete_ = true;
      return Status::ok();
    }
    return invalid_input("stream message: type " + std::to_string(static_cast<int>(type)) +
                         " is not a downlink message after the base");
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory receiving vsplit packets");
  }
}

Result<Bytes> StreamClient::reconnect() {
  try {
    std::vector<HierarchyNodeId> leaves;
    for (uint32_t v = 0; v < h_->node_count(); ++v) {
      if (h_->is_leaf(v)) leaves.push_back(ids_[v]);
    }
    LODBAKE_ASSIGN_OR_RETURN(Bytes message,
                             encode_resume_message(std::move(leaves), widths_, roots_));
    pending_ = 0;
    complete_ = true;
    return message;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory writing the resume message");
  }
}

WedgeFace StreamClient::face_of(uint32_t origin) const {
  const auto base = static_cast<uint32_t>(h_->base.triangles.size());
  if (origin < base) return {origin, 0, 0};
  const HierarchyNodeId& id = ids_[(origin - base) / 2];
  return {id.tree, id.heap, static_cast<uint8_t>((origin - base) % 2)};
}

Result<std::vector<std::array<uint32_t, 3>>> StreamClient::corner_wedges() const {
  if (!has_wedges()) return invalid_input("the stream carries no wedges");
  try {
    const std::vector<Triangle> faces = refiner_->triangles();
    const std::vector<uint32_t> origins = refiner_->face_origins();
    std::vector<std::array<uint32_t, 3>> out(faces.size());
    for (size_t f = 0; f < faces.size(); ++f) {
      const WedgeFace face = face_of(origins[f]);
      for (int k = 0; k < 3; ++k) {
        out[f][k] = corner_wedges_.wedge(face, ids_[faces[f][k]]);
        if (out[f][k] == kNoVertex)
          return invalid_input("the corner at node <" + std::to_string(ids_[faces[f][k]].tree) +
                               "," + std::to_string(ids_[faces[f][k]].heap) + "> of face " +
                               std::to_string(f) + " has no wedge");
      }
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory finding the client's corner wedges");
  }
}

Result<StreamClientAdapt> StreamClient::adapt(const StreamView& view, size_t max_passes) {
  StreamClientAdapt stats;
  const VertexHierarchy& h = *h_;
  SelectiveRefiner& r = *refiner_;
  const auto n = static_cast<uint32_t>(h.node_count());
  for (bool changed = true; changed && stats.passes < max_passes;) {
    changed = false;
    ++stats.passes;
    stats.missing = 0;
    for (uint32_t v = 0; v < n; ++v) {
      if (!r.is_active(v)) continue;
      if (internal_[v] && stream_qrefine(view, data_[v], h.position[v])) {
        if (h.first_child[v] == kNoNode) {
          ++stats.missing;
          continue;
        }
        std::vector<uint32_t> made;
        LODBAKE_RETURN_IF_ERROR(r.split_with_dependencies(v, &made));
        stats.splits += made.size();
        changed = true;
        continue;
      }
      const uint32_t p = h.parent[v];
      if (p == kNoNode || v != h.first_child[p]) continue;  // each pair once, from its left child
      if (!r.is_active(v + 1) || stream_qrefine(view, data_[p], h.position[p])) continue;
      if (r.can_collapse(p)) {
        LODBAKE_RETURN_IF_ERROR(r.collapse(p));
        ++stats.collapses;
        changed = true;
      }
    }
  }
  return stats;
}

}  // namespace lodbake
