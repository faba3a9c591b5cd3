// The QEM edge-collapse engine (Garland & Heckbert 1997) and the progressive
// mesh it records (Hoppe 1996). The entry point every tool and benchmark uses.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

enum class Placement {
  kHalf,     // the surviving vertex keeps one endpoint's position (PM, streaming, strips)
  kOptimal,  // the quadric's minimiser (Eigen 3x3 solve), endpoint/midpoint when singular
};

inline constexpr double kDefaultHeightGuardFactor = 4.0 / 3.0;

// What SimplifyOptions::height_guard_factor accepts.
inline bool is_valid_height_guard_factor(double factor) {
  return factor > 0 && std::isfinite(factor);
}

// The default seam release bound: gltfpack's default error bound, the
// error above which keeping texture seams flattens charts more than moving
// them distorts the texture (docs/lab/seam-release.md).
constexpr double kDefaultSeamRelease = 0.01;

// The most triangles simplify() takes (its engine names a half-edge by
// 3 * triangle + corner in 32 bits); more is kUnsupported.
constexpr uint64_t kMaxSimplifyTriangles = 0xffffffffu / 3;

struct SimplifyOptions {
  Placement placement = Placement::kHalf;
  // Stop criteria: simplification stops at the first one reached. With none
  // set it runs until no legal collapse is left.
  std::optional<uint64_t> target_triangles;  // stop at or below this many triangles
  std::optional<double> target_ratio;        // of the input triangles, in (0, 1]
  std::optional<double> max_error;           // largest collapse error allowed, relative to the
                                    // bounding-box diagonal (like meshoptimizer's target_error)
  double boundary_weight = 10.0;  // half placement: boundary constraint planes weigh this * edge
                                  // length (faces: sqrt(area)), 10 being meshoptimizer's border
                                  // weight; optimal placement: this (faces: 1)
  bool lock_border = false;       // never move or remove boundary vertices
  // Empty, or one flag per input vertex: nonzero, the vertex is never moved
  // or removed (the out-of-core blocks lock a band along their cuts).
  std::vector<uint8_t> locked_vertices;
  double max_normal_change_degrees = 150.0;  // refuse collapses turning a face normal more
  bool permissive = false;                   // allow collapses across texture seams
  // Assets, without `permissive`: seams stay until keeping them costs more
  // than this error, relative to the diagonal (WedgeCollapseOptions;
  // docs/simplify.md "Assets"); unset or infinite, they never move.
  std::optional<double> seam_release = kDefaultSeamRelease;
  // Half placement only: also refuse a collapse when the removed vertex lies
  // farther from the plane of one of the faces it moves than the pass's
  // error scale allows (the cost, a mean over its faces, misses one face
  // tilting away). A lower Hausdorff error for 1.1 to 1.5 times the time
  // (docs/simplify.md, "The height guard").
  bool height_guard = false;
  // The guard's allowance: a moved face may pass at most
  // sqrt(height_guard_factor * scale) from the removed vertex, scale being
  // the larger of the collapse's cost and the pass's cost limit (squared
  // lengths). Finite and above 0. A larger factor refuses fewer collapses
  // and costs less time; 4/3 was chosen on the benchmark meshes, and 3 did
  // as well on 18 others at a fraction of the cost (docs/simplify.md).
  double height_guard_factor = kDefaultHeightGuardFactor;
  bool record_pm = false;  // also record the progressive mesh
  // Threads for the engine's parallel steps (the listing and sort of each
  // pass, the sweep between passes, the input check, the quadric set-up,
  // the assembly), on oneTBB (lib/core/parallel.h): any count; 0 runs them
  // on the caller's task arena (every core, or a bake's --jobs threads).
  // The result is the same byte for byte for every count.
  unsigned threads = 0;
  // Called now and then with the fraction done (0..1); may be empty.
  std::function<void(double)> progress;
};

struct SimplifyStats {
  uint64_t input_triangles = 0;
  uint64_t output_triangles = 0;
  uint64_t collapses = 0;
  // Passes over the cost-sorted edges (docs/simplify.md, "Algorithm"):
  // each lists and sorts every live edge, so a run's time grows with them.
  uint64_t passes = 0;
  uint64_t refused_link = 0;      // would make the mesh non-manifold
  uint64_t refused_flip = 0;      // would flip or nearly flip a face normal
  uint64_t refused_other = 0;     // pockets, locked border, seams
  uint64_t refused_height = 0;    // the height guard
  double max_collapse_error = 0;  // largest collapse error applied (the square root of a mean
                                  // squared distance), relative to the diagonal
};

struct SimplifyResult {
  TriangleMesh mesh;  // the simplified mesh (unused vertices removed)
  // The input vertex each of mesh's vertices is (increasing): what joins
  // separately simplified pieces of one mesh again (lib/outofcore).
  std::vector<uint32_t> vertex_sources;
  std::optional<ProgressiveMesh> pm;  // when SimplifyOptions::record_pm
  SimplifyStats stats;
};

// Simplifies `input`.
// \pre input passed check_usable(): finite, no out-of-range index, edge-manifold
//      (the engine refuses non-manifold edges with kInvalidInput otherwise).
// Deterministic: same input and options, identical result (ties broken by
// vertex index, no pointer order, no unordered iteration in the result).
Result<SimplifyResult> simplify(const TriangleMesh& input, const SimplifyOptions& options);

// The same result, taking `input`'s positions and triangles once they are
// checked: the engine's copy is then the only one (18 bytes per input
// triangle less at the peak). Afterwards `input` holds its attributes only,
// or, on failure, possibly its positions and triangles too.
Result<SimplifyResult> simplify(TriangleMesh&& input, const SimplifyOptions& options);

}  // namespace lodbake
