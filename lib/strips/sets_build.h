// Building the SETS strip graph (Belmonte, Aguado, Sancho, ICCS 2006) from
// triangle strips over a progressive mesh's full mesh and the PM's
// contraction order.
#pragma once

#include <cstdint>

#include "formats/mesh/progressive_mesh.h"
#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/support/status.h"

namespace lodbake {

struct SetsBuildStats {
  uint64_t contractions = 0;     ///< LoDs - 1
  uint64_t strip_updates = 0;    ///< (strip, LoD) pairs whose sequence changed
  uint64_t removed_indices = 0;  ///< vertices removed from sequences by compaction
  uint64_t emptied_strips = 0;   ///< strips left without a triangle at the coarsest LoD
};

/// Replays the contractions of `pm` (LoD l contracts vertex B + S - l into
/// splits[S - l].vs, B base vertices, S splits) on every strip: every
/// occurrence of the removed vertex becomes the kept one, then the strip is
/// compacted (lib/strips/strip_compaction.h); and records the graph:
/// per strip its beginnings, per vertex occurrence its sorted successor runs.
/// \pre strips.vertex_count == pm.full_vertex_count(), the strips' indices
///      are PM vertex ids (stripify the mesh of mesh_at_lod(pm, full)).
/// \return the graph (check_sets_structure() holds), kInvalidInput when the
///         counts disagree or a split names a vertex that does not exist
///         yet, kRuntime when memory runs out. Deterministic: the same
///         graph and stats for any `threads` (lib/core/parallel.h; 0, the
///         caller's task arena: every core, or a bake's --jobs threads).
Result<SetsGraph> build_sets(const TriangleStrips& strips, const ProgressiveMesh& pm,
                             SetsBuildStats* stats = nullptr, unsigned threads = 0);

}  // namespace lodbake
