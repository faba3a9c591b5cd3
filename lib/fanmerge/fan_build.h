// Construction of the fan-hierarchy (Livny, Sokolovsky & El-Sana 2007,
// sections 3.1-3.3): fan-merges in increasing order of their quadric error,
// each recorded as a node whose children, in order, are the fine path of
// half-edge collapses that gives the same mesh.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "formats/mesh/fan_hierarchy.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

struct FanBuildOptions {
  // Stop criteria: construction stops at the first one reached, or when no
  // vertex is left whose fan-merge is legal.
  std::optional<uint64_t> target_vertices;  ///< stop at or below this many vertices
  std::optional<double> target_ratio;       ///< of the input's vertices, in (0, 1]
  /// Skip fan-merges whose error sqrt(Delta(v)) exceeds this times the
  /// bounding-box diagonal.
  std::optional<double> max_error;
  /// Priority = Delta(v) * (degree(v) / 6)^degree_weight: with a positive
  /// weight low-degree fans merge first among similar errors (the paper's
  /// remark in 3.2). 0 (default): the priority is the error.
  double degree_weight = 0;
  /// Boundary edges add a plane through them, perpendicular to their face,
  /// weighted by this times the edge length (as lodbake-simplify).
  double boundary_weight = 10.0;
  /// A fan-merge (and each collapse of its fine path) is refused when it
  /// turns a modified triangle's normal by more than this (fold-over test).
  double max_normal_change_degrees = 90.0;
  /// Threads for the quadric set-up and the first keys (lib/core/parallel.h):
  /// 0, the caller's task arena (every core, or a bake's --jobs threads).
  /// The hierarchy does not depend on it.
  unsigned threads = 0;
  /// Called now and then with the fraction done (0..1); may be empty.
  std::function<void(double)> progress;
};

struct FanBuildStats {
  uint64_t merges = 0;            ///< internal nodes created
  uint64_t refused_topology = 0;  ///< attempts leaving a non-manifold or degenerate fan
  uint64_t refused_flip = 0;      ///< attempts folding a modified triangle over
  uint64_t skipped_error = 0;     ///< candidates over max_error
  uint64_t output_vertices = 0;   ///< vertices of the coarsest mesh
  uint64_t output_triangles = 0;  ///< triangles of the coarsest mesh
};

struct FanBuildResult {
  FanHierarchy hierarchy;
  TriangleMesh coarsest;  ///< the input's positions, the coarsest mesh's triangles
  FanBuildStats stats;
};

/// Builds the fan-hierarchy of `input`.
/// \pre none checked by the caller: the mesh must be an oriented 2-manifold
///      (boundaries allowed) with finite coordinates, else kInvalidInput
///      naming the first problem. Unreferenced vertices become roots.
/// Deterministic: ties in the heap are broken by vertex index.
/// \return kRuntime when memory runs out.
Result<FanBuildResult> build_fan_hierarchy(const TriangleMesh& input,
                                           const FanBuildOptions& options);

}  // namespace lodbake
