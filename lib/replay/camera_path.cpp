// Camera paths (issue 8). The DAG paper describes its two routes only in
// words ("moves close to the model and scans it from bottom to top", "moves
// close and rotates around the model with increasing speed"); the distances,
// heights and the quadratic speed-up here are our choice, fixed relative to
// the bounding sphere so that every model is replayed the same way. The
// CSV reader is hostile-input safe: it never allocates more than one frame
// per line of input and stops at kMaxPathFrames.
#include "lib/replay/camera_path.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>

namespace lodbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr size_t kApproachFrames = 30;

Vec3f at(const BoundingSphere& s, double x, double y, double z) {
  return {static_cast<float>(s.center[0] + x), static_cast<float>(s.center[1] + y),
          static_cast<float>(s.center[2] + z)};
}

double lerp(double a, double b, double t) {
  return a + (b - a) * t;
}

CameraFrame frame(const Vec3f& eye, const Vec3f& target, float fov) {
  CameraFrame f;
  f.eye = eye;
  f.target = target;
  f.up = {0, 1, 0};
  f.fov_degrees = fov;
  return f;
}

using Vec3d = std::array<double, 3>;
Vec3d to_d(const Vec3f& v) {
  return {v[0], v[1], v[2]};
}
Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3d normalized(const Vec3d& v) {
  const double len = std::sqrt(dot(v, v));
  return len > 0 ? Vec3d{v[0] / len, v[1] / len, v[2] / len} : Vec3d{0, 0, 0};
}
std::array<float, 4> plane(const Vec3d& normal, const Vec3d& point) {
  const Vec3d n = normalized(normal);
  return {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]),
          static_cast<float>(-dot(n, point))};
}

// Fields of one line: trims blanks around each, parses with from_chars (no
// locale, no allocation beyond the output).
Status parse_line(const std::string& line, size_t line_number, CameraFrame* out) {
  const std::string where = "line " + std::to_string(line_number) + ": ";
  double v[10];
  size_t count = 0;
  size_t pos = 0;
  while (true) {
    const size_t comma = line.find(',', pos);
    const size_t end = comma == std::string::npos ? line.size() : comma;
    size_t b = pos, e = end;
    while (b < e && (line[b] == ' ' || line[b] == '\t'))
      ++b;
    while (e > b && (line[e - 1] == ' ' || line[e - 1] == '\t' || line[e - 1] == '\r'))
      --e;
    if (count == 10) {
      return invalid_input(where +
                           "more than 10 fields (expected eye xyz, target xyz, up xyz, fov)");
    }
    double value = 0;
    const auto parsed = std::from_chars(line.data() + b, line.data() + e, value);
    if (b == e || parsed.ec != std::errc() || parsed.ptr != line.data() + e ||
        !std::isfinite(value)) {
      return invalid_input(where + "field " + std::to_string(count + 1) +
                           " is not a finite number");
    }
    v[count++] = value;
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  if (count != 10) {
    return invalid_input(where + std::to_string(count) +
                         " fields, expected 10 (eye xyz, target xyz, up xyz, fov)");
  }
  for (double x : v) {
    if (std::fabs(x) > 1e30) return invalid_input(where + "a value exceeds 1e30 in magnitude");
  }
  if (!(v[9] > 0 && v[9] < 180)) {
    return invalid_input(where + "fov " + std::to_string(v[9]) + " is not in (0, 180) degrees");
  }
  const Vec3d forward = sub({v[3], v[4], v[5]}, {v[0], v[1], v[2]});
  const Vec3d up{v[6], v[7], v[8]};
  if (dot(forward, forward) == 0) return invalid_input(where + "eye and target coincide");
  const Vec3d side = cross(normalized(forward), normalized(up));
  if (dot(up, up) == 0 || dot(side, side) < 1e-12) {
    return invalid_input(where + "up vector is zero or parallel to the view direction");
  }
  for (int i = 0; i < 3; ++i) {
    out->eye[i] = static_cast<float>(v[i]);
    out->target[i] = static_cast<float>(v[3 + i]);
    out->up[i] = static_cast<float>(v[6 + i]);
  }
  out->fov_degrees = static_cast<float>(v[9]);
  if (out->eye == out->target) return invalid_input(where + "eye and target coincide");
  return Status();
}

}  // namespace

BoundingSphere bounding_sphere(const std::vector<Vec3f>& points) {
  BoundingSphere s;
  if (points.empty()) {
    s.radius = 1;
    return s;
  }
  Vec3f lo = points[0], hi = points[0];
  for (const Vec3f& p : points) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
  Vec3d c{};
  for (int i = 0; i < 3; ++i)
    c[i] = 0.5 * (double{lo[i]} + double{hi[i]});
  double r2 = 0;
  for (const Vec3f& p : points)
    r2 = std::max(r2, dot(sub(to_d(p), c), sub(to_d(p), c)));
  for (int i = 0; i < 3; ++i)
    s.center[i] = static_cast<float>(c[i]);
  // Float rounding of the centre must not leave a point outside.
  s.radius = std::max(static_cast<float>(std::sqrt(r2) * (1 + 1e-6)), 1e-6f);
  return s;
}

