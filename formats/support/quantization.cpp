// Quantization shared by BASE and VSPL. Rounding is half away from zero
// (floor(t + 0.5), t >= 0) in IEEE double with the operations in the
// documented order, so any conforming implementation reproduces the
// integers and the decoded floats bit for bit. An axis of zero extent stores
// q = 0 (the box bound itself is the exact value).
#include "formats/support/quantization.h"

#include <algorithm>
#include <cmath>

#include "formats/support/bit_packing.h"

namespace lodbake {

uint32_t quantization_steps(int bits) {
  return static_cast<uint32_t>((uint64_t{1} << bits) - 1);
}

uint32_t quantize_coordinate(float p, float lo, float hi, uint32_t steps) {
  const double extent = static_cast<double>(hi) - static_cast<double>(lo);
  if (!(extent > 0)) return 0;
  const double t = (static_cast<double>(p) - static_cast<double>(lo)) / extent * steps;
  const double q = std::floor(t + 0.5);
  if (q <= 0) return 0;
  if (q >= steps) return steps;
  return static_cast<uint32_t>(q);
}

float dequantize_coordinate(uint32_t q, float lo, float hi, uint32_t steps) {
  const double t = static_cast<double>(q) / steps;
  const double extent = static_cast<double>(hi) - static_cast<double>(lo);
  return static_cast<float>(static_cast<double>(lo) + t * extent);
}

void bounding_box(const std::vector<Vec3f>& positions, Vec3f* box_min, Vec3f* box_max) {
  *box_min = {0, 0, 0};
  *box_max = {0, 0, 0};
  if (positions.empty()) return;
  *box_min = positions[0];
  *box_max = positions[0];
  for (const Vec3f& p : positions) {
    for (int a = 0; a < 3; ++a) {
      (*box_min)[a] = std::min((*box_min)[a], p[a]);
      (*box_max)[a] = std::max((*box_max)[a], p[a]);
    }
  }
}

bool is_valid_quantization_box(const Vec3f& box_min, const Vec3f& box_max, int* bad_axis) {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box_min[a]) || !std::isfinite(box_max[a]) || !(box_min[a] <= box_max[a])) {
      if (bad_axis != nullptr) *bad_axis = a;
      return false;
    }
  }
  return true;
}

double quantization_error_bound(const Vec3f& box_min, const Vec3f& box_max, int bits) {
  const double steps = quantization_steps(bits);
  double bound = 0;
  for (int a = 0; a < 3; ++a) {
    const double extent = static_cast<double>(box_max[a]) - static_cast<double>(box_min[a]);
    const double magnitude = std::max(std::fabs(static_cast<double>(box_min[a])),
                                      std::fabs(static_cast<double>(box_max[a])));
    bound = std::max(
        bound, extent * (0.5 / steps + std::ldexp(1.0, -40)) + magnitude * std::ldexp(1.0, -23));
  }
  return bound;
}

// On the bit pattern: IEEE floats of one sign order like their patterns'
// magnitudes, so clearing the low bits truncates the magnitude and adding
// one unit of the kept bits after setting them rounds it up (a carry into
// the exponent is the next binade's first value).
float round_up_to_significant_bits(float x, int bits) {
  const int drop = kMaxSignificantBits - bits;
  if (drop <= 0 || !std::isfinite(x)) return x;
  const uint32_t mask = (uint32_t{1} << drop) - 1;
  const uint32_t pattern = float_bits(x);
  if ((pattern & mask) == 0) return x;
  if (std::signbit(x)) return bits_float(pattern & ~mask);  // towards zero is up
  const float up = bits_float((pattern | mask) + 1);
  return std::isfinite(up) ? up : x;
}

}  // namespace lodbake
