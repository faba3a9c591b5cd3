// Triangle strips over a whole mesh that keep every triangle's orientation,
// the starting point of the SETS strip graph (sets_build.h) and what
// `lodbake-strips --strips-only` stores.
#pragma once

#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/sections/strp.h"
#include "formats/support/status.h"

namespace lodbake {

struct StripifyStats {
  uint64_t triangles = 0;           ///< non-degenerate input triangles, all in some strip
  uint64_t skipped_degenerate = 0;  ///< input triangles repeating a vertex (not stripped)
  uint64_t strips = 0;
  uint64_t indices = 0;  ///< sum of strip lengths
  uint64_t swaps = 0;    ///< repeated vertices inserted to turn a strip
  /// Indices a renderer draws with one restart index between strips:
  /// (indices + strips - 1) / triangles, the figure meshopt_stripify reports.
  double indices_per_triangle() const {
    return triangles == 0 ? 0.0
                          : static_cast<double>(indices + (strips == 0 ? 0 : strips - 1)) /
                                static_cast<double>(triangles);
  }
};

/// Covers every non-degenerate triangle of `mesh` with strips (the window
/// rule of TriangleStrips): each triangle is described exactly once, with
/// its own orientation, and no other non-degenerate triangle is described.
/// Strips walk across edges shared by two consistently oriented triangles
/// only. Deterministic.
/// \pre indices < mesh.vertex_count() (else kInvalidInput).
/// \return the strips over mesh.vertex_count() vertices; kRuntime when
///         memory runs out.
Result<TriangleStrips> stripify(const TriangleMesh& mesh, StripifyStats* stats = nullptr);

}  // namespace lodbake
