// Camera -> view request -> view parameters for mode stream. The request
// carries gluLookAt's matrix in float32; the parameters are rebuilt from it
// in double (the inverse of the 3x3 part for the eye, the eye-space planes
// transformed by the transpose of the matrix), so the client's own view and
// the server's are the same function of the same bytes.
#include "lib/replay/stream_view.h"

#include <cmath>

#include "formats/mesh/vec3d.h"

namespace lodbake {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3d normalized(const Vec3d& v) {
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return len > 0 ? Vec3d{v[0] / len, v[1] / len, v[2] / len} : Vec3d{0, 0, 0};
}

}  // namespace

ViewRequest view_request_for(const CameraFrame& frame, const Viewport& viewport,
                             float near_distance, float tolerance_pixels) {
  const Vec3d eye{frame.eye[0], frame.eye[1], frame.eye[2]};
  const Vec3d f = normalized({double{frame.target[0]} - eye[0], double{frame.target[1]} - eye[1],
                              double{frame.target[2]} - eye[2]});
  const Vec3d s = normalized(cross(f, {frame.up[0], frame.up[1], frame.up[2]}));
  const Vec3d u = cross(s, f);
  ViewRequest r;
  // Rows s, u, -f; column-major: m[col * 4 + row].
  for (int c = 0; c < 3; ++c) {
    r.modelview[c * 4 + 0] = static_cast<float>(s[c]);
    r.modelview[c * 4 + 1] = static_cast<float>(u[c]);
    r.modelview[c * 4 + 2] = static_cast<float>(-f[c]);
    r.modelview[c * 4 + 3] = 0;
  }
  r.modelview[12] = static_cast<float>(-dot(s, eye));
  r.modelview[13] = static_cast<float>(-dot(u, eye));
  r.modelview[14] = static_cast<float>(dot(f, eye));
  r.modelview[15] = 1;
  r.fovy_degrees = frame.fov_degrees;
  r.aspect = viewport.height > 0 ? static_cast<float>(viewport.width) / viewport.height : 1.0f;
  r.tolerance = viewport.height > 0 ? tolerance_pixels / static_cast<float>(viewport.height) : 0;
  r.near_distance = near_distance;
  return r;
}

StreamView stream_view(const ViewRequest& request) {
  const std::array<float, 16>& m = request.modelview;
  auto at = [&m](int row, int col) { return double{m[col * 4 + row]}; };
  // Eye = -A^-1 t for the 3x3 part A and translation t (adjugate / det).
  double a[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      a[i][j] = at(i, j);
  }
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[2][1] * a[1][2]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[2][0] * a[1][2]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[2][0] * a[1][1]);
  double inv[3][3];
  inv[0][0] = (a[1][1] * a[2][2] - a[2][1] * a[1][2]) / det;
  inv[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
  inv[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
  inv[1][0] = (a[1][2] * a[2][0] - a[1][0] * a[2][2]) / det;
  inv[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
  inv[1][2] = (a[1][0] * a[0][2] - a[0][0] * a[1][2]) / det;
  inv[2][0] = (a[1][0] * a[2][1] - a[2][0] * a[1][1]) / det;
  inv[2][1] = (a[2][0] * a[0][1] - a[0][0] * a[2][1]) / det;
  inv[2][2] = (a[0][0] * a[1][1] - a[1][0] * a[0][1]) / det;
  const double t[3] = {at(0, 3), at(1, 3), at(2, 3)};
  StreamView view;
  for (int i = 0; i < 3; ++i) {
    view.params.eye[i] =
        static_cast<float>(-(inv[i][0] * t[0] + inv[i][1] * t[1] + inv[i][2] * t[2]));
  }
  const double tan_v = std::tan(double{request.fovy_degrees} * kPi / 360);
  const double tan_h = tan_v * request.aspect;
  // Eye-space planes (x, y, z, 1) . p >= 0 inside; the eye looks down -z.
  const double eye_planes[5][4] = {{0, 0, -1, -double{request.near_distance}},
                                   {1, 0, -tan_h, 0},
                                   {-1, 0, -tan_h, 0},
                                   {0, 1, -tan_v, 0},
                                   {0, -1, -tan_v, 0}};
  for (const auto& pe : eye_planes) {
    std::array<float, 4> pw{};
    for (int j = 0; j < 4; ++j) {
      double sum = 0;
      for (int i = 0; i < 4; ++i)
        sum += pe[i] * at(i, j);
      pw[j] = static_cast<float>(sum);
    }
    view.params.frustum.push_back(pw);
  }
  view.params.kappa = static_cast<float>(2 * double{request.tolerance} * tan_v);
  view.refine_all = request.tolerance == 0;
  return view;
}

}  // namespace lodbake
