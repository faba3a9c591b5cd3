// Geometric error between two triangle meshes: the symmetric Hausdorff
// distance and the mean surface distance, measured by closest-point queries
// on CGAL AABB trees from a fixed, deterministic set of samples. What
// lodbake-simplify reports and what the simplification benchmark compares.
// The sampling and the averaging are stated in docs/metrics.md.
#pragma once

#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

struct DistanceOptions {
  // Area samples per direction, spread over the triangles in proportion to
  // their area (each triangle's share rounded by a running sum, so the total
  // is this number up to rounding). Every referenced vertex is sampled on
  // top of these. Larger: tighter maximum, slower.
  uint64_t area_samples = 500000;
  // Threads for the tree builds and the queries (lib/core/parallel.h): 0,
  // the caller's task arena (every core, or a bake's --jobs threads). The
  // result does not depend on it (fixed blocks, summed in block order).
  unsigned threads = 0;
};

// Distances from the samples of one mesh to the surface of the other.
struct OneSidedDistance {
  double max = 0;               // largest sample distance (vertices and area samples)
  double mean = 0;              // mean over the area samples: the area-weighted mean
                                // distance (over the vertices when the mesh has no area)
  uint64_t vertex_samples = 0;  // referenced vertices sampled
  uint64_t area_samples = 0;    // samples placed inside triangles
};

struct SurfaceDistance {
  OneSidedDistance a_to_b;  // samples on a, distances to b's surface
  OneSidedDistance b_to_a;  // samples on b, distances to a's surface
  double hausdorff = 0;     // max(a_to_b.max, b_to_a.max)
  double mean = 0;          // (a_to_b.mean + b_to_a.mean) / 2
  double diagonal = 0;      // of the bounding box of a's referenced vertices
  // hausdorff / diagonal and mean / diagonal; 0 when the diagonal is 0.
  double hausdorff_relative = 0;
  double mean_relative = 0;
};

// Measures the distance between the surfaces of `a` and `b` (typically an
// input mesh and its simplification) in both directions. Distances are
// computed in double precision from the float positions.
// \pre nothing: a mesh without triangles, with an index out of range or a
//      non-finite referenced position gives kInvalidInput; running out of
//      memory or a CGAL failure gives kRuntime.
// Deterministic: same meshes and area_samples, bit-identical result, for
// any thread count.
Result<SurfaceDistance> measure_surface_distance(const TriangleMesh& a, const TriangleMesh& b,
                                                 const DistanceOptions& options = {});

}  // namespace lodbake
