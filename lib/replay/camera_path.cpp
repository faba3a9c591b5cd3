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
#include <nlohmann/json.hpp>
#include <string>

#include "formats/mesh/vec3d.h"

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

Vec3d normalized(const Vec3d& v) {
  const double len = std::sqrt(dot(v, v));
  return len > 0 ? Vec3d{v[0] / len, v[1] / len, v[2] / len} : Vec3d{0, 0, 0};
}
std::array<float, 4> plane(const Vec3d& normal, const Vec3d& point) {
  const Vec3d n = normalized(normal);
  return {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]),
          static_cast<float>(-dot(n, point))};
}

// The checks every recorded frame passes, whatever its file format: v holds
// eye xyz, target xyz, up xyz and the fov in degrees; `where` prefixes the
// message ("line N: ", "frame N: ").
Status check_frame(const double v[10], const std::string& where, CameraFrame* out) {
  for (int i = 0; i < 10; ++i) {
    if (!std::isfinite(v[i])) return invalid_input(where + "a value is not a finite number");
    if (std::fabs(v[i]) > 1e30) return invalid_input(where + "a value exceeds 1e30 in magnitude");
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
  return check_frame(v, where, out);
}

// Builds frames straight from SAX events, so memory stays one frame per
// frame of input whatever the nesting or size of the document: an array of
// frames, or an object whose only key "frames" holds one; each frame an
// object with exactly the keys eye, target, up (arrays of 3 numbers) and fov.
class PathSax {
 public:
  std::vector<CameraFrame> frames;
  std::string error;

  bool null() { return fail_value("null"); }
  bool boolean(bool) { return fail_value("a boolean"); }
  bool number_integer(int64_t v) { return number(static_cast<double>(v)); }
  bool number_unsigned(uint64_t v) { return number(static_cast<double>(v)); }
  bool number_float(double v, const std::string&) { return number(v); }
  bool string(std::string&) { return fail_value("a string"); }
  bool binary(std::vector<uint8_t>&) { return fail_value("binary data"); }
  bool start_object(size_t) {
    if (state_ == kStart) {
      state_ = kTopObject;
      return true;
    }
    if (state_ == kFrames) {
      if (frames.size() == kMaxPathFrames) {
        return fail("more than " + std::to_string(kMaxPathFrames) + " frames");
      }
      state_ = kFrame;
      seen_ = 0;
      return true;
    }
    return fail_value("an object");
  }
  bool key(std::string& k) {
    if (state_ == kTopObject) {
      if (k != "frames") return fail("unknown key '" + k.substr(0, 64) + "' (expected 'frames')");
      state_ = kFramesKey;
      return true;
    }
    static const char* const kKeys[4] = {"eye", "target", "up", "fov"};
    for (int i = 0; i < 4; ++i) {
      if (k != kKeys[i]) continue;
      if ((seen_ & (1u << i)) != 0) return fail(where() + "'" + k + "' given twice");
      seen_ |= 1u << i;
      field_ = i;
      state_ = kFrameValue;
      return true;
    }
    return fail(where() + "unknown key '" + k.substr(0, 64) + "' (expected eye, target, up, fov)");
  }
  bool end_object() {
    if (state_ == kTopObject) {
      state_ = kDone;
      return true;
    }
    // state_ == kFrame: the SAX parser pairs braces.
    if (seen_ != 15) return fail(where() + "needs eye, target, up and fov");
    CameraFrame f;
    const Status checked = check_frame(v_, where(), &f);
    if (!checked.is_ok()) return fail(checked.message());
    frames.push_back(f);
    state_ = kFrames;
    return true;
  }
  bool start_array(size_t) {
    if (state_ == kStart || state_ == kFramesKey) {
      wrapped_ = state_ == kFramesKey;
      state_ = kFrames;
      return true;
    }
    if (state_ == kFrameValue && field_ < 3) {
      state_ = kVector;
      count_ = 0;
      return true;
    }
    return fail_value("an array");
  }
  bool end_array() {
    if (state_ == kFrames) {
      state_ = wrapped_ ? kTopObject : kDone;
      return true;
    }
    // state_ == kVector
    if (count_ != 3)
      return fail(where() + "'" + name() + "' has " + std::to_string(count_) +
                  " numbers, expected 3");
    state_ = kFrame;
    return true;
  }
  bool parse_error(size_t position, const std::string&, const nlohmann::detail::exception&) {
    if (error.empty()) error = "byte " + std::to_string(position) + ": not valid JSON";
    return false;
  }

 private:
  enum State { kStart, kTopObject, kFramesKey, kFrames, kFrame, kFrameValue, kVector, kDone };

  std::string where() const { return "frame " + std::to_string(frames.size() + 1) + ": "; }
  std::string name() const {
    static const char* const kKeys[4] = {"eye", "target", "up", "fov"};
    return kKeys[field_];
  }
  bool fail(const std::string& message) {
    if (error.empty()) error = message;
    return false;
  }
  bool fail_value(const char* what) {
    if (state_ == kFrameValue || state_ == kVector) {
      return fail(where() + "'" + name() + "' is " + what +
                  (field_ < 3 ? ", expected an array of 3 numbers" : ", expected a number"));
    }
    if (state_ == kFrames) return fail(where() + what + " where a frame object was expected");
    return fail(std::string(what) +
                " where an array of frames or {\"frames\": [...]} was expected");
  }
  bool number(double value) {
    if (state_ == kVector && count_ < 3) {
      v_[3 * field_ + count_++] = value;
      return true;
    }
    if (state_ == kVector) return fail(where() + "'" + name() + "' has more than 3 numbers");
    if (state_ == kFrameValue && field_ == 3) {
      v_[9] = value;
      state_ = kFrame;
      return true;
    }
    return fail_value("a number");
  }

  State state_ = kStart;
  bool wrapped_ = false;
  unsigned seen_ = 0;
  int field_ = 0;
  int count_ = 0;
  double v_[10] = {};
};

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

std::vector<CameraFrame> turned_about_vertical(std::vector<CameraFrame> path,
                                               const BoundingSphere& sphere, float degrees) {
  const float a = degrees * 3.14159265f / 180, c = std::cos(a), s = std::sin(a);
  for (CameraFrame& f : path) {
    for (Vec3f* p : {&f.eye, &f.target}) {
      const float x = (*p)[0] - sphere.center[0], z = (*p)[2] - sphere.center[2];
      (*p)[0] = sphere.center[0] + c * x + s * z;
      (*p)[2] = sphere.center[2] - s * x + c * z;
    }
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

Result<std::vector<CameraFrame>> parse_camera_path_json(const uint8_t* data, size_t size) {
  try {
    PathSax sax;
    const bool parsed = nlohmann::json::sax_parse(data, data + size, &sax);
    if (!parsed || !sax.error.empty()) {
      return invalid_input(sax.error.empty() ? std::string("not valid JSON") : sax.error);
    }
    if (sax.frames.empty()) return invalid_input("camera path has no frames");
    return std::move(sax.frames);
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory reading the camera path");
  }
}

Result<std::vector<CameraFrame>> parse_camera_path(const uint8_t* data, size_t size) {
  size_t i = 0;
  while (i < size && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n'))
    ++i;
  if (i < size && (data[i] == '[' || data[i] == '{')) return parse_camera_path_json(data, size);
  return parse_camera_path_csv(data, size);
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
