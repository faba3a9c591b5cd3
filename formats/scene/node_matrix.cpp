#include "formats/scene/node_matrix.h"

#include <cmath>

namespace lodbake {

Mat4 identity_matrix() {
  Mat4 m{};
  m[0] = m[5] = m[10] = m[15] = 1.0;
  return m;
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      double sum = 0;
      for (int k = 0; k < 4; ++k)
        sum += a[k * 4 + r] * b[c * 4 + k];
      m[c * 4 + r] = sum;
    }
  return m;
}

Mat4 trs_matrix(const double* translation, const double* rotation, const double* scale) {
  double qx = 0, qy = 0, qz = 0, qw = 1;
  if (rotation != nullptr) {
    const double* r = rotation;
    const double norm = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    if (norm > 0) {
      qx = r[0] / norm;
      qy = r[1] / norm;
      qz = r[2] / norm;
      qw = r[3] / norm;
    }
  }
  const double rot[3][3] = {
      {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)},
      {2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)},
      {2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)}};
  Mat4 m = identity_matrix();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col)
      m[col * 4 + row] = rot[row][col] * (scale != nullptr ? scale[col] : 1.0);
    m[12 + row] = translation != nullptr ? translation[row] : 0.0;
  }
  return m;
}

Mat4 local_matrix(const SceneNode& node) {
  if (node.matrix) return *node.matrix;
  return trs_matrix(node.translation ? node.translation->data() : nullptr,
                    node.rotation ? node.rotation->data() : nullptr,
                    node.scale ? node.scale->data() : nullptr);
}

bool is_identity(const Mat4& m) {
  return m == identity_matrix();
}

double linear_determinant(const Mat4& m) {
  auto a = [&m](int r, int c) { return m[static_cast<size_t>(c) * 4 + static_cast<size_t>(r)]; };
  return a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) -
         a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0)) +
         a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
}

}  // namespace lodbake
