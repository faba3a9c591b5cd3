// Sequential replay of a progressive mesh that reports what each vertex
// split does to the faces: which face slots move from vs to vt and which are
// added, plus the boundary half-edges around the split vertex. The DAG
// builder (lineage of triangles) and the vertex-tree builder (vertex fans
// after each split) both walk a PM through it. Same split semantics and the
// same record checks as lib/simplify/pm_replay.h (PmRefiner).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

/// A directed edge a -> b packed as (a << 32) | b.
using HalfEdgeKey = uint64_t;
inline HalfEdgeKey half_edge_key(uint32_t a, uint32_t b) {
  return (uint64_t{a} << 32) | b;
}

/// One run of a vertex fan: neighbours in clockwise order; closed when the
/// last neighbour is adjacent to the first (an interior vertex).
struct FanRun {
  bool closed = false;
  std::vector<uint32_t> vertices;
};

class SplitSimulator {
 public:
  /// Starts at `pm`'s base mesh. Fails when a base triangle has an
  /// out-of-range or repeated index. `pm` must outlive the simulator.
  static Result<SplitSimulator> create(const ProgressiveMesh& pm);

  /// What the last split did (face slots index faces()).
  struct Effect {
    std::vector<uint32_t> moved;  // slots whose vs became vt
    std::vector<uint32_t> added;  // new slots: (vs, vt, vl) first, then (vt, vs, vr)
  };

  size_t applied_splits() const { return applied_; }
  size_t vertex_count() const { return faces_of_.size(); }
  /// Face slots: base triangles first, then the added ones in split order.
  /// A moved slot keeps its index and changes its content.
  const std::vector<Triangle>& faces() const { return faces_; }
  const std::vector<uint32_t>& faces_of(uint32_t v) const { return faces_of_[v]; }

  /// Applies the next split; fails (mesh unchanged) on the record errors
  /// PmRefiner::split_next() reports.
  Status split_next(Effect* effect);

  /// Boundary half-edges with an end at `v` (a half-edge whose twin has a
  /// face and which has none), appended to `out`.
  void boundary_half_edges(uint32_t v, std::vector<HalfEdgeKey>* out) const;

  /// The fan of `v`: its runs, each clockwise, ordered by first vertex; a
  /// closed run starts at its smallest neighbour. Empty for a vertex without
  /// faces.
  std::vector<FanRun> fan(uint32_t v) const;

 private:
  explicit SplitSimulator(const ProgressiveMesh& pm) : pm_(&pm) {}

  const ProgressiveMesh* pm_;
  std::vector<Triangle> faces_;
  std::vector<std::vector<uint32_t>> faces_of_;
  size_t applied_ = 0;
};

}  // namespace lodbake
