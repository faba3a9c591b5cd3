// Uniform scalar quantization of float32 coordinates over a box, shared by
// every section that stores quantized positions (BASE, VSPL). The formulas
// are part of the format: docs/format.md "Quantization".
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

/// How a section stores positions (BASE and VSPL use the same codes).
enum class PositionEncoding : uint8_t {
  kFloat32 = 0,    ///< three little-endian float32 per position, exact
  kQuantized = 1,  ///< three `bits`-bit integers per position over a stored box
};

inline constexpr int kMinQuantizationBits = 1;
inline constexpr int kMaxQuantizationBits = 30;

/// 2^bits - 1, the largest quantized value.
/// \pre bits in kMinQuantizationBits..kMaxQuantizationBits.
uint32_t quantization_steps(int bits);

/// The integer for coordinate `p` on an axis [lo, hi]:
///   0 when hi == lo, else floor((p - lo) / (hi - lo) * steps + 0.5) clamped
///   to 0..steps, in IEEE double in that order.
uint32_t quantize_coordinate(float p, float lo, float hi, uint32_t steps);

/// The coordinate for integer `q`: (float)(lo + (q / steps) * (hi - lo)) in
/// IEEE double in that order, so every conforming reader gets the same float.
float dequantize_coordinate(uint32_t q, float lo, float hi, uint32_t steps);

/// The axis-aligned bounding box of `positions`; all zeros when empty.
void bounding_box(const std::vector<Vec3f>& positions, Vec3f* box_min, Vec3f* box_max);

/// True when every axis of the box is finite with min <= max: what a decoder
/// requires of a stored dequantization box.
bool is_valid_quantization_box(const Vec3f& box_min, const Vec3f& box_max, int* bad_axis);

/// The documented bound on a quantized coordinate's error: half a
/// quantization step of the widest axis, plus one float32 rounding of the
/// result and a margin for double rounding:
///   max over axes of  extent * (0.5 / (2^bits - 1) + 2^-40) + max(|min|, |max|) * 2^-23
/// \pre box finite with min <= max per axis; bits in 1..30.
double quantization_error_bound(const Vec3f& box_min, const Vec3f& box_max, int bits);

inline constexpr int kMinSignificantBits = 1;
inline constexpr int kMaxSignificantBits = 24;  ///< float32's: keeps every value

/// `x` rounded towards +infinity to `bits` significant bits (the leading one
/// and bits - 1 mantissa bits), so that a bound stays a bound: the result is
/// the smallest float >= x whose lowest 24 - bits mantissa bits are zero.
/// Non-finite values, values that already fit, and positive values whose
/// rounding would overflow to infinity come back unchanged. Monotone and
/// idempotent; bits = 24 is the identity. Used to quantize collapse errors
/// (docs/format.md "Compact VSPL", version 4).
/// \pre bits in kMinSignificantBits..kMaxSignificantBits.
float round_up_to_significant_bits(float x, int bits);

}  // namespace lodbake
