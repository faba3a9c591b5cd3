#include "lib/hierarchy/front_wedges.h"

#include <new>
#include <string>
#include <utility>

#include "lib/hierarchy/hierarchy_to_pm.h"

namespace lodbake {

Result<std::vector<uint32_t>> hierarchy_split_order(const VertexHierarchy& h,
                                                    const ProgressiveMesh& pm) {
  std::vector<uint32_t> order;
  LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh own, hierarchy_to_progressive_mesh(h, &order));
  if (own.base.triangles != pm.base.triangles || own.splits.size() != pm.splits.size())
    return invalid_input("the progressive mesh beside VHIE is not the hierarchy's own");
  for (size_t k = 0; k < own.splits.size(); ++k) {
    const VertexSplit& a = own.splits[k];
    const VertexSplit& b = pm.splits[k];
    if (a.vs != b.vs || a.vl != b.vl || a.vr != b.vr)
      return invalid_input("split " + std::to_string(k) +
                           " of the progressive mesh beside VHIE is not the hierarchy's");
  }
  return order;
}

Result<FrontWedges> FrontWedges::create(const VertexHierarchy& h, const ProgressiveMesh& pm,
                                        const PmWedges& wedges) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(std::vector<uint32_t> order, hierarchy_split_order(h, pm));
    LODBAKE_ASSIGN_OR_RETURN(CornerWedges lookup, CornerWedges::create(pm, wedges));
    FrontWedges out(h, std::move(lookup));
    const auto roots = static_cast<uint32_t>(h.root_count());
    out.base_faces_ = static_cast<uint32_t>(pm.base.triangles.size());
    out.pm_vertex_.assign(h.node_count(), kNoVertex);
    out.split_of_node_.assign(h.node_count(), kNoVertex);
    std::vector<uint32_t> node_at(pm.full_vertex_count(), kNoNode);
    for (uint32_t r = 0; r < roots; ++r)
      out.pm_vertex_[r] = node_at[r] = r;
    // (node_at[r] = r: the roots are nodes 0 .. roots - 1 and PM vertices
    // 0 .. roots - 1.)
    uint32_t slot = out.base_faces_;
    for (uint32_t k = 0; k < order.size(); ++k) {
      const uint32_t s = order[k];
      const VertexSplit& split = pm.splits[k];
      const uint32_t left = h.first_child[s];
      out.split_of_node_[s] = k;
      out.first_slot_.push_back(slot);
      slot += (split.vl != kNoVertex ? 1 : 0) + (split.vr != kNoVertex ? 1 : 0);
      out.wing_node_.push_back(split.vl != kNoVertex ? node_at[split.vl] : kNoNode);
      out.wing_node_.push_back(split.vr != kNoVertex ? node_at[split.vr] : kNoNode);
      out.pm_vertex_[left] = out.pm_vertex_[s];
      out.pm_vertex_[left + 1] = roots + k;
      node_at[out.pm_vertex_[s]] = left;
      node_at[roots + k] = left + 1;
    }
    out.added_ = wedges.added;
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory preparing the hierarchy's wedges");
  }
}

uint32_t FrontWedges::slot_of(uint32_t origin, uint32_t* split, int* side) const {
  if (origin < base_faces_) return origin;
  const uint32_t node = (origin - base_faces_) / 2;
  if (node >= split_of_node_.size() || split_of_node_[node] == kNoVertex) return kNoVertex;
  *split = split_of_node_[node];
  *side = static_cast<int>((origin - base_faces_) % 2);
  const bool has_left = added_[*split][0] != kNoVertex;
  if (*side == 0 ? !has_left : added_[*split][3] == kNoVertex) return kNoVertex;
  return first_slot_[*split] + (*side == 1 && has_left ? 1 : 0);
}

uint32_t FrontWedges::wedge(uint32_t origin, uint32_t node) const {
  if (node >= pm_vertex_.size()) return kNoVertex;
  uint32_t split = kNoVertex;
  int side = 0;
  const uint32_t slot = slot_of(origin, &split, &side);
  if (slot == kNoVertex) return kNoVertex;
  const uint32_t found = lookup_.wedge(slot, pm_vertex_[node]);
  if (found != kNoVertex || split == kNoVertex) return found;
  // The wing corner, coarser than the PM ever had it: from its node at the
  // face's creation up to `node`.
  uint32_t wedge = added_[split][side == 0 ? 2 : 5];
  for (uint32_t x = wing_node_[2 * size_t{split} + side]; x != node;) {
    if (x == kNoNode) return kNoVertex;
    const uint32_t parent = h_->parent[x];
    if (parent == kNoNode) return kNoVertex;
    if (x == h_->first_child[parent] + 1) {
      // x (vt) collapses into its sibling (vs): the partners across the
      // edge are the wing faces' corners, (vs, vt, vl) and (vt, vs, vr).
      const std::array<uint32_t, 6>& a = added_[split_of_node_[parent]];
      if (a[0] != kNoVertex && a[1] == wedge) {
        wedge = a[0];
      } else if (a[3] != kNoVertex && a[3] == wedge) {
        wedge = a[4];
      }
    }
    x = parent;
  }
  return wedge;
}

Result<std::vector<std::array<uint32_t, 3>>> FrontWedges::corners(
    const SelectiveRefiner& refiner) const {
  try {
    const std::vector<Triangle> faces = refiner.triangles();
    const std::vector<uint32_t> origins = refiner.face_origins();
    std::vector<std::array<uint32_t, 3>> out(faces.size());
    for (size_t f = 0; f < faces.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        out[f][k] = wedge(origins[f], faces[f][k]);
        if (out[f][k] == kNoVertex)
          return invalid_input("the corner at node " + std::to_string(faces[f][k]) + " of face " +
                               std::to_string(f) + " has no wedge");
      }
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory finding the front's wedges");
  }
}

}  // namespace lodbake
