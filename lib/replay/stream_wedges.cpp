// Choices: entries are keyed by the hierarchy's <tree-id, node-id> of the
// face and of the "canonical" node of the corner's vertex (a left child
// keeps its parent's PM vertex, so the key climbs while the heap id is
// even), which the client computes from ids alone, whether or not it holds
// the node; the carried wing wedges change rarely (only where a collapse's
// partner rule applies), so a wing sends the levels where it changes, not
// a wedge per level.
#include "lib/replay/stream_wedges.h"

#include <new>

#include "formats/sections/vhie.h"
#include "formats/support/bit_packing.h"
#include "lib/hierarchy/front_wedges.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/simplify/wedge_replay.h"

namespace lodbake {
namespace {

uint32_t depth_of(const HierarchyNodeId& id) {
  return static_cast<uint32_t>(bit_width(id.heap) - 1);
}

// a is b or an ancestor of b.
bool is_prefix(const HierarchyNodeId& a, const HierarchyNodeId& b) {
  const int wa = bit_width(a.heap), wb = bit_width(b.heap);
  return a.tree == b.tree && wa <= wb && (b.heap >> (wb - wa)) == a.heap;
}

// The node whose PM vertex `id` sits at: the top of its run of left children.
HierarchyNodeId canonical(HierarchyNodeId id) {
  while (id.heap > 1 && id.heap % 2 == 0)
    id.heap >>= 1;
  return id;
}

// FrontWedges' step: vt's corner wedge when vt collapses into vs, from the
// split's added corners (vs, vt, vl) and (vt, vs, vr).
uint32_t carried(const std::array<uint32_t, 6>& a, uint32_t wedge) {
  if (a[0] != kNoVertex && a[1] == wedge) return a[0];
  if (a[3] != kNoVertex && a[3] == wedge) return a[4];
  return wedge;
}

}  // namespace

Result<StreamWedgeTable> stream_wedge_table(const VertexHierarchy& h, const ProgressiveMesh& pm,
                                            const PmWedges& wedges) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(std::vector<uint32_t> order, hierarchy_split_order(h, pm));
    LODBAKE_ASSIGN_OR_RETURN(WedgeRefiner replay, WedgeRefiner::create(pm, wedges));
    const std::vector<HierarchyNodeId> ids = hierarchy_node_ids(h);
    const auto roots = static_cast<uint32_t>(h.root_count());
    StreamWedgeTable out;
    out.wedge_count = static_cast<uint32_t>(wedges.wedge_count());
    out.base = replay.corners();
    out.splits.resize(h.node_count());
    std::vector<WedgeFace> slot_face;
    for (uint32_t f = 0; f < pm.base.triangles.size(); ++f)
      slot_face.push_back({f, 0, 0});
    std::vector<uint32_t> split_of_node(h.node_count(), kNoVertex);
    for (uint32_t k = 0; k < order.size(); ++k)
      split_of_node[order[k]] = k;
    std::vector<uint32_t> node_at(pm.full_vertex_count(), kNoNode);
    for (uint32_t r = 0; r < roots; ++r)
      node_at[r] = r;
    std::vector<uint32_t> pm_vertex(h.node_count(), kNoVertex);
    for (uint32_t r = 0; r < roots; ++r)
      pm_vertex[r] = r;
    for (uint32_t k = 0; k < order.size(); ++k) {
      const uint32_t s = order[k];
      const VertexSplit& split = pm.splits[k];
      VsplitWedges& d = out.splits[s];
      d.added = wedges.added[k];
      const uint32_t cuts[2] = {h.cut_left[s], h.cut_right[s]};
      const uint32_t wings[2] = {split.vl, split.vr};
      for (int side = 0; side < 2; ++side) {
        if (wings[side] == kNoVertex) continue;
        slot_face.push_back({ids[s].tree, ids[s].heap, static_cast<uint8_t>(side)});
        const uint32_t w = node_at[wings[side]];
        if (cuts[side] == kNoNode || w == kNoNode || !is_prefix(ids[w], ids[cuts[side]]))
          return invalid_input("the wing of node " + std::to_string(s) +
                               "'s split is not above its cut vertex");
        WingWedges& wing = d.wings[side];
        wing.lift = depth_of(ids[cuts[side]]) - depth_of(ids[w]);
        uint32_t wedge = d.added[3 * side + 2];
        uint32_t level = 0;
        for (uint32_t x = w; h.parent[x] != kNoNode; x = h.parent[x]) {
          const uint32_t parent = h.parent[x];
          ++level;
          if (x != h.first_child[parent] + 1) continue;
          const uint32_t changed = carried(wedges.added[split_of_node[parent]], wedge);
          if (changed != wedge) wing.changes.emplace_back(level, changed);
          wedge = changed;
        }
      }
      LODBAKE_RETURN_IF_ERROR(replay.split_next());
      const TriangleMesh& m = replay.mesh();
      const auto vt = static_cast<uint32_t>(m.positions.size() - 1);
      const auto [begin, end] = replay.refiner().last_moved_faces();
      for (const uint32_t* f = begin; f != end; ++f) {
        for (int c = 0; c < 3; ++c) {
          if (m.triangles[*f][c] == vt) d.moved.push_back({slot_face[*f], replay.corners()[*f][c]});
        }
      }
      if (slot_face.size() != m.triangles.size())
        return invalid_input("split " + std::to_string(k) + " adds other faces than its wings");
      const uint32_t left = h.first_child[s];
      pm_vertex[left] = pm_vertex[s];
      pm_vertex[left + 1] = roots + k;
      node_at[pm_vertex[s]] = left;
      node_at[roots + k] = left + 1;
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the stream's wedges");
  }
}

