// Truly selective refinement (Kim & Lee 2001; Kim, Lee and Kobbelt 2005,
// sections 4 and 5.3). Choices where the papers are vague:
// - the split of vs into (left, right) with cut vertices cl = AA(v^l),
//   cr = AA(v^r) is Hoppe's vsplit in lodbake's progressive-mesh convention
//   (formats/mesh/progressive_mesh.h): the faces around vs counter-clockwise
//   from (vs, cr, .) to (vs, ., cl) go to the right child, the others stay
//   with the left one, and (left, right, cl), (right, left, cr) appear. With
//   one wing missing the walk runs from the wing to the boundary. Both
//   wings present and the walk meeting the boundary first is refused (the
//   builder never removes a boundary vertex across an interior edge);
// - ecol is legal when the result is again a valid mesh: the wing faces are
//   there, the link condition holds, no interior edge joins two boundary
//   vertices, and every vertex keeps three faces (one on a boundary) - the
//   builder's own rules, so every front it passed through stays reachable;
// - ActiveAncestor climbs parent indices, which is the right shift of the
//   heap id; active_ancestor_id() does the shifts on ids alone, for clients
//   that hold only <tree-id, node-id> (the tests check both agree);
// - SelStreamVSplit's recursion runs on an explicit stack bounded by the node
//   count, so a malformed hierarchy cannot overflow the call stack or loop.
#include "lib/hierarchy/selective_refiner.h"

#include <algorithm>

#include "formats/sections/vhie.h"
#include "lib/simplify/split_fan.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {

Result<SelectiveRefiner> SelectiveRefiner::create(const VertexHierarchy& h) {
  const std::vector<std::string> problems = validate_hierarchy(h);
  if (!problems.empty()) return invalid_input("vertex hierarchy: " + problems.front());
  SelectiveRefiner r(h);
  const size_t n = h.node_count();
  r.ids_ = hierarchy_node_ids(h);
  r.id_index_.reserve(n);
  for (uint32_t i = 0; i < n; ++i)
    r.id_index_.emplace_back(r.ids_[i], i);
  std::sort(r.id_index_.begin(), r.id_index_.end());
  LODBAKE_RETURN_IF_ERROR(r.start_at_base());
  return r;
}

Result<SelectiveRefiner> SelectiveRefiner::create_by_index(const VertexHierarchy& h) {
  const std::vector<std::string> problems = validate_hierarchy(h);
  if (!problems.empty()) return invalid_input("vertex hierarchy: " + problems.front());
  SelectiveRefiner r(h);
  LODBAKE_RETURN_IF_ERROR(r.start_at_base());
  return r;
}

Result<SelectiveRefiner> SelectiveRefiner::create_growing(const VertexHierarchy& h) {
  const size_t n = h.node_count();
  if (n < h.root_count() || h.first_child.size() != n || h.cut_left.size() != n ||
      h.cut_right.size() != n || h.position.size() != n) {
    return invalid_input("partial vertex hierarchy: arrays of different sizes");
  }
  SelectiveRefiner r(h);
  LODBAKE_RETURN_IF_ERROR(r.start_at_base());
  return r;
}

void SelectiveRefiner::grow() {
  const size_t n = h_->node_count();
  if (n <= active_.size()) return;
  active_.resize(n, 0);
  vertex_faces_.resize(n);
}

Status SelectiveRefiner::start_at_base() {
  const size_t n = h_->node_count();
  active_.assign(n, 0);
  const size_t roots = h_->root_count();
  for (size_t i = 0; i < roots; ++i)
    active_[i] = 1;
  front_size_ = roots;
  vertex_faces_.resize(n);
  for (size_t f = 0; f < h_->base.triangles.size(); ++f) {
    const Triangle& t = h_->base.triangles[f];
    if (t[0] >= roots || t[1] >= roots || t[2] >= roots || t[0] == t[1] || t[1] == t[2] ||
        t[0] == t[2]) {
      return invalid_input("base triangle " + std::to_string(f) +
                           " has an out-of-range or repeated vertex index");
    }
    add_face(t, static_cast<uint32_t>(f));
  }
  return Status::ok();
}

std::vector<uint32_t> SelectiveRefiner::front() const {
  std::vector<uint32_t> out;
  out.reserve(front_size_);
  for (uint32_t i = 0; i < active_.size(); ++i) {
    if (active_[i]) out.push_back(i);
  }
  return out;
}

uint32_t SelectiveRefiner::active_ancestor(uint32_t node) const {
  while (node != kNoNode && !active_[node])
    node = h_->parent[node];
  return node;
}

