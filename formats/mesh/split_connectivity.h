// The connectivity of a progressive mesh as its vertex splits are applied,
// for codecs that code a split's wings by their place in the fan of the
// split vertex (docs/format.md "Compact VSPL", version 2). Self-contained
// (formats/ does not depend on lib/simplify, whose PmRefiner checks the
// records) and total: any sequence of format-valid records is applied
// deterministically, a record that does not fit the mesh moves what its
// fan walk finds, and every operation is bounded by kMaxFanFaces.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

class SplitConnectivity {
 public:
  /// A vertex with more faces than this has no fan for the codec (its
  /// wings are coded by id) and a split of it moves no faces; real meshes
  /// stay far below, and the cap keeps hostile records from costing more
  /// than O(kMaxFanFaces^2) each.
  static constexpr size_t kMaxFanFaces = 128;

  /// The mesh of `vertex_count` vertices and `triangles`.
  /// \pre every triangle index < vertex_count.
  SplitConnectivity(uint32_t vertex_count, const std::vector<Triangle>& triangles);

  /// Room for `vertices` vertices and `faces` faces in all, so that the
  /// splits after it do not reallocate (a list per vertex moved each time
  /// the table grows). Only for counts the caller trusts (an encoder's own
  /// records), never a count read from a file. No effect on the mesh.
  void reserve(size_t vertices, size_t faces) {
    vertex_faces_.reserve(vertices);
    faces_.reserve(faces);
  }

  uint32_t vertex_count() const { return static_cast<uint32_t>(vertex_faces_.size()); }
  /// The current triangles: the base ones (vs replaced by vt where faces
  /// moved), then those of each split, as PmRefiner (lib/simplify) orders
  /// them.
  const std::vector<Triangle>& triangles() const { return faces_; }

  /// Writes vs's neighbours to `ring` in fan order: following the faces
  /// (vs, a, b) from a to b, starting at the smallest id that begins a
  /// boundary (no face ends there), else at the smallest id; neighbours the
  /// walk does not reach follow in increasing id order. Returns true when
  /// the walk closed one ring through all of vs's faces. `ring` is empty
  /// when vs has no faces or more than kMaxFanFaces.
  /// \pre vs < vertex_count().
  bool neighbours(uint32_t vs, std::vector<uint32_t>* ring) const;

  /// Applies a split creating vertex vt = vertex_count(): the faces of vs
  /// counter-clockwise from (vs, vr, .) until (vs, ., vl), or from vl
  /// clockwise to the boundary when the first walk does not reach vl
  /// (lib/simplify/split_fan.h's rule, each face at most once), move to
  /// vt; then (vs, vt, vl) and (vt, vs, vr) are added for the wings given.
  /// \pre vs < vt; each wing < vt or kNoVertex.
  void split(uint32_t vs, uint32_t vl, uint32_t vr);

  /// A hint that v's faces are read or changed soon (a split whose wing it
  /// is): starts loading v's face list. No effect on the mesh.
  /// \pre v < vertex_count().
  void prefetch(uint32_t v) const { vertex_faces_.prefetch(v); }
  /// A hint that v's fan is walked soon: starts loading the faces of v's
  /// list (read from the list, so best after prefetch(v) had time to load
  /// it). No effect on the mesh; any v.
  void prefetch_faces(uint32_t v) const;

 private:
  // Each vertex's faces in insertion order: up to kInline inline in one
  // 64-byte cache line (fans average six faces; a vertex split often keeps
  // more for a while), more in a spill vector that goes back to the pool
  // once the list fits inline again, so a million-vertex mesh needs no
  // allocation per vertex and a list is mostly one line to load.
  class FaceLists {
   public:
    explicit FaceLists(size_t vertices) : lists_(vertices) {}
    size_t size() const { return lists_.size(); }
    void reserve(size_t vertices) { lists_.reserve(vertices); }
    void add_vertex() { lists_.emplace_back(); }
    size_t count(uint32_t v) const { return lists_[v].count; }
    void prefetch(uint32_t v) const { __builtin_prefetch(&lists_[v]); }
    const uint32_t* data(uint32_t v) const {
      const List& l = lists_[v];
      return l.spill == kNoSpill ? l.head : spills_[l.spill].data();
    }
    bool contains(uint32_t v, uint32_t f) const;
    void push(uint32_t v, uint32_t f);
    /// Removes the first f, keeping the order of the others.
    void erase(uint32_t v, uint32_t f);

   private:
    static constexpr uint32_t kInline = 14;
    static constexpr uint32_t kNoSpill = UINT32_MAX;
    struct alignas(64) List {
      uint32_t count = 0;
      uint32_t spill = kNoSpill;
      uint32_t head[kInline] = {};
    };
    std::vector<List> lists_;
    std::vector<std::vector<uint32_t>> spills_;
    std::vector<uint32_t> free_spills_;  // spills_ entries no list uses
  };

  void add_face(const Triangle& t);
  std::vector<Triangle> faces_;
  FaceLists vertex_faces_;
};

}  // namespace lodbake
