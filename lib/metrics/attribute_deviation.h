// How far a simplified asset's appearance strays from its input's: from
// points sampled on every input primitive to the closest point of the
// output, the texture coordinate and normal found there are compared with
// the input's at the sample (issue "attribute-aware simplification", part
// 6), next to the geometric distances. What lodbake-simplify reports for an
// asset and what the attribute benchmark scores every simplifier with.
// Sampling, closest-point choice and interpolation: docs/metrics.md.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/scene/scene.h"
#include "formats/support/status.h"

namespace lodbake {

struct DeviationOptions {
  // Area samples over the input's world-space triangles, spread in
  // proportion to area as measure_surface_distance spreads them, and as many
  // over the output's (for the Hausdorff distance's other side); every
  // referenced vertex is sampled on top. Larger: tighter percentiles, slower.
  uint64_t area_samples = 200000;
  // Threads (lib/core/parallel.h): 0, the caller's task arena (every core,
  // or a bake's --jobs threads). The result does not depend on it.
  unsigned threads = 0;
};

// A mean and a 95th percentile over samples (0 and 0 with no sample).
struct DeviationStats {
  double mean = 0;
  double p95 = 0;
  uint64_t samples = 0;
};

struct PrimitiveDeviation {
  uint32_t mesh = 0;
  uint32_t primitive = 0;         // index in the input mesh's primitives (world samples
                                  // of every instance together)
  DeviationStats distance;        // model units, to the closest output point
  double max_distance = 0;        // the largest of them
  DeviationStats uv;              // |uv - uv'| of TEXCOORD_0, UV units (no samples: no UV)
  DeviationStats normal_degrees;  // angle between NORMAL and NORMAL' (no samples: no normal)
};

struct SceneDeviation {
  std::vector<PrimitiveDeviation> primitives;  // triangle primitives of every mesh, in order
  // Over every sample of every primitive (not a mean of the primitives').
  DeviationStats distance;
  DeviationStats uv;
  DeviationStats normal_degrees;
  // Symmetric Hausdorff distance between the world-space surfaces (input
  // samples to output and output samples to input), and relative to the
  // input's diagonal.
  double hausdorff = 0;
  double hausdorff_relative = 0;
  double mean_relative = 0;  // distance.mean / diagonal
  double diagonal = 0;       // of the input's world-space referenced positions
};

// Measures `output` (a simplification of `input`, by lodbake or any other
// tool: meshes, primitives and nodes may be merged, split or renumbered)
// against `input` in world space: each mesh under every node that uses it,
// the nodes' transforms applied (a mesh no node uses: its own frame). A
// sample of an input primitive is compared with the closest point among
// the output triangles whose material equals its own (the same JSON object,
// its name included, numbers equal as 32-bit floats), and among all output
// triangles when none does.
// \pre nothing: a non-finite position or an index out of range gives
//      kInvalidInput; an output without triangles gives kInvalidInput.
// Deterministic: same scenes and options, bit-identical result.
Result<SceneDeviation> measure_scene_deviation(const Scene& input, const Scene& output,
                                               const DeviationOptions& options = {});

}  // namespace lodbake