uint32_t SelectiveRefiner::node_of(HierarchyNodeId id) const {
  auto it = std::lower_bound(
      id_index_.begin(), id_index_.end(), std::make_pair(id, uint32_t{0}),
      [](const std::pair<HierarchyNodeId, uint32_t>& a,
         const std::pair<HierarchyNodeId, uint32_t>& b) { return a.first < b.first; });
  return it != id_index_.end() && it->first == id ? it->second : kNoNode;
}

HierarchyNodeId SelectiveRefiner::active_ancestor_id(HierarchyNodeId id) const {
  for (; id.heap != 0; id.heap >>= 1) {
    const uint32_t node = node_of(id);
    if (node != kNoNode && active_[node]) return id;
  }
  return id;
}

// The shared lookups answer kNoVertex for "none", which is kNoNode.
static_assert(kNoVertex == kNoNode, "face lookups use one 'none' value");

uint32_t SelectiveRefiner::face_with_next(uint32_t v, uint32_t next) const {
  return lodbake::face_with_next(faces_, vertex_faces_, v, next);
}

uint32_t SelectiveRefiner::face_with_prev(uint32_t v, uint32_t prev) const {
  return lodbake::face_with_prev(faces_, vertex_faces_, v, prev);
}

void SelectiveRefiner::neighbours(uint32_t v, std::vector<uint32_t>* out) const {
  out->clear();
  for (uint32_t f : vertex_faces_[v]) {
    const Triangle& t = faces_[f];
    const int k = corner_of(t, v);
    out->push_back(t[(k + 1) % 3]);
    out->push_back(t[(k + 2) % 3]);
  }
  std::sort(out->begin(), out->end());
  out->erase(std::unique(out->begin(), out->end()), out->end());
}

// In a manifold fan an interior vertex has as many neighbours as faces.
bool SelectiveRefiner::is_boundary_vertex(uint32_t v) const {
  std::vector<uint32_t> ring;
  neighbours(v, &ring);
  return ring.size() != vertex_faces_[v].size();
}

uint32_t SelectiveRefiner::add_face(const Triangle& t, uint32_t origin) {
  uint32_t f;
  if (!free_faces_.empty()) {
    f = free_faces_.back();
    free_faces_.pop_back();
    faces_[f] = t;
    face_origin_[f] = origin;
    face_alive_[f] = 1;
  } else {
    f = static_cast<uint32_t>(faces_.size());
    faces_.push_back(t);
    face_origin_.push_back(origin);
    face_alive_.push_back(1);
  }
  for (uint32_t v : t)
    vertex_faces_[v].push_back(f);
  ++live_faces_;
  return f;
}

void SelectiveRefiner::remove_face(uint32_t f) {
  for (uint32_t v : faces_[f]) {
    std::vector<uint32_t>& list = vertex_faces_[v];
    list.erase(std::find(list.begin(), list.end(), f));
  }
  face_alive_[f] = 0;
  free_faces_.push_back(f);
  --live_faces_;
}

// Every face of `from` now names `to` instead; `to` takes over the list.
void SelectiveRefiner::rename(uint32_t from, uint32_t to) {
  for (uint32_t f : vertex_faces_[from]) {
    Triangle& t = faces_[f];
    t[corner_of(t, from)] = to;
  }
  std::vector<uint32_t>& dst = vertex_faces_[to];
  dst.insert(dst.end(), vertex_faces_[from].begin(), vertex_faces_[from].end());
  vertex_faces_[from].clear();
  vertex_faces_[from].shrink_to_fit();
}

bool SelectiveRefiner::plan_split(uint32_t s, SplitPlan* plan, std::string* why) const {
  auto fail = [why](const std::string& reason) {
    if (why != nullptr) *why = reason;
    return false;
  };
  if (s >= active_.size()) return fail("node out of range");
  if (!active_[s]) return fail("node is not on the front");
  if (h_->is_leaf(s)) return fail("node is a leaf");
  const uint32_t l = h_->cut_left[s];
  const uint32_t r = h_->cut_right[s];
  plan->cl = l == kNoNode ? kNoNode : active_ancestor(l);
  plan->cr = r == kNoNode ? kNoNode : active_ancestor(r);
  const uint32_t cl = plan->cl;
  const uint32_t cr = plan->cr;
  if (cl == cr) return fail("both cut vertices have the active ancestor " + std::to_string(cl));
  if (cl == s || cr == s) return fail("a cut vertex's active ancestor is the node itself");
  for (uint32_t w : {cl, cr}) {
    if (w != kNoNode && face_with_next(s, w) == kNoNode && face_with_prev(s, w) == kNoNode) {
      return fail("cut vertex " + std::to_string(w) + " is not adjacent to the node");
    }
  }
  plan->moved.clear();
  const size_t limit = vertex_faces_[s].size();
  if (cr != kNoNode) {
    uint32_t next = cr;
    bool reached = false;
    for (;;) {
      const uint32_t f = face_with_next(s, next);
      if (f == kNoNode) break;
      if (plan->moved.size() >= limit) return fail("the fan around the node does not end");
      plan->moved.push_back(f);
      const Triangle& t = faces_[f];
      next = t[(corner_of(t, s) + 2) % 3];
      if (next == cl) {
        reached = true;
        break;
      }
    }
    if (cl != kNoNode && !reached)
      return fail("the fan from the right to the left cut vertex is open");
  } else {
    uint32_t prev = cl;
    for (;;) {
      const uint32_t f = face_with_prev(s, prev);
      if (f == kNoNode) break;
      if (plan->moved.size() >= limit) return fail("the fan around the node does not end");
      plan->moved.push_back(f);
      const Triangle& t = faces_[f];
      prev = t[(corner_of(t, s) + 1) % 3];
    }
  }
  return true;
}

