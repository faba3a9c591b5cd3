// Replaying a progressive mesh: from the base mesh, vertex splits one at a
// time (and edge collapses back), with the current mesh available as a
// TriangleMesh. The PM may come from a file, so every record is validated
// before it is applied and a malformed one gives a Status, never a crash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

class PmRefiner {
 public:
  /// Starts at `pm`'s base mesh. Fails when the base has an out-of-range or
  /// repeated index, when input_vertex or the attributes do not have
  /// full_vertex_count() entries. `pm` must outlive the refiner.
  static Result<PmRefiner> create(const ProgressiveMesh& pm);

  /// Vertices of the current mesh (base vertices plus applied splits).
  size_t vertex_count() const { return mesh_.positions.size(); }
  size_t applied_splits() const { return applied_; }
  bool fully_refined() const { return applied_ == pm_->splits.size(); }
  /// The current mesh: vertices 0 .. vertex_count()-1, the base triangles
  /// first, then two (one on a boundary) per applied split, in split order.
  const TriangleMesh& mesh() const { return mesh_; }

  /// Applies the next split. Fails (leaving the mesh unchanged) when the
  /// record is inconsistent with the current mesh: index out of range, both
  /// wings missing, repeated vertices, a wing not adjacent to vs, or a fan
  /// around vs that does not lead from vr to vl.
  Status split_next();
  /// The faces the last applied split moved from vs to vt, in the order
  /// its walk met them (what PmWedges::moved follows). Empty when no split
  /// is applied.
  std::pair<const uint32_t*, const uint32_t*> last_moved_faces() const {
    if (undo_.empty()) return {nullptr, nullptr};
    return {moved_faces_.data() + undo_.back().moved_begin,
            moved_faces_.data() + moved_faces_.size()};
  }
  /// Undoes the last applied split (the edge collapse of vt into vs). Fails
  /// when no split has been applied.
  Status collapse_last();
  /// Splits or collapses until vertex_count() == `vertex_count`.
  /// \pre base vertex count <= vertex_count <= full_vertex_count().
  Status refine_to(size_t vertex_count);

 private:
  explicit PmRefiner(const ProgressiveMesh& pm) : pm_(&pm) {}
  void add_face(uint32_t f);
  void remove_last_face();
  void copy_attributes(size_t vertex);

  struct Undo {
    Vec3f vs_position;
    uint32_t moved_begin;  // into moved_faces_
    uint32_t added_faces;
  };
  const ProgressiveMesh* pm_;
  TriangleMesh mesh_;
  std::vector<std::vector<uint32_t>> vertex_faces_;
  std::vector<uint32_t> moved_faces_;
  std::vector<Undo> undo_;
  size_t applied_ = 0;
};

/// The mesh after the first vertex_count - base vertex count splits.
/// Fails when vertex_count is outside [base vertex count, full_vertex_count()]
/// or a record is malformed.
Result<TriangleMesh> mesh_at_lod(const ProgressiveMesh& pm, size_t vertex_count);

/// A fully refined mesh (`full`, in PM vertex ids) renumbered to the input's
/// vertex ids through pm.input_vertex. Fails when input_vertex is not a
/// permutation of 0 .. full.vertex_count()-1.
Result<TriangleMesh> map_to_input(const ProgressiveMesh& pm, const TriangleMesh& full);

/// True when `a` and `b` have the same vertex count and the same multiset of
/// triangles with the same orientation (a triangle may start at any corner).
bool same_oriented_triangles(const TriangleMesh& a, const TriangleMesh& b);

}  // namespace lodbake
