// Internal to lib/metrics: the fixed sample pattern and the fixed-block
// thread pool that measure_surface_distance and measure_scene_deviation
// share, so that both spread their samples (and reduce their results) the
// same way. docs/metrics.md states the pattern.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <thread>
#include <vector>

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

// Runs `work(block)` for blocks [0, blocks) on `threads` threads (the
// caller being one of them). Returns false when a worker threw. Callers
// keep one result per block and reduce them in block order, so the thread
// count never changes the result.
template <typename Work>
bool run_blocks(size_t blocks, unsigned threads, const Work& work) {
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  auto worker = [&]() {
    try {
      for (size_t b = next++; b < blocks && !failed; b = next++)
        work(b);
    } catch (...) {
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  const size_t extra =
      std::min<size_t>(threads, blocks) > 1 ? std::min<size_t>(threads, blocks) - 1 : 0;
  for (size_t i = 0; i < extra; ++i) {
    try {
      pool.emplace_back(worker);
    } catch (const std::exception&) {
      break;  // fewer threads: the remaining ones take the blocks
    }
  }
  worker();
  for (std::thread& t : pool)
    t.join();
  return !failed;
}

}  // namespace metrics
}  // namespace lodbake