bool SelectiveRefiner::can_split(uint32_t node, std::string* why) const {
  SplitPlan plan;
  return plan_split(node, &plan, why);
}

Status SelectiveRefiner::split(uint32_t s) {
  SplitPlan plan;
  std::string why;
  if (!plan_split(s, &plan, &why)) {
    return invalid_input("cannot split node " + std::to_string(s) + ": " + why);
  }
  const uint32_t left = h_->first_child[s];
  const uint32_t right = left + 1;
  for (uint32_t f : plan.moved) {
    Triangle& t = faces_[f];
    t[corner_of(t, s)] = right;
    vertex_faces_[right].push_back(f);
    std::vector<uint32_t>& list = vertex_faces_[s];
    list.erase(std::find(list.begin(), list.end(), f));
  }
  rename(s, left);
  active_[s] = 0;
  active_[left] = active_[right] = 1;
  ++front_size_;
  const auto wing = static_cast<uint32_t>(h_->base.triangles.size() + 2 * size_t{s});
  if (plan.cl != kNoNode) add_face({left, right, plan.cl}, wing);
  if (plan.cr != kNoNode) add_face({right, left, plan.cr}, wing + 1);
  return Status::ok();
}

bool SelectiveRefiner::can_collapse(uint32_t s, std::string* why) const {
  uint32_t blocker = kNoNode;
  return check_collapse(s, why, &blocker);
}

bool SelectiveRefiner::check_collapse(uint32_t s, std::string* why, uint32_t* blocker) const {
  auto fail = [why](const std::string& reason) {
    if (why != nullptr) *why = reason;
    return false;
  };
  if (s >= active_.size()) return fail("node out of range");
  if (h_->is_leaf(s)) return fail("node is a leaf");
  const uint32_t left = h_->first_child[s];
  const uint32_t right = left + 1;
  if (!active_[left] || !active_[right]) return fail("its children are not both on the front");
  const uint32_t l = h_->cut_left[s];
  const uint32_t r = h_->cut_right[s];
  const uint32_t cl = l == kNoNode ? kNoNode : active_ancestor(l);
  const uint32_t cr = r == kNoNode ? kNoNode : active_ancestor(r);
  // The faces holding both children must be exactly the wings.
  size_t shared = 0;
  for (uint32_t f : vertex_faces_[left]) {
    const Triangle& t = faces_[f];
    const int k = corner_of(t, left);
    if (t[(k + 1) % 3] == right) {
      if (t[(k + 2) % 3] != cl) return fail("a face on the edge is not the left wing");
      ++shared;
    } else if (t[(k + 2) % 3] == right) {
      if (t[(k + 1) % 3] != cr) return fail("a face on the edge is not the right wing");
      ++shared;
    }
  }
  const size_t wings = (cl != kNoNode ? 1 : 0) + (cr != kNoNode ? 1 : 0);
  if (shared != wings) return fail("the wing faces are not on the front");
  std::vector<uint32_t> ring_left;
  std::vector<uint32_t> ring_right;
  neighbours(left, &ring_left);
  neighbours(right, &ring_right);
  for (uint32_t w : ring_left) {
    if (w == right || w == cl || w == cr) continue;
    if (std::binary_search(ring_right.begin(), ring_right.end(), w)) {
      *blocker = w;
      return fail("the link condition fails at vertex " + std::to_string(w));
    }
  }
  const bool left_boundary = ring_left.size() != vertex_faces_[left].size();
  const bool right_boundary = ring_right.size() != vertex_faces_[right].size();
  if (shared == 2 && left_boundary && right_boundary) {
    return fail("an interior edge joins two boundary vertices");
  }
  const bool boundary_after = left_boundary || right_boundary;
  if (vertex_faces_[left].size() + vertex_faces_[right].size() - 2 * shared <
      (boundary_after ? 1u : 3u)) {
    return fail("the merged vertex would keep too few faces");
  }
  for (uint32_t w : {cl, cr}) {
    if (w != kNoNode && vertex_faces_[w].size() - 1 < (is_boundary_vertex(w) ? 1u : 3u)) {
      return fail("cut vertex " + std::to_string(w) + " would keep too few faces");
    }
  }
  return true;
}

