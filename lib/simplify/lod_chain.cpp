#include "lib/simplify/lod_chain.h"

#include <algorithm>
#include <numeric>

#include "lib/simplify/pm_replay.h"

namespace lodbake {

Result<std::vector<TriangleMesh>> extract_lods(const ProgressiveMesh& pm,
                                               const std::vector<uint64_t>& triangle_targets) {
  // Visit the targets from the smallest up, so one refinement pass serves all.
  std::vector<size_t> order(triangle_targets.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return triangle_targets[a] < triangle_targets[b]; });
  LODBAKE_ASSIGN_OR_RETURN(PmRefiner refiner, PmRefiner::create(pm));
  std::vector<TriangleMesh> lods(triangle_targets.size());
  for (size_t index : order) {
    while (refiner.mesh().triangle_count() < triangle_targets[index] && !refiner.fully_refined())
      LODBAKE_RETURN_IF_ERROR(refiner.split_next());
    lods[index] = refiner.mesh();
  }
  return lods;
}

}  // namespace lodbake
