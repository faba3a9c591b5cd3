// Visible vertex list and triangle selection of To, Lau & Green, section
// 5.2. Fan vertices that are not visible are replaced by their first
// visible ancestor at read time (the paper's server does it before sending;
// here every node is present, so the client does it). The walk up is
// bounded by the tree depth.
#include "lib/vtrees/visible_vertex_list.h"

#include <new>
#include <string>

namespace lodbake {

Result<VisibleVertexList> VisibleVertexList::create(const VertexTrees& trees) {
  try {
    const size_t b = trees.base_vertex_count;
    const size_t splits = trees.split_count();
    const size_t vertices = b + splits;
    const size_t nodes = trees.node_count();
    if (vertices >= kNoVertex) return invalid_input("vertex trees have too many vertices");
    if (trees.run_offsets.size() != nodes + 1 || trees.run_offsets[0] != 0 ||
        trees.run_offsets.back() != trees.run_count() ||
        trees.vertex_offsets.size() != trees.run_count() + 1 || trees.vertex_offsets[0] != 0 ||
        trees.vertex_offsets.back() != trees.fan_vertices.size()) {
      return invalid_input("vertex tree fan offsets do not span the fan arrays");
    }
    for (size_t n = 0; n < nodes; ++n) {
      if (trees.run_offsets[n + 1] < trees.run_offsets[n]) {
        return invalid_input("vertex tree fan offsets decrease at node " + std::to_string(n));
      }
    }
    for (size_t r = 0; r < trees.run_count(); ++r) {
      if (trees.vertex_offsets[r + 1] < trees.vertex_offsets[r]) {
        return invalid_input("vertex tree fan offsets decrease at run " + std::to_string(r));
      }
    }
    for (uint32_t v : trees.fan_vertices) {
      if (v >= vertices) {
        return invalid_input("vertex tree fan vertex " + std::to_string(v) + " out of range (" +
                             std::to_string(vertices) + " vertices)");
      }
    }
    VisibleVertexList list(trees);
    std::vector<uint32_t> current(vertices, kNoVertex);
    for (size_t v = 0; v < b; ++v)
      current[v] = static_cast<uint32_t>(v);
    list.parent_node_.resize(splits);
    for (size_t k = 0; k < splits; ++k) {
      const uint32_t vs = trees.parent_vertex[k];
      if (vs >= b + k) {
        return invalid_input("vertex tree split " + std::to_string(k) + ": parent vertex " +
                             std::to_string(vs) + " does not exist yet");
      }
      list.parent_node_[k] = current[vs];
      current[vs] = static_cast<uint32_t>(b + 2 * k + 1);
      current[b + k] = static_cast<uint32_t>(b + 2 * k);
    }
    list.visible_.assign(vertices, kNoVertex);
    for (size_t v = 0; v < b; ++v)
      list.visible_[v] = static_cast<uint32_t>(v);
    list.visible_count_ = b;
    return list;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while setting up the visible vertex list");
  }
}

bool VisibleVertexList::can_split(uint32_t split) const {
  return split < parent_node_.size() &&
         visible_[trees_->parent_vertex[split]] == parent_node_[split];
}

bool VisibleVertexList::can_collapse(uint32_t split) const {
  if (split >= parent_node_.size()) return false;
  const uint32_t b = trees_->base_vertex_count;
  return visible_[b + split] == b + 2 * split &&
         visible_[trees_->parent_vertex[split]] == b + 2 * split + 1;
}

Status VisibleVertexList::split(uint32_t split) {
  if (!can_split(split)) {
    return invalid_input("split " + std::to_string(split) + ": its parent node is not visible");
  }
  const uint32_t b = trees_->base_vertex_count;
  visible_[trees_->parent_vertex[split]] = b + 2 * split + 1;
  visible_[b + split] = b + 2 * split;
  ++visible_count_;
  return Status::ok();
}

Status VisibleVertexList::collapse(uint32_t split) {
  if (!can_collapse(split)) {
    return invalid_input("split " + std::to_string(split) + ": its children are not both visible");
  }
  const uint32_t b = trees_->base_vertex_count;
  visible_[trees_->parent_vertex[split]] = parent_node_[split];
  visible_[b + split] = kNoVertex;
  --visible_count_;
  return Status::ok();
}

uint32_t VisibleVertexList::vertex_state(uint32_t node) const {
  const uint32_t b = trees_->base_vertex_count;
  const uint32_t splits = static_cast<uint32_t>(trees_->split_count());
  if (node < b) return splits;
  return splits - 1 - (node - b) / 2;
}

uint64_t VisibleVertexList::selection_key(uint32_t node) const {
  const uint32_t b = trees_->base_vertex_count;
  // State first; the left child (even offset) before the right; among base
  // nodes the larger vertex id first.
  if (node < b) return (uint64_t{vertex_state(node)} << 33) | (b - 1 - node);
  return (uint64_t{vertex_state(node)} << 33) | ((node - b) % 2);
}

uint32_t VisibleVertexList::visible_ancestor(uint32_t vertex) const {
  const uint32_t b = trees_->base_vertex_count;
  while (visible_[vertex] == kNoVertex)
    vertex = trees_->parent_vertex[vertex - b];  // only split vertices can be invisible
  return vertex;
}

std::vector<Triangle> VisibleVertexList::triangles() const {
  std::vector<Triangle> out;
  const VertexTrees& t = *trees_;
  auto consider = [&](uint32_t v, uint64_t key, uint32_t a, uint32_t c) {
    a = visible_ancestor(a);
    c = visible_ancestor(c);
    if (a == v || c == v || a == c) return;  // degenerate
    if (selection_key(visible_[a]) < key || selection_key(visible_[c]) < key) return;
    out.push_back({v, a, c});
  };
  for (uint32_t v = 0; v < visible_.size(); ++v) {
    const uint32_t node = visible_[v];
    if (node == kNoVertex) continue;
    const uint64_t key = selection_key(node);
    for (uint32_t r = t.run_offsets[node]; r < t.run_offsets[node + 1]; ++r) {
      const uint32_t* fan = t.fan_vertices.data() + t.vertex_offsets[r];
      const uint32_t len = t.vertex_offsets[r + 1] - t.vertex_offsets[r];
      // Clockwise neighbours c_j, c_j+1 make the counter-clockwise (v, c_j+1, c_j).
      for (uint32_t j = 0; j + 1 < len; ++j)
        consider(v, key, fan[j + 1], fan[j]);
      if (t.run_closed[r] && len > 2) consider(v, key, fan[0], fan[len - 1]);
    }
  }
  return out;
}

}  // namespace lodbake
