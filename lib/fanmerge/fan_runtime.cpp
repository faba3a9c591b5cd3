// Fan-hierarchy runtime (Livny, Sokolovsky & El-Sana 2007, sections 3.4 and
// 4). Choices where the paper is vague:
// - dependencies: the paper prevents fold-overs with El-Sana & Varshney's
//   implicit dependencies; here a step is taken only when the triangles it
//   names are exactly those around the vertex it collapses (so the lists
//   mean what they meant at construction) and the stars of every touched
//   vertex are valid afterwards; otherwise the step is refused and nothing
//   changes. Any mix of partial fine paths reached this way is therefore a
//   valid triangulation, which the tests check globally;
// - a node's centre child and the child being collapsed must be fully
//   merged, and a node is frozen while its parent holds it, so the forest
//   cut stays a cut;
// - optionally (FanRuntimeOptions::construction_dependencies, what the
//   replay uses) the paper's implicit dependencies as exact neighbourhoods:
//   a step also needs every triangle it names to have the corners it had
//   at that step of the construction, recorded by replaying the
//   construction once in create();
// - the active list is a vector of 256-entry blocks (the paper: a linked
//   list of them); the active nodes are the nodes standing for the current
//   vertices: a node with a nonzero pointer replaces its centre child.
#include "lib/fanmerge/fan_runtime.h"

#include <algorithm>
#include <new>

#include "formats/sections/fanh.h"

