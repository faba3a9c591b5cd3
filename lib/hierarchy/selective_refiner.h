// Truly selective refinement of a balanced vertex hierarchy (Kim & Lee
// 2001, as used by Kim, Lee and Kobbelt section 4 and 5.3): a vertex front
// moved up and down by vsplit / ecol, the cut vertices of a split found as
// ActiveAncestor(fundamental cut vertex), and SelStreamVSplit's partial
// order. The current mesh is kept as faces over node indices.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"

namespace lodbake {

class SelectiveRefiner {
 public:
  /// Starts at the base mesh: the roots are the front. Fails when `h` does
  /// not pass validate_hierarchy() (formats/sections/vhie.h) or its base
  /// mesh has an out-of-range or repeated index. `h` must outlive the refiner.
  static Result<SelectiveRefiner> create(const VertexHierarchy& h);
  /// create() without the <tree-id, node-id> lookups: id_of(), node_of()
  /// and active_ancestor_id() must not be called. For a caller that works on
  /// node indices (hierarchy_to_progressive_mesh()), without the ids and
  /// their sorted index (40 bytes a node).
  static Result<SelectiveRefiner> create_by_index(const VertexHierarchy& h);
  /// A refiner over a hierarchy that grows while it is refined: a streaming
  /// client's partial hierarchy (lib/replay/stream_client.h). Only the base
  /// mesh and the array sizes are checked. Nodes the owner appends to `h`
  /// later (a pair of children after their parent, parent[] and
  /// first_child[] set) are taken in by grow(). cut_left / cut_right may
  /// name any node on the path from the fundamental cut vertex to its root
  /// that is not above the front: ActiveAncestor climbs from there. The
  /// <tree-id, node-id> functions (id_of, node_of, active_ancestor_id) and
  /// collapse_to_base() need a complete hierarchy (create()).
  static Result<SelectiveRefiner> create_growing(const VertexHierarchy& h);
  /// Extends the per-node state to the hierarchy's node count (new nodes
  /// inactive, without faces).
  void grow();

  bool is_active(uint32_t node) const { return active_[node] != 0; }
  /// Nodes of the front (the current mesh's vertices), ascending.
  std::vector<uint32_t> front() const;
  size_t front_size() const { return front_size_; }
  size_t triangle_count() const { return live_faces_; }

  /// ActiveAncestor(node): the active node on the path from `node` to its
  /// root (climbing parents, i.e. right-shifting the heap id).
  /// \pre node < node_count.
  uint32_t active_ancestor(uint32_t node) const;
  /// The same on ids alone, as a client that only knows <tree-id, node-id>
  /// does it: shift the heap id right until the node it names is active.
  /// Returns heap 0 when no node on the way is active or the id is unknown.
  HierarchyNodeId active_ancestor_id(HierarchyNodeId id) const;
  /// <tree-id, node-id> of a node, and the node of an id (kNoNode if none).
  HierarchyNodeId id_of(uint32_t node) const { return ids_[node]; }
  uint32_t node_of(HierarchyNodeId id) const;

  /// vsplit(node) is legal: node active and internal, the active ancestors
  /// of its fundamental cut vertices distinct and adjacent to it, and the fan
  /// between them well formed. *why gets the reason when not null.
  bool can_split(uint32_t node, std::string* why = nullptr) const;
  /// ecol(node) is legal: both children active, the wing faces
  /// (left, right, AA(cut_left)) and (right, left, AA(cut_right)) present,
  /// the link condition holds, no interior edge between two boundary
  /// vertices, and every vertex keeps three faces (one on a boundary).
  bool can_collapse(uint32_t node, std::string* why = nullptr) const;
  /// Applies vsplit / ecol; kInvalidInput with the reason (mesh unchanged)
  /// when it is not legal.
  Status split(uint32_t node);
  Status collapse(uint32_t node);
  /// SelStreamVSplit: while both cut vertices of `node` have the same active
  /// ancestor, that ancestor is split first (recursively), then `node`.
  /// Every split made is appended to *made when not null.
  Status split_with_dependencies(uint32_t node, std::vector<uint32_t>* made = nullptr);

  /// Collapses until the front is the roots: every legal ecol, deepest node
  /// first, while that makes progress. The link condition can block all the
  /// remaining ones (a vertex of a region coarser than when the collapse was
  /// built is adjacent to both children); then the front is refined to the
  /// leaves and collapsed in the reverse of the refinement order that
  /// SelStreamVSplit gives from the base, which is legal step by step.
  /// \return the error of a refused operation (a malformed hierarchy).
  Status collapse_to_base();

  /// The current mesh's faces over node indices, in face-slot order.
  std::vector<Triangle> triangles() const;
  /// Where each face of triangles() comes from, in the same order: base
  /// triangle i is i; the faces node s's split adds are base + 2 s (the
  /// left wing, (left, right, AA(cut_left))) and base + 2 s + 1 (the right
  /// wing), base = the base mesh's triangle count. A face keeps its origin
  /// while its corners move, as a progressive mesh's face slot does.
  std::vector<uint32_t> face_origins() const;
  /// The current mesh with the front's nodes as vertices (ascending node
  /// order; (*vertex_node)[i] is vertex i's node when not null).
  TriangleMesh current_mesh(std::vector<uint32_t>* vertex_node = nullptr) const;

 private:
  explicit SelectiveRefiner(const VertexHierarchy& h) : h_(&h) {}
  Status start_at_base();
  struct SplitPlan {
    uint32_t cl = kNoNode;
    uint32_t cr = kNoNode;
    std::vector<uint32_t> moved;  // faces of the node that go to the right child
  };
  bool plan_split(uint32_t node, SplitPlan* plan, std::string* why) const;
  bool check_collapse(uint32_t node, std::string* why, uint32_t* blocker) const;
  uint32_t face_with_next(uint32_t v, uint32_t next) const;
  uint32_t face_with_prev(uint32_t v, uint32_t prev) const;
  bool is_boundary_vertex(uint32_t v) const;
  void neighbours(uint32_t v, std::vector<uint32_t>* out) const;
  uint32_t add_face(const Triangle& t, uint32_t origin);
  void remove_face(uint32_t f);
  void rename(uint32_t from, uint32_t to);

  const VertexHierarchy* h_;
  std::vector<HierarchyNodeId> ids_;
  std::vector<std::pair<HierarchyNodeId, uint32_t>> id_index_;  // sorted by id
  std::vector<uint8_t> active_;
  size_t front_size_ = 0;
  std::vector<Triangle> faces_;
  std::vector<uint32_t> face_origin_;
  std::vector<uint8_t> face_alive_;
  std::vector<uint32_t> free_faces_;
  size_t live_faces_ = 0;
  std::vector<std::vector<uint32_t>> vertex_faces_;  // by node
};

}  // namespace lodbake
