// The fan-hierarchy at run time (Livny, Sokolovsky & El-Sana 2007, sections
// 3.4 and 4): the current mesh as a cut through the forest, changed along
// the coarse path (fan-merge / fan-split of a node) or the fine path (advance
// or retreat a node's merge pointer by one half-edge collapse / vertex
// split), and the active-nodes list in blocks of 256. No CGAL: this is the
// part a viewer embeds.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/fan_hierarchy.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"  // kNoNode, shared with the vertex hierarchy
#include "formats/support/status.h"
#include "lib/fanmerge/fan_mesh_state.h"

namespace lodbake {

/// The active nodes as the paper's implementation keeps them: blocks of 256
/// entries; an activated node is appended, a deactivated one is replaced by
/// the last entry. Each node's position is kept so removal is O(1).
class ActiveNodeList {
 public:
  static constexpr size_t kBlockSize = 256;

  /// Empty list for nodes 0 .. node_count-1.
  void reset(size_t node_count);
  /// \pre !contains(node)
  void add(uint32_t node);
  /// \pre contains(node)
  void remove(uint32_t node);
  bool contains(uint32_t node) const { return position_[node] != kNoNode; }
  size_t size() const { return size_; }
  size_t block_count() const { return (size_ + kBlockSize - 1) / kBlockSize; }
  /// The entries of block i (block_size(i) of them, the last block may be partial).
  const uint32_t* block(size_t i) const { return blocks_[i].data(); }
  size_t block_size(size_t i) const {
    return i + 1 < block_count() ? kBlockSize : size_ - i * kBlockSize;
  }
  /// Every entry, in list order.
  std::vector<uint32_t> nodes() const;

 private:
  uint32_t& at(size_t index) { return blocks_[index / kBlockSize][index % kBlockSize]; }
  std::vector<std::array<uint32_t, kBlockSize>> blocks_;
  std::vector<uint32_t> position_;
  size_t size_ = 0;
};

struct FanRuntimeOptions {
  /// Implicit dependencies (the paper's section 3.4, after El-Sana and
  /// Varshney): a step is also refused unless every triangle its lists name
  /// has exactly the corners it had at that step of the construction (for a
  /// collapse: before it, for a split: after it). The local checks alone
  /// let a fan take a neighbour's triangle out of construction order, after
  /// which the neighbour can never merge again; with this, the current mesh
  /// is always a mesh the construction's steps give in some order that
  /// respects their overlaps, so the earliest unmerged step and the latest
  /// merged one stay legal (no dead end) and no fold-over the construction
  /// refused can appear. create() then replays the construction once to
  /// record the corners (12 bytes per list entry).
  bool construction_dependencies = false;
};

/// A fan-hierarchy over its input mesh, starting fully refined (every merge
/// pointer 0). Operations return false and change nothing when they are not
/// legal in the current state:
/// - a node can change only while its parent does not hold it (its parent's
///   pointer is 0 for the centre child, below its index for the others);
/// - advancing collapses child k = pointer + 1 into the centre; it needs the
///   centre child and child k fully merged (or leaves), child k's vertex's
///   triangles to be exactly the node's removed and modified lists for k
///   (removed ones holding the centre, modified ones not), and the result to
///   be a valid triangulation around every touched vertex;
/// - retreating splits child k = pointer off again; it needs the removed
///   triangles dead with every corner present, the modified ones alive with
///   the centre once, and a valid result likewise.
/// Fan-merge / fan-split run the remaining steps as one operation (one
/// validity check at the end), giving the same mesh as the steps one by one.
class FanRuntime {
 public:
  /// Checks that `hierarchy` is well formed for `input` (counts, forest,
  /// ids, list offsets: the checks of formats/sections/fanh.h's
  /// validate_fanh_structure()) and starts fully refined. `input` and
  /// `hierarchy` are copied as needed; neither must outlive the call.
  /// With options.construction_dependencies, also kInvalidInput when a
  /// step of the construction does not replay over `input`.
  /// \return kInvalidInput naming the first problem; kRuntime on out of memory.
  static Result<FanRuntime> create(const TriangleMesh& input, const FanHierarchy& hierarchy,
                                   const FanRuntimeOptions& options = {});

