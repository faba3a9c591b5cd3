#include "lib/metrics/surface_sampling.h"

#include <cmath>

namespace lodbake {
namespace metrics {
namespace {

// The R2 sequence's generator: 1/g and 1/g^2 for the plastic number g.
constexpr double kPlastic = 1.32471795724474602596;
constexpr double kR2StepU = 1.0 / kPlastic;
constexpr double kR2StepV = 1.0 / (kPlastic * kPlastic);

}  // namespace

std::vector<uint64_t> samples_per_triangle(const std::vector<double>& areas, uint64_t budget) {
  std::vector<uint64_t> counts(areas.size(), 0);
  double total_area = 0;
  for (double a : areas)
    total_area += a;
  if (!(total_area > 0) || budget == 0) return counts;
  const double density = static_cast<double>(budget) / total_area;
  double running = 0;
  uint64_t placed = 0;
  for (size_t t = 0; t < areas.size(); ++t) {
    running += areas[t] * density;
    const uint64_t target =
        std::min<uint64_t>(budget, static_cast<uint64_t>(std::llround(running)));
    if (target <= placed) continue;
    counts[t] = target - placed;
    placed = target;
  }
  return counts;
}

std::array<double, 3> triangle_sample(uint64_t j) {
  double u = 1.0 / 3.0;
  double v = 1.0 / 3.0;
  if (j > 0) {
    const double fj = static_cast<double>(j);
    u = 0.5 + fj * kR2StepU;
    v = 0.5 + fj * kR2StepV;
    u -= std::floor(u);
    v -= std::floor(v);
    if (u + v > 1.0) {
      u = 1.0 - u;
      v = 1.0 - v;
    }
  }
  return {1.0 - u - v, u, v};
}

}  // namespace metrics
}  // namespace lodbake
