// Node transforms as column-major 4x4 matrices (glTF's layout): what the
// glTF reader's node forest, the scene flattening and the attribute
// metric's world space share.
#pragma once

#include <array>

#include "formats/scene/scene.h"

namespace lodbake {

using Mat4 = std::array<double, 16>;  // column-major

Mat4 identity_matrix();
Mat4 multiply(const Mat4& a, const Mat4& b);

/// T * R * S from a translation, a rotation quaternion (x, y, z, w) and a
/// scale, each null when absent. The quaternion is normalised; the caller
/// refuses one without a usable length (a zero one gives no rotation here).
Mat4 trs_matrix(const double* translation, const double* rotation, const double* scale);

/// A scene node's local transform: its matrix when it has one (glTF forbids
/// both; a matrix wins), else T * R * S of the parts it has.
Mat4 local_matrix(const SceneNode& node);

/// Exactly the identity (then a transform can leave values bit-exact).
bool is_identity(const Mat4& m);

/// Determinant of the upper-left 3x3 part (negative: the transform mirrors).
double linear_determinant(const Mat4& m);

}  // namespace lodbake