std::vector<CameraFrame> scan_path(const BoundingSphere& s, float fov) {
  const double r = s.radius;
  std::vector<CameraFrame> path;
  path.reserve(kScanFrames);
  for (size_t i = 0; i < kScanFrames; ++i) {
    double distance = 1.25 * r, height = -0.8 * r;
    if (i < kApproachFrames) {
      distance = lerp(4 * r, 1.25 * r, static_cast<double>(i) / (kApproachFrames - 1));
    } else {
      const double t =
          static_cast<double>(i - kApproachFrames) / (kScanFrames - kApproachFrames - 1);
      height = lerp(-0.8 * r, 0.8 * r, t);
    }
    path.push_back(frame(at(s, 0, height, distance), at(s, 0, height, 0), fov));
  }
  return path;
}

std::vector<CameraFrame> orbit_path(const BoundingSphere& s, float fov) {
  const double r = s.radius;
  std::vector<CameraFrame> path;
  path.reserve(kOrbitFrames);
  for (size_t i = 0; i < kOrbitFrames; ++i) {
    double distance = 2 * r, angle = 0;
    if (i < kApproachFrames) {
      distance = lerp(4 * r, 2 * r, static_cast<double>(i) / (kApproachFrames - 1));
    } else {
      const double t =
          static_cast<double>(i - kApproachFrames) / (kOrbitFrames - kApproachFrames - 1);
      angle = 4 * kPi * t * t;
    }
    path.push_back(
        frame(at(s, distance * std::sin(angle), 0, distance * std::cos(angle)), s.center, fov));
  }
  return path;
}

Result<std::vector<CameraFrame>> builtin_path(const std::string& name, const BoundingSphere& s,
                                              float fov) {
  if (name == "scan") return scan_path(s, fov);
  if (name == "orbit") return orbit_path(s, fov);
  return invalid_input("unknown camera path '" + name + "' (built in: scan, orbit)");
}

Result<std::vector<CameraFrame>> parse_camera_path_csv(const uint8_t* data, size_t size) {
  try {
    std::vector<CameraFrame> path;
    size_t line_number = 0;
    size_t pos = 0;
    std::string line;
    while (pos < size) {
      ++line_number;
      const uint8_t* nl = static_cast<const uint8_t*>(std::memchr(data + pos, '\n', size - pos));
      const size_t end = nl == nullptr ? size : static_cast<size_t>(nl - data);
      if (end - pos > kMaxPathLineBytes) {
        return invalid_input("line " + std::to_string(line_number) + ": longer than " +
                             std::to_string(kMaxPathLineBytes) + " bytes");
      }
      line.assign(reinterpret_cast<const char*>(data + pos), end - pos);
      pos = end + 1;
      const size_t first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      if (path.size() == kMaxPathFrames) {
        return invalid_input("line " + std::to_string(line_number) + ": more than " +
                             std::to_string(kMaxPathFrames) + " frames");
      }
      CameraFrame f;
      LODBAKE_RETURN_IF_ERROR(parse_line(line, line_number, &f));
      path.push_back(f);
    }
    if (path.empty()) return invalid_input("camera path has no frames");
    return path;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory reading the camera path");
  }
}

ViewParameters view_parameters(const CameraFrame& f, const Viewport& viewport, float near_distance,
                               float tolerance_pixels) {
  const Vec3d eye = to_d(f.eye);
  const Vec3d fw = normalized(sub(to_d(f.target), eye));
  const Vec3d right = normalized(cross(fw, to_d(f.up)));
  const Vec3d up = cross(right, fw);
  const double tan_v = std::tan(double{f.fov_degrees} * kPi / 360);
  const double aspect =
      viewport.height > 0 ? static_cast<double>(viewport.width) / viewport.height : 1.0;
  const double tan_h = tan_v * aspect;
  auto mix = [](const Vec3d& a, double ka, const Vec3d& b, double kb) {
    return Vec3d{a[0] * ka + b[0] * kb, a[1] * ka + b[1] * kb, a[2] * ka + b[2] * kb};
  };
  ViewParameters view;
  view.eye = f.eye;
  const Vec3d near_point = mix(eye, 1, fw, near_distance);
  view.frustum.push_back(plane(fw, near_point));
  view.frustum.push_back(plane(mix(fw, tan_h, right, -1), eye));
  view.frustum.push_back(plane(mix(fw, tan_h, right, 1), eye));
  view.frustum.push_back(plane(mix(fw, tan_v, up, -1), eye));
  view.frustum.push_back(plane(mix(fw, tan_v, up, 1), eye));
  const double tau = viewport.height > 0 ? double{tolerance_pixels} / viewport.height : 0;
  view.kappa = static_cast<float>(2 * tau * tan_v);
  return view;
}

}  // namespace lodbake