Status StreamCornerWedges::put_all(const std::vector<Entry>& entries) {
  // All or nothing: a refused message leaves what earlier ones gave.
  std::map<Key, uint32_t> fresh;
  for (const Entry& e : entries) {
    auto known = lookup_.find(e.first);
    auto [it, added] = fresh.emplace(e.first, e.second);
    if ((known != lookup_.end() && known->second != e.second) || (!added && it->second != e.second))
      return invalid_input("a corner's wedge differs from what an earlier message gave");
  }
  lookup_.insert(fresh.begin(), fresh.end());
  return Status::ok();
}

Status StreamCornerWedges::add_base(const std::vector<Triangle>& triangles,
                                    const std::vector<std::array<uint32_t, 3>>& corners) {
  try {
    if (corners.size() != triangles.size())
      return invalid_input("the base message's corner wedges do not match its triangles");
    std::vector<Entry> entries;
    for (uint32_t f = 0; f < triangles.size(); ++f) {
      for (int c = 0; c < 3; ++c)
        entries.push_back({{{f, 0, 0}, canonical({triangles[f][c], 1})}, corners[f][c]});
    }
    return put_all(entries);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory receiving the base corners' wedges");
  }
}

Status StreamCornerWedges::add_split(const VsplitPacket& p) {
  try {
    const VsplitWedges& d = p.wedges;
    const HierarchyNodeId right{p.vs.tree, p.vs.heap * 2 + 1};
    const HierarchyNodeId cuts[2] = {p.cut_left, p.cut_right};
    std::vector<Entry> entries;
    Wing wings[2];
    auto put = [&](const WedgeFace& face, const HierarchyNodeId& at, uint32_t wedge) {
      entries.push_back({{face, canonical(at)}, wedge});
    };
    for (int side = 0; side < 2; ++side) {
      if (cuts[side].heap == 0) continue;
      const WedgeFace face{p.vs.tree, p.vs.heap, static_cast<uint8_t>(side)};
      const WingWedges& wing = d.wings[side];
      wings[side].w = {cuts[side].tree, cuts[side].heap >> wing.lift};
      wings[side].wedge = d.added[3 * side + 2];
      wings[side].changes = wing.changes;
      // (vs, vt, vl) on the left, (vt, vs, vr) on the right.
      put(face, side == 0 ? p.vs : right, d.added[3 * side]);
      put(face, side == 0 ? right : p.vs, d.added[3 * side + 1]);
      put(face, wings[side].w, wings[side].wedge);
    }
    for (const MovedWedge& m : d.moved)
      put(m.face, right, m.wedge);
    LODBAKE_RETURN_IF_ERROR(put_all(entries));
    for (int side = 0; side < 2; ++side) {
      if (cuts[side].heap != 0)
        wings_[{p.vs.tree, p.vs.heap, static_cast<uint8_t>(side)}] = std::move(wings[side]);
    }
    return Status::ok();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory receiving a split's wedges");
  }
}

uint32_t StreamCornerWedges::wedge(const WedgeFace& face, const HierarchyNodeId& at) const {
  auto found = lookup_.find(std::make_pair(face, canonical(at)));
  if (found != lookup_.end()) return found->second;
  if (face.heap == 0) return kNoVertex;
  auto wing = wings_.find(face);
  if (wing == wings_.end() || !is_prefix(at, wing->second.w)) return kNoVertex;
  const uint32_t level = depth_of(wing->second.w) - depth_of(at);
  uint32_t wedge = wing->second.wedge;
  for (const auto& [from, value] : wing->second.changes) {
    if (level >= from) wedge = value;
  }
  return wedge;
}

}  // namespace lodbake