  uint64_t node_count() const { return parent_.size(); }
  uint32_t leaf_count() const { return h_.vertex_count; }
  /// The input's triangles: corners() and alive() take ids below it.
  uint32_t input_triangle_count() const { return h_.triangle_count; }
  size_t internal_count() const { return h_.internal_count(); }
  bool is_leaf(uint32_t node) const { return node < h_.vertex_count; }
  /// The node's parent, or kNoNode for a root.
  uint32_t parent(uint32_t node) const { return parent_[node]; }
  /// The vertex a node stands for (its centre's, down to a leaf).
  uint32_t vertex(uint32_t node) const { return vertex_[node]; }
  /// Children a fan-merge collapses (the centre child not counted); 0 for a leaf.
  uint32_t collapsible_children(uint32_t node) const;
  /// The i-th child, 0 being the centre. \pre i <= collapsible_children(node)
  uint32_t child(uint32_t node, uint32_t i) const;
  /// How many children are merged; 0 for a leaf.
  uint32_t merge_pointer(uint32_t node) const {
    return is_leaf(node) ? 0 : pointer_[node - h_.vertex_count];
  }
  float error(uint32_t node) const {
    return is_leaf(node) ? 0.f : h_.error[node - h_.vertex_count];
  }
  /// A leaf, or an internal node with every child merged.
  bool fully_merged(uint32_t node) const {
    return merge_pointer(node) == collapsible_children(node);
  }
  /// True when the node's parent holds it (it cannot change).
  bool held(uint32_t node) const;

  bool advance(uint32_t node);
  bool retreat(uint32_t node);
  bool fan_merge(uint32_t node);
  bool fan_split(uint32_t node);
  /// Fan-merges every internal node in construction order (the coarsest
  /// mesh) / fan-splits every one in reverse (the input). False when one is
  /// refused, which a hierarchy that passed create() over its own input
  /// never is, from the fully refined / fully merged state.
  bool merge_all();
  bool split_all();

  const ActiveNodeList& active() const { return active_; }
  size_t vertex_count() const { return state_.present_count(); }
  size_t triangle_count() const { return state_.alive_count(); }
  /// Triangle t's current corners and whether it is in the mesh.
  const Triangle& corners(uint32_t t) const { return state_.corners(t); }
  bool alive(uint32_t t) const { return state_.alive(t); }
  /// The current mesh: the input's positions (and per-vertex normals and
  /// texture coordinates), the alive triangles in input order.
  TriangleMesh mesh() const;

 private:
  FanRuntime() = default;
  struct Lists {
    const uint32_t* removed;
    size_t removed_count;
    const uint32_t* modified;
    size_t modified_count;
  };
  Lists lists(uint32_t node, uint32_t k) const;
  // The step's offsets into h_.removed and h_.modified.
  uint32_t removed_offset(uint32_t node, uint32_t k) const;
  uint32_t modified_offset(uint32_t node, uint32_t k) const;
  bool can_collapse(uint32_t node, uint32_t k) const;
  bool can_split(uint32_t node, uint32_t k) const;
  void apply_collapse(uint32_t node, uint32_t k);
  void apply_split(uint32_t node, uint32_t k);
  void touch(uint32_t node, uint32_t k);
  bool touched_valid();
  // Runs `steps` collapses (forward) or splits from the current pointer;
  // checks validity after each one (fine) or once (coarse); undoes all on
  // refusal.
  bool run(uint32_t node, uint32_t steps, bool forward, bool check_each);

  FanHierarchy h_;
  TriangleMesh base_;  // positions and per-vertex attributes of the input
  fan_internal::FanMeshState state_;
  std::vector<uint32_t> parent_;
  std::vector<uint32_t> index_in_parent_;
  std::vector<uint32_t> vertex_;
  std::vector<uint32_t> pointer_;  // per internal node
  ActiveNodeList active_;
  std::vector<uint32_t> touched_;
  // With construction dependencies: per entry of h_.removed / h_.modified,
  // the triangle's corners before its step in the construction.
  bool dependencies_ = false;
  std::vector<Triangle> removed_before_;
  std::vector<Triangle> modified_before_;
};

}  // namespace lodbake
