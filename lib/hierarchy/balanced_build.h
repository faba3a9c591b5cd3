// Building a balanced vertex hierarchy from a triangle mesh (Kim, Lee and
// Kobbelt section 6.2: half-edge collapses chosen level by level as
// maximally independent sets, ordered by an error that includes subtree
// depth). docs/hierarchy.md describes the choices.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/support/status.h"

namespace lodbake {

struct BalancedBuildOptions {
  /// Boundary edges add a plane perpendicular to their face weighted by this
  /// times the edge length (as lib/simplify's engine does).
  double boundary_weight = 10.0;
  /// A collapse may not turn a moved face's normal by more than this.
  double max_normal_change_degrees = 150.0;
  /// How many of the three fixed candidate orderings finish the build (1..3)
  /// from the state shared down to 1/16 of the vertices; the hierarchy with
  /// the fewest <tree-id, node-id> bits is kept.
  int orderings = 3;
  /// Threads of the parallel steps (candidate listing and sorting): 0 runs them on the caller's
  /// task arena (every core, or a bake's --jobs threads). The hierarchy is the same for every
  /// count.
  unsigned threads = 0;
};

struct BalancedBuildStats {
  uint32_t levels_built = 0;  ///< rounds of independent collapses made
  /// Vertex count after each round (index 0: the input).
  std::vector<uint64_t> vertices_after_level;
};

struct BalancedHierarchy {
  VertexHierarchy hierarchy;
  BalancedBuildStats stats;
};

/// Builds the hierarchy of `mesh`: its leaves are the mesh's vertices
/// (input_vertex), its roots the base mesh's. Attributes are not carried.
/// \return kInvalidInput when the mesh is not an oriented 2-manifold
///         (possibly with boundary) or has 2^32 - 1 vertices or more;
///         kRuntime when memory runs out or a tree would need more than 64
///         bits of ids. Deterministic.
Result<BalancedHierarchy> build_balanced_hierarchy(const TriangleMesh& mesh,
                                                   const BalancedBuildOptions& options);

}  // namespace lodbake
