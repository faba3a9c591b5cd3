// Internal to lib/metrics: the fixed sample pattern and the fixed-block
// parallel loop that measure_surface_distance and measure_scene_deviation
// share, so that both spread their samples (and reduce their results) the
// same way. docs/metrics.md states the pattern.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lib/core/parallel.h"

namespace lodbake {
namespace metrics {

// How many of `budget` samples each triangle receives: triangle t gets
// round(C_t) - round(C_{t-1}), C_t being the running sum of
// area * budget / total_area in triangle order, so the shares follow the
// area and add up to the budget. All zero when the total area is not > 0.
std::vector<uint64_t> samples_per_triangle(const std::vector<double>& areas, uint64_t budget);

// Barycentric weights (w0, w1, w2) of sample j inside a triangle: the
// centroid for j = 0, else the j-th point of the R2 low-discrepancy
// sequence (Roberts 2018) folded from the unit square into the triangle.
std::array<double, 3> triangle_sample(uint64_t j);

// Runs `work(block)` for blocks [0, blocks) on `threads` threads of
// lib/core/parallel.h (0: the caller's task arena, every core or a bake's
// --jobs threads). Returns false when a block threw. Callers keep one result
// per block and reduce them in block order, so the thread count never
// changes the result.
template <typename Work>
bool run_blocks(size_t blocks, unsigned threads, const Work& work) {
  try {
    ParallelScope(threads).for_each_part(blocks, [&](size_t b) { work(b); });
  } catch (...) {
    return false;
  }
  return true;
}

}  // namespace metrics
}  // namespace lodbake
