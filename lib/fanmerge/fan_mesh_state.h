// The mutable triangle mesh that fan-merges and their fine paths edit, shared
// by the construction (fan_build.cpp) and the runtime (fan_runtime.cpp):
// input triangles by index with their current corners, alive flags, exact
// vertex-to-triangle lists, and the local
// check that an edit left a valid triangulation around the vertices it
// touched. Internal to lib/fanmerge.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {
namespace fan_internal {

/// A read-only view of one vertex's triangle list.
struct TriangleList {
  const uint32_t* first = nullptr;
  const uint32_t* last = nullptr;
  const uint32_t* begin() const { return first; }
  const uint32_t* end() const { return last; }
  size_t size() const { return static_cast<size_t>(last - first); }
  bool empty() const { return first == last; }
  uint32_t operator[](size_t i) const { return first[i]; }
};

/// Per-vertex lists of triangle ids with vector semantics (push_back,
/// swap-remove: the order is exactly a std::vector's), laid out for the
/// builder's random access: one 64-byte slot per vertex holds its size and up
/// to kInline entries, so reading a typical star costs one cache line instead
/// of a vector header plus its heap block. A longer list (a fan-merge centre)
/// moves to a shared pool, doubling its block when full.
class IncidenceLists {
 public:
  static constexpr uint32_t kInline = 14;
  /// `n` empty lists; list v gets room for capacity[v] before it overflows.
  void init(size_t n, const std::vector<uint32_t>& capacity);
  TriangleList operator[](uint32_t v) const {
    const Slot& s = slots_[v];
    const uint32_t* d = s.where == 0 ? s.items : pool_.data() + s.where;
    return {d, d + s.size};
  }
  uint32_t size(uint32_t v) const { return slots_[v].size; }
  /// Hints that list v is read soon.
  void prefetch(uint32_t v) const { __builtin_prefetch(&slots_[v]); }
  void push_back(uint32_t v, uint32_t t);
  /// Swap-removes the first occurrence of t (no-op when absent).
  void remove(uint32_t v, uint32_t t);

 private:
  struct alignas(64) Slot {
    uint32_t size = 0;
    uint32_t where = 0;  // 0: items; else the list's offset in pool_ (capacity at where - 1)
    uint32_t items[kInline];
  };
  uint32_t* data(Slot& s) { return s.where == 0 ? s.items : pool_.data() + s.where; }
  uint32_t* grow(Slot& s, uint32_t capacity);
  std::vector<Slot> slots_;
  std::vector<uint32_t> pool_;
};

class FanMeshState {
 public:
  /// Every triangle of `mesh` alive with its input corners; a vertex is
  /// present when a triangle uses it.
  /// \pre indices in range (the caller checked the mesh).
  void init(const TriangleMesh& mesh);

  const Triangle& corners(uint32_t t) const { return corners_[t]; }
  bool alive(uint32_t t) const { return alive_[t] != 0; }
  bool present(uint32_t v) const { return present_[v] != 0; }
  uint32_t degree(uint32_t v) const { return incident_.size(v); }
  size_t alive_count() const { return alive_count_; }
  size_t present_count() const { return present_count_; }
  size_t triangle_count() const { return corners_.size(); }

  /// The alive triangles with a corner `v`, into *out (replaced), in the
  /// deterministic order of v's list.
  void star(uint32_t v, std::vector<uint32_t>* out) const;
  /// The same without a copy; valid until the next edit.
  TriangleList triangles_of(uint32_t v) const { return incident_[v]; }
  /// Hints that v's list (triangles_of) is read soon; no effect otherwise.
  void prefetch_star(uint32_t v) const { incident_.prefetch(v); }
  /// Hints that triangle t's corners are read soon.
  void prefetch_corners(uint32_t t) const { __builtin_prefetch(&corners_[t]); }

  /// The half-edge collapse of c into v: the `removed` triangles die, `c`
  /// becomes `v` in the `modified` ones, c is no longer present.
  /// \pre the lists are c's star split by whether a triangle holds v.
  void collapse(uint32_t c, uint32_t v, const uint32_t* removed, size_t removed_count,
                const uint32_t* modified, size_t modified_count);
  /// The inverse vertex split: c present again, the `modified` triangles'
  /// corner `v` becomes `c`, the `removed` ones live again with the corners
  /// they died with.
  void split(uint32_t c, uint32_t v, const uint32_t* removed, size_t removed_count,
             const uint32_t* modified, size_t modified_count);

  /// Appends to *out the vertices whose stars a collapse of c into v (call
  /// before it) or the split of c off v (call after it) changes other than
  /// by renaming c to v throughout: v, c, the third corners of `removed`,
  /// and the other corners of `modified` that are neighbours of v outside
  /// c's triangles. Every other corner of a modified triangle sees only the
  /// rename, so a star that was valid stays valid: checking these vertices
  /// is enough when the mesh was valid before.
  void collect_changed(uint32_t c, uint32_t v, const uint32_t* removed, size_t removed_count,
                       const uint32_t* modified, size_t modified_count, std::vector<uint32_t>* out);

  /// True when around every vertex of `vertices` the mesh is a valid
  /// triangulation: a present vertex has at least one triangle, and its
  /// triangles form one fan (a chain or a cycle) in which no neighbour
  /// follows or precedes it twice (edge-manifold, consistently oriented) and
  /// no two triangles share all three vertices; an absent vertex has none.
  bool stars_valid(const std::vector<uint32_t>& vertices);

  /// The alive triangles, in input order, with their current corners.
  std::vector<Triangle> alive_triangles() const;

 private:
  std::vector<Triangle> corners_;
  std::vector<uint8_t> alive_;
  std::vector<uint8_t> present_;
  IncidenceLists incident_;  // exactly the alive triangles of each vertex
  size_t alive_count_ = 0;
  size_t present_count_ = 0;
  std::vector<uint32_t> mark_;  // collect_changed()'s neighbour marks
  uint32_t stamp_ = 0;
  std::vector<uint32_t> next_, prev_, successor_;  // stars_valid()'s scratch
};

/// True when triangle `t` has a corner `v`.
inline bool has_corner(const Triangle& t, uint32_t v) {
  return t[0] == v || t[1] == v || t[2] == v;
}

}  // namespace fan_internal
}  // namespace lodbake