Status SelectiveRefiner::collapse(uint32_t s) {
  std::string why;
  if (!can_collapse(s, &why)) {
    return invalid_input("cannot collapse node " + std::to_string(s) + ": " + why);
  }
  const uint32_t left = h_->first_child[s];
  const uint32_t right = left + 1;
  std::vector<uint32_t> wing_faces;
  for (uint32_t f : vertex_faces_[left]) {
    const Triangle& t = faces_[f];
    if (t[0] == right || t[1] == right || t[2] == right) wing_faces.push_back(f);
  }
  for (uint32_t f : wing_faces)
    remove_face(f);
  rename(right, s);
  rename(left, s);
  active_[left] = active_[right] = 0;
  active_[s] = 1;
  --front_size_;
  return Status::ok();
}

Status SelectiveRefiner::split_with_dependencies(uint32_t node, std::vector<uint32_t>* made) {
  if (node >= active_.size() || !active_[node]) {
    return invalid_input("cannot split node " + std::to_string(node) + ": not on the front");
  }
  std::vector<uint32_t> stack{node};
  size_t steps = 0;
  while (!stack.empty()) {
    if (++steps > 4 * active_.size() + 4) {
      return invalid_input("the split order of node " + std::to_string(node) + " does not end");
    }
    const uint32_t s = stack.back();
    if (h_->is_leaf(s)) {
      return invalid_input("cannot split node " + std::to_string(s) + ": node is a leaf");
    }
    const uint32_t l = h_->cut_left[s];
    const uint32_t r = h_->cut_right[s];
    const uint32_t cl = l == kNoNode ? kNoNode : active_ancestor(l);
    const uint32_t cr = r == kNoNode ? kNoNode : active_ancestor(r);
    if (cl == cr && cl != kNoNode) {
      stack.push_back(cl);
      continue;
    }
    LODBAKE_RETURN_IF_ERROR(split(s));
    if (made != nullptr) made->push_back(s);
    stack.pop_back();
  }
  return Status::ok();
}

Status SelectiveRefiner::collapse_to_base() {
  const size_t roots = h_->root_count();
  for (bool progress = true; progress && front_size_ > roots;) {
    progress = false;
    for (uint32_t s = static_cast<uint32_t>(active_.size()); s-- > 0;) {
      if (!h_->is_leaf(s) && can_collapse(s)) {
        LODBAKE_RETURN_IF_ERROR(collapse(s));
        progress = true;
      }
    }
  }
  if (front_size_ == roots) return Status::ok();
  // Blocked: go through the full mesh, where a known legal sequence starts.
  for (uint32_t s = 0; s < active_.size(); ++s) {
    if (active_[s] && !h_->is_leaf(s)) LODBAKE_RETURN_IF_ERROR(split_with_dependencies(s));
  }
  LODBAKE_ASSIGN_OR_RETURN(SelectiveRefiner fresh, create(*h_));
  std::vector<uint32_t> order;
  for (uint32_t s = 0; s < active_.size(); ++s) {
    if (fresh.active_[s] && !h_->is_leaf(s)) {
      LODBAKE_RETURN_IF_ERROR(fresh.split_with_dependencies(s, &order));
    }
  }
  for (size_t i = order.size(); i-- > 0;)
    LODBAKE_RETURN_IF_ERROR(collapse(order[i]));
  return Status::ok();
}

std::vector<Triangle> SelectiveRefiner::triangles() const {
  std::vector<Triangle> out;
  out.reserve(live_faces_);
  for (size_t f = 0; f < faces_.size(); ++f) {
    if (face_alive_[f]) out.push_back(faces_[f]);
  }
  return out;
}

std::vector<uint32_t> SelectiveRefiner::face_origins() const {
  std::vector<uint32_t> out;
  out.reserve(live_faces_);
  for (size_t f = 0; f < faces_.size(); ++f) {
    if (face_alive_[f]) out.push_back(face_origin_[f]);
  }
  return out;
}

TriangleMesh SelectiveRefiner::current_mesh(std::vector<uint32_t>* vertex_node) const {
  TriangleMesh mesh;
  std::vector<uint32_t> index(active_.size(), kNoNode);
  std::vector<uint32_t> nodes = front();
  for (uint32_t i = 0; i < nodes.size(); ++i) {
    index[nodes[i]] = i;
    mesh.positions.push_back(h_->position[nodes[i]]);
  }
  for (const Triangle& t : triangles())
    mesh.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
  if (vertex_node != nullptr) *vertex_node = std::move(nodes);
  return mesh;
}

}  // namespace lodbake
