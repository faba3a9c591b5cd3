// Replaying a progressive mesh with its wedges: PmRefiner's levels, and the
// wedge each corner of each level uses. The data may come from a file, so
// every record is checked before it is applied and a malformed one gives a
// Status, never a crash.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/support/status.h"
#include "lib/simplify/pm_replay.h"

namespace lodbake {

class WedgeRefiner {
 public:
  /// Starts at the base mesh. Fails when `wedges` does not fit `pm` (counts
  /// that differ, a wedge out of range, offsets out of order). `pm` and
  /// `wedges` must outlive the refiner.
  static Result<WedgeRefiner> create(const ProgressiveMesh& pm, const PmWedges& wedges);

  const PmRefiner& refiner() const { return refiner_; }
  const TriangleMesh& mesh() const { return refiner_.mesh(); }
  /// The wedges of mesh()'s corners, triangle by triangle.
  const std::vector<std::array<uint32_t, 3>>& corners() const { return corners_; }

  /// Applies the next split. Fails (the state is then unusable) when the
  /// split's wedge records do not match what it does: a missing wing with
  /// wedges, a wing without, or another number of moved faces.
  Status split_next();
  /// Undoes the last applied split.
  Status collapse_last();
  /// Splits or collapses until the mesh has `vertex_count` vertices.
  Status refine_to(size_t vertex_count);

 private:
  WedgeRefiner(PmRefiner refiner, const PmWedges& wedges)
      : refiner_(std::move(refiner)), wedges_(&wedges) {}

  PmRefiner refiner_;
  const PmWedges* wedges_;
  std::vector<std::array<uint32_t, 3>> corners_;
  std::vector<uint32_t> undo_;  // the wedges moved corners had at vs, split by split
};

// The wedge of every (face, vertex) pair a level of detail can hold: a face
// slot of the progressive mesh (its base triangles, then each split's added
// faces) keeps, at each vertex its corner ever sits at, the wedge it took
// there. So any mesh made of the PM's face slots whose corners sit at PM
// vertices (the levels of the PM, and the fronts of the structures built
// over it) finds its corners' wedges without replaying its own history.
class CornerWedges {
 public:
  /// Replays `pm` once with `wedges` (fails as WedgeRefiner does).
  static Result<CornerWedges> create(const ProgressiveMesh& pm, const PmWedges& wedges);

  /// The wedge face slot `face` has at `vertex`, or kNoVertex when its
  /// corner is never at that vertex.
  uint32_t wedge(uint32_t face, uint32_t vertex) const;

  size_t size() const { return keys_.size(); }

 private:
  std::vector<uint64_t> keys_;  // face << 32 | vertex, sorted
  std::vector<uint32_t> values_;
};

}  // namespace lodbake