namespace lodbake {

using fan_internal::has_corner;

void ActiveNodeList::reset(size_t node_count) {
  blocks_.clear();
  position_.assign(node_count, kNoNode);
  size_ = 0;
}

void ActiveNodeList::add(uint32_t node) {
  if (size_ == blocks_.size() * kBlockSize) blocks_.emplace_back();
  at(size_) = node;
  position_[node] = static_cast<uint32_t>(size_);
  ++size_;
}

void ActiveNodeList::remove(uint32_t node) {
  const uint32_t pos = position_[node];
  const uint32_t last = at(size_ - 1);
  at(pos) = last;
  position_[last] = pos;
  position_[node] = kNoNode;
  --size_;
  if (size_ + kBlockSize <= blocks_.size() * kBlockSize) blocks_.pop_back();
}

std::vector<uint32_t> ActiveNodeList::nodes() const {
  std::vector<uint32_t> out;
  out.reserve(size_);
  for (size_t i = 0; i < size_; ++i)
    out.push_back(blocks_[i / kBlockSize][i % kBlockSize]);
  return out;
}

Result<FanRuntime> FanRuntime::create(const TriangleMesh& input, const FanHierarchy& hierarchy,
                                      const FanRuntimeOptions& options) {
  std::vector<std::string> findings = validate_fanh_structure(hierarchy);
  if (!findings.empty()) return invalid_input("fan hierarchy: " + findings.front());
  if (input.vertex_count() != hierarchy.vertex_count ||
      input.triangle_count() != hierarchy.triangle_count)
    return invalid_input("fan hierarchy over " + std::to_string(hierarchy.vertex_count) +
                         " vertices and " + std::to_string(hierarchy.triangle_count) +
                         " triangles, mesh with " + std::to_string(input.vertex_count()) + " and " +
                         std::to_string(input.triangle_count()));
  for (size_t t = 0; t < input.triangles.size(); ++t)
    for (uint32_t v : input.triangles[t])
      if (v >= input.vertex_count())
        return invalid_input("triangle " + std::to_string(t) + " has vertex index " +
                             std::to_string(v) + " out of range");
  try {
    FanRuntime r;
    r.h_ = hierarchy;
    r.base_.positions = input.positions;
    if (input.normals.binding == AttributeBinding::kPerVertex) r.base_.normals = input.normals;
    if (input.texcoords.binding == AttributeBinding::kPerVertex)
      r.base_.texcoords = input.texcoords;
    const uint64_t nodes = hierarchy.node_count();
    r.parent_.assign(nodes, kNoNode);
    r.index_in_parent_.assign(nodes, 0);
    r.vertex_.resize(nodes);
    for (uint32_t v = 0; v < hierarchy.vertex_count; ++v)
      r.vertex_[v] = v;
    for (size_t i = 0; i < hierarchy.internal_count(); ++i) {
      const uint32_t id = static_cast<uint32_t>(hierarchy.vertex_count + i);
      const uint32_t b = hierarchy.child_start[i];
      for (uint32_t j = b; j < hierarchy.child_start[i + 1]; ++j) {
        r.parent_[hierarchy.children[j]] = id;
        r.index_in_parent_[hierarchy.children[j]] = j - b;
      }
      r.vertex_[id] = r.vertex_[hierarchy.children[b]];
    }
    r.pointer_.assign(hierarchy.internal_count(), 0);
    r.state_.init(input);
    r.active_.reset(nodes);
    for (uint32_t v = 0; v < hierarchy.vertex_count; ++v)
      if (r.state_.present(v)) r.active_.add(v);
    if (options.construction_dependencies) {
      // Replay the construction on a copy of the state, recording the
      // corners each step sees; the lists' own checks (can_collapse) run
      // without dependencies, which are not recorded yet.
      r.removed_before_.resize(hierarchy.removed.size());
      r.modified_before_.resize(hierarchy.modified.size());
      const fan_internal::FanMeshState initial = r.state_;
      for (size_t i = 0; i < hierarchy.internal_count(); ++i) {
        const uint32_t id = static_cast<uint32_t>(hierarchy.vertex_count + i);
        for (uint32_t k = 1; k <= r.collapsible_children(id); ++k) {
          if (!r.can_collapse(id, k)) {
            return invalid_input("fan hierarchy: node " + std::to_string(id) + " child " +
                                 std::to_string(k) + " does not replay over the mesh");
          }
          const Lists l = r.lists(id, k);
          const uint32_t ro = r.removed_offset(id, k), mo = r.modified_offset(id, k);
          for (size_t j = 0; j < l.removed_count; ++j)
            r.removed_before_[ro + j] = r.state_.corners(l.removed[j]);
          for (size_t j = 0; j < l.modified_count; ++j)
            r.modified_before_[mo + j] = r.state_.corners(l.modified[j]);
          r.state_.collapse(r.vertex_[r.child(id, k)], r.vertex_[id], l.removed, l.removed_count,
                            l.modified, l.modified_count);
          r.pointer_[i] = k;
        }
      }
      r.state_ = initial;
      r.pointer_.assign(hierarchy.internal_count(), 0);
      r.dependencies_ = true;
    }
    return r;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while loading the fan hierarchy");
  }
}

uint32_t FanRuntime::collapsible_children(uint32_t node) const {
  if (is_leaf(node)) return 0;
  const size_t i = node - h_.vertex_count;
  return h_.child_start[i + 1] - h_.child_start[i] - 1;
}

uint32_t FanRuntime::child(uint32_t node, uint32_t i) const {
  return h_.children[h_.child_start[node - h_.vertex_count] + i];
}

bool FanRuntime::held(uint32_t node) const {
  const uint32_t p = parent_[node];
  if (p == kNoNode) return false;
  const uint32_t index = index_in_parent_[node];
  const uint32_t pointer = merge_pointer(p);
  return index == 0 ? pointer > 0 : pointer >= index;
}

FanRuntime::Lists FanRuntime::lists(uint32_t node, uint32_t k) const {
  const uint32_t j = h_.child_start[node - h_.vertex_count] + k;
  return {h_.removed.data() + h_.removed_start[j], h_.removed_start[j + 1] - h_.removed_start[j],
          h_.modified.data() + h_.modified_start[j],
          h_.modified_start[j + 1] - h_.modified_start[j]};
}

uint32_t FanRuntime::removed_offset(uint32_t node, uint32_t k) const {
  return h_.removed_start[h_.child_start[node - h_.vertex_count] + k];
}

uint32_t FanRuntime::modified_offset(uint32_t node, uint32_t k) const {
  return h_.modified_start[h_.child_start[node - h_.vertex_count] + k];
}

bool FanRuntime::can_collapse(uint32_t node, uint32_t k) const {
  const uint32_t v = vertex_[node];
  const uint32_t c = vertex_[child(node, k)];
  if (!fully_merged(child(node, 0)) || !fully_merged(child(node, k))) return false;
  if (!state_.present(c) || !state_.present(v)) return false;
  const Lists l = lists(node, k);
  if (state_.degree(c) != l.removed_count + l.modified_count) return false;
  for (size_t i = 0; i < l.removed_count; ++i) {
    const uint32_t t = l.removed[i];
    if (!state_.alive(t) || !has_corner(state_.corners(t), c) || !has_corner(state_.corners(t), v))
      return false;
  }
  for (size_t i = 0; i < l.modified_count; ++i) {
    const uint32_t t = l.modified[i];
    if (!state_.alive(t) || !has_corner(state_.corners(t), c) || has_corner(state_.corners(t), v))
      return false;
  }
  if (dependencies_) {
    const uint32_t ro = removed_offset(node, k), mo = modified_offset(node, k);
    for (size_t i = 0; i < l.removed_count; ++i)
      if (state_.corners(l.removed[i]) != removed_before_[ro + i]) return false;
    for (size_t i = 0; i < l.modified_count; ++i)
      if (state_.corners(l.modified[i]) != modified_before_[mo + i]) return false;
  }
  return true;
}

bool FanRuntime::can_split(uint32_t node, uint32_t k) const {
  const uint32_t v = vertex_[node];
  const uint32_t c = vertex_[child(node, k)];
  if (state_.present(c) || !state_.present(v)) return false;
  const Lists l = lists(node, k);
  for (size_t i = 0; i < l.modified_count; ++i) {
    const uint32_t t = l.modified[i];
    if (!state_.alive(t)) return false;
    const Triangle& tri = state_.corners(t);
    if ((tri[0] == v) + (tri[1] == v) + (tri[2] == v) != 1 || has_corner(tri, c)) return false;
  }
  for (size_t i = 0; i < l.removed_count; ++i) {
    const uint32_t t = l.removed[i];
    if (state_.alive(t)) return false;
    const Triangle& tri = state_.corners(t);
    if (!has_corner(tri, c) || !has_corner(tri, v)) return false;
    for (uint32_t x : tri)
      if (x != c && !state_.present(x)) return false;
  }
  if (dependencies_) {
    // After the step: removed triangles died with their corners, modified
    // ones hold v where they held c.
    const uint32_t ro = removed_offset(node, k), mo = modified_offset(node, k);
    for (size_t i = 0; i < l.removed_count; ++i)
      if (state_.corners(l.removed[i]) != removed_before_[ro + i]) return false;
    for (size_t i = 0; i < l.modified_count; ++i) {
      Triangle after = modified_before_[mo + i];
      for (uint32_t& x : after)
        if (x == c) x = v;
      if (state_.corners(l.modified[i]) != after) return false;
    }
  }
  return true;
}

void FanRuntime::apply_collapse(uint32_t node, uint32_t k) {
  const Lists l = lists(node, k);
  const uint32_t c_node = child(node, k);
  state_.collapse(vertex_[c_node], vertex_[node], l.removed, l.removed_count, l.modified,
                  l.modified_count);
  uint32_t& pointer = pointer_[node - h_.vertex_count];
  if (pointer == 0) {
    active_.remove(child(node, 0));
    active_.add(node);
  }
  active_.remove(c_node);
  pointer = k;
}

void FanRuntime::apply_split(uint32_t node, uint32_t k) {
  const Lists l = lists(node, k);
  const uint32_t c_node = child(node, k);
  state_.split(vertex_[c_node], vertex_[node], l.removed, l.removed_count, l.modified,
               l.modified_count);
  uint32_t& pointer = pointer_[node - h_.vertex_count];
  pointer = k - 1;
  active_.add(c_node);
  if (pointer == 0) {
    active_.remove(node);
    active_.add(child(node, 0));
  }
}

void FanRuntime::touch(uint32_t node, uint32_t k) {
  const Lists l = lists(node, k);
  state_.collect_changed(vertex_[child(node, k)], vertex_[node], l.removed, l.removed_count,
                         l.modified, l.modified_count, &touched_);
}

bool FanRuntime::touched_valid() {
  std::sort(touched_.begin(), touched_.end());
  touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
  const bool ok = state_.stars_valid(touched_);
  touched_.clear();
  return ok;
}

bool FanRuntime::run(uint32_t node, uint32_t steps, bool forward, bool check_each) {
  if (node >= node_count() || is_leaf(node) || held(node) || steps == 0) return false;
  const uint32_t start = merge_pointer(node);
  if (forward ? start + steps > collapsible_children(node) : steps > start) return false;
  touched_.clear();
  uint32_t done = 0;
  bool ok = true;
  for (; done < steps; ++done) {
    const uint32_t k = forward ? start + done + 1 : start - done;
    if (!(forward ? can_collapse(node, k) : can_split(node, k))) {
      ok = false;
      break;
    }
    // The changed vertices are collected where c's triangles are apart
    // from v's: before a collapse, after a split.
    if (forward) {
      touch(node, k);
      apply_collapse(node, k);
    } else {
      apply_split(node, k);
      touch(node, k);
    }
    if (check_each && !touched_valid()) {
      ++done;
      ok = false;
      break;
    }
  }
  if (ok && !check_each && !touched_valid()) ok = false;
  if (ok) return true;
  touched_.clear();
  // Undo in reverse: the state before each undone step is the one it left.
  for (uint32_t i = done; i-- > 0;) {
    const uint32_t k = forward ? start + i + 1 : start - i;
    if (forward) {
      apply_split(node, k);
    } else {
      apply_collapse(node, k);
    }
  }
  return false;
}

bool FanRuntime::advance(uint32_t node) {
  return run(node, 1, true, true);
}

bool FanRuntime::retreat(uint32_t node) {
  return run(node, 1, false, true);
}

bool FanRuntime::fan_merge(uint32_t node) {
  if (node >= node_count() || is_leaf(node)) return false;
  return run(node, collapsible_children(node) - merge_pointer(node), true, false);
}

bool FanRuntime::fan_split(uint32_t node) {
  if (node >= node_count() || is_leaf(node)) return false;
  return run(node, merge_pointer(node), false, false);
}

bool FanRuntime::merge_all() {
  bool ok = true;
  for (size_t i = 0; i < h_.internal_count(); ++i) {
    const uint32_t node = static_cast<uint32_t>(h_.vertex_count + i);
    if (!fully_merged(node)) ok = fan_merge(node) && ok;
  }
  return ok;
}

bool FanRuntime::split_all() {
  bool ok = true;
  for (size_t i = h_.internal_count(); i-- > 0;) {
    const uint32_t node = static_cast<uint32_t>(h_.vertex_count + i);
    if (merge_pointer(node) != 0) ok = fan_split(node) && ok;
  }
  return ok;
}

TriangleMesh FanRuntime::mesh() const {
  TriangleMesh out = base_;
  out.triangles = state_.alive_triangles();
  return out;
}

}  // namespace lodbake
