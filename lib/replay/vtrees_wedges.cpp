// Choices: the pairs' face slots are found on the server by replaying the
// progressive mesh (SplitSimulator, whose face slots WedgeRefiner shares)
// to each node's split and matching the fan pair to the face around the
// node's vertex, so VTRE itself stays as it is; every record carries its
// pairs' wedges at its own vertex (a right record repeats what its parent
// node's gave for the faces that did not change: simpler than a moved list
// and the client needs no face order); the carried wing wedges are keyed by
// the ancestor vertex where they change, which the client compares by id.
#include "lib/replay/vtrees_wedges.h"

#include <new>
#include <string>

#include "lib/dag/split_simulator.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/simplify/wedge_replay.h"

namespace lodbake {
namespace {

// FrontWedges' step: vt's corner wedge when vt collapses into vs, from the
// split's added corners (vs, vt, vl) and (vt, vs, vr).
uint32_t carried(const std::array<uint32_t, 6>& a, uint32_t wedge) {
  if (a[0] != kNoVertex && a[1] == wedge) return a[0];
  if (a[3] != kNoVertex && a[3] == wedge) return a[4];
  return wedge;
}

uint64_t key(uint32_t slot, uint32_t vertex) {
  return (uint64_t{slot} << 32) | vertex;
}

// Node `node`'s pairs (vertex v) in the simulator's current mesh.
Status node_pairs(const VertexTrees& t, uint32_t node, const SplitSimulator& sim,
                  const WedgeRefiner& replay, std::vector<VtreesPairWedge>* out) {
  const uint32_t v = t.node_vertex(node);
  auto find = [&](uint32_t a, uint32_t c) -> Status {
    for (uint32_t f : sim.faces_of(v)) {
      const Triangle& tri = sim.faces()[f];
      for (int i = 0; i < 3; ++i) {
        if (tri[i] != v || tri[(i + 1) % 3] != a || tri[(i + 2) % 3] != c) continue;
        if (f >= replay.mesh().triangles.size() || replay.mesh().triangles[f] != tri)
          return invalid_input("the wedge replay's face slot " + std::to_string(f) +
                               " is not the trees' progressive mesh's");
        out->push_back({f, replay.corners()[f][i]});
        return Status::ok();
      }
    }
    return invalid_input("node " + std::to_string(node) + "'s fan has a pair without a face in " +
                         "the progressive mesh beside VTRE (VTRE and VSPL from different builds)");
  };
  for (uint32_t r = t.run_offsets[node]; r < t.run_offsets[node + 1]; ++r) {
    const uint32_t* fan = t.fan_vertices.data() + t.vertex_offsets[r];
    const uint32_t len = t.vertex_offsets[r + 1] - t.vertex_offsets[r];
    for (uint32_t j = 0; j + 1 < len; ++j)
      LODBAKE_RETURN_IF_ERROR(find(fan[j + 1], fan[j]));
    if (t.run_closed[r] && len > 2) LODBAKE_RETURN_IF_ERROR(find(fan[0], fan[len - 1]));
  }
  return Status::ok();
}

}  // namespace

Result<VtreesWedgeTable> vtrees_wedge_table(const VertexTrees& t, const ProgressiveMesh& pm,
                                            const PmWedges& wedges) {
  try {
    const uint32_t b = t.base_vertex_count;
    const size_t splits = t.split_count();
    if (pm.base.vertex_count() != b || pm.splits.size() != splits)
      return invalid_input("the progressive mesh beside VTRE is not the trees' own");
    for (size_t k = 0; k < splits; ++k) {
      if (pm.splits[k].vs != t.parent_vertex[k])
        return invalid_input("split " + std::to_string(k) +
                             " of the progressive mesh beside VTRE is not the trees'");
    }
    LODBAKE_ASSIGN_OR_RETURN(SplitSimulator sim, SplitSimulator::create(pm));
    LODBAKE_ASSIGN_OR_RETURN(WedgeRefiner replay, WedgeRefiner::create(pm, wedges));
    VtreesWedgeTable out;
    out.wedge_count = static_cast<uint32_t>(wedges.wedge_count());
    out.pairs.resize(t.node_count());
    out.wings.resize(splits);
    out.slot_split.assign(pm.base.triangles.size(), kNoVertex);
    out.slot_side.assign(pm.base.triangles.size(), 0);
    for (uint32_t v = 0; v < b; ++v)
      LODBAKE_RETURN_IF_ERROR(node_pairs(t, v, sim, replay, &out.pairs[v]));
    SplitSimulator::Effect effect;
    for (uint32_t k = 0; k < splits; ++k) {
      LODBAKE_RETURN_IF_ERROR(sim.split_next(&effect));
      LODBAKE_RETURN_IF_ERROR(replay.split_next());
      const uint32_t left = b + 2 * k;
      LODBAKE_RETURN_IF_ERROR(node_pairs(t, left, sim, replay, &out.pairs[left]));
      LODBAKE_RETURN_IF_ERROR(node_pairs(t, left + 1, sim, replay, &out.pairs[left + 1]));
      const VertexSplit& s = pm.splits[k];
      const uint32_t wing_vertex[2] = {s.vl, s.vr};
      size_t added = 0;
      for (int side = 0; side < 2; ++side) {
        if (wing_vertex[side] == kNoVertex) continue;
        if (added >= effect.added.size())
          return invalid_input("split " + std::to_string(k) + " adds fewer faces than its wings");
        VtreesWing& wing = out.wings[k][side];
        wing.present = true;
        wing.slot = effect.added[added++];
        wing.wedge = wedges.added[k][3 * side + 2];
        out.slot_split.push_back(k);
        out.slot_side.push_back(static_cast<uint8_t>(side));
        uint32_t wedge = wing.wedge;
        for (uint32_t y = wing_vertex[side]; y >= b;) {
          const uint32_t up = y - b;
          if (up >= k)
            return invalid_input("a wing vertex of split " + std::to_string(k) +
                                 " that does not exist yet");
          const uint32_t changed = carried(wedges.added[up], wedge);
          y = pm.splits[up].vs;
          if (changed != wedge) wing.changes.emplace_back(y, changed);
          wedge = changed;
        }
      }
      if (added != effect.added.size() || out.slot_split.size() != sim.faces().size())
        return invalid_input("split " + std::to_string(k) + " adds other faces than its wings");
    }
    out.slot_count = static_cast<uint32_t>(sim.faces().size());
    if (out.slot_count == 0 || out.wedge_count == 0)
      return invalid_input("an asset's trees without faces or wedges");
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the vertex trees' wedges");
  }
}

Status VtreesCornerWedges::add_record(uint32_t vertex, const VtreesNodeRecord& record) {
  for (const VtreesPairWedge& p : record.pairs) {
    auto [it, added] = lookup_.emplace(key(p.slot, vertex), p.wedge);
    if (!added && it->second != p.wedge) {
      return invalid_input("vtrees client: face slot " + std::to_string(p.slot) + "'s wedge at " +
                           "vertex " + std::to_string(vertex) +
                           " differs from an earlier record's");
    }
  }
  return Status::ok();
}

Status VtreesCornerWedges::add_wings(const VtreesWing (&wings)[2]) {
  for (const VtreesWing& w : wings) {
    if (!w.present) continue;
    if (!wings_.emplace(w.slot, w).second) {
      return invalid_input("vtrees client: face slot " + std::to_string(w.slot) +
                           " is the wing of two splits");
    }
  }
  return Status::ok();
}

uint32_t VtreesCornerWedges::wedge(uint32_t slot, uint32_t vertex) const {
  auto found = lookup_.find(key(slot, vertex));
  if (found != lookup_.end()) return found->second;
  auto wing = wings_.find(slot);
  if (wing == wings_.end()) return kNoVertex;
  uint32_t wedge = wing->second.wedge;
  for (const auto& [y, value] : wing->second.changes) {
    if (y < vertex) break;  // decreasing: the rest lie above `vertex`
    wedge = value;
  }
  return wedge;
}

Result<VtreesFrontReference> VtreesFrontReference::create(const VertexHierarchy& h,
                                                          const VertexTrees& trees,
                                                          const VtreesWedgeTable& table,
                                                          const FrontWedges& front) {
  try {
    VtreesFrontReference r;
    r.table_ = &table;
    r.front_ = &front;
    r.base_faces_ = static_cast<uint32_t>(h.base.triangles.size());
    LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh pm,
                             hierarchy_to_progressive_mesh(h, &r.node_of_split_));
    if (r.node_of_split_.size() != trees.split_count() ||
        pm.base.vertex_count() != trees.base_vertex_count)
      return invalid_input("the vertex trees are not those of the hierarchy's progressive mesh");
    r.hier_node_.resize(trees.node_count());
    for (uint32_t v = 0; v < trees.base_vertex_count; ++v)
      r.hier_node_[v] = v;  // root v sits at base vertex v
    for (size_t k = 0; k < trees.split_count(); ++k) {
      // The trees' left child is the new vertex: the hierarchy's right child.
      const uint32_t first = h.first_child[r.node_of_split_[k]];
      r.hier_node_[trees.base_vertex_count + 2 * k] = first + 1;
      r.hier_node_[trees.base_vertex_count + 2 * k + 1] = first;
    }
    return r;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the vertex trees' reference wedges");
  }
}

uint32_t VtreesFrontReference::wedge(uint32_t slot, uint32_t node) const {
  if (slot >= table_->slot_split.size() || node >= hier_node_.size()) return kNoVertex;
  const uint32_t k = table_->slot_split[slot];
  const uint32_t origin =
      k == kNoVertex ? slot : base_faces_ + 2 * node_of_split_[k] + table_->slot_side[slot];
  return front_->wedge(origin, hier_node_[node]);
}

}  // namespace lodbake
