// Camera paths (lib/replay/camera_path.h): built-in routes' frame counts,
// determinism and distances, the CSV reader's acceptance and its line-numbered
// rejections, and the frustum / kappa of one view.
#include "lib/replay/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace lodbake {
namespace {

double distance(const Vec3f& a, const Vec3f& b) {
  double s = 0;
  for (int i = 0; i < 3; ++i)
    s += (double{a[i]} - b[i]) * (double{a[i]} - b[i]);
  return std::sqrt(s);
}

BoundingSphere sample_sphere() {
  BoundingSphere s;
  s.center = {1, 2, 3};
  s.radius = 2;
  return s;
}

Result<std::vector<CameraFrame>> parse(const std::string& text) {
  return parse_camera_path_csv(reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

Result<std::vector<CameraFrame>> parse_any(const std::string& text) {
  return parse_camera_path(reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

TEST(CameraPath, BoundingSphereHoldsEveryPoint) {
  const std::vector<Vec3f> points = {{0, 0, 0}, {2, 0, 0}, {0, 4, 0}, {1, 1, -2}};
  const BoundingSphere s = bounding_sphere(points);
  EXPECT_FLOAT_EQ(s.center[0], 1);
  EXPECT_FLOAT_EQ(s.center[1], 2);
  EXPECT_FLOAT_EQ(s.center[2], -1);
  for (const Vec3f& p : points)
    EXPECT_LE(distance(p, s.center), s.radius);
  EXPECT_GT(bounding_sphere({}).radius, 0);
}

TEST(CameraPath, ScanHas180FramesApproachesAndRises) {
  const BoundingSphere s = sample_sphere();
  const std::vector<CameraFrame> path = scan_path(s, 45);
  ASSERT_EQ(path.size(), kScanFrames);
  EXPECT_EQ(path.size(), 180u);
  EXPECT_NEAR(distance(path.front().eye, path.front().target), 4 * s.radius, 1e-4);
  EXPECT_NEAR(distance(path.back().eye, path.back().target), 1.25 * s.radius, 1e-4);
  // Bottom to top: the eye's height never decreases and spans +-0.8 R.
  for (size_t i = 1; i < path.size(); ++i)
    EXPECT_GE(path[i].eye[1], path[i - 1].eye[1]);
  EXPECT_NEAR(path.front().eye[1], s.center[1] - 0.8 * s.radius, 1e-5);
  EXPECT_NEAR(path.back().eye[1], s.center[1] + 0.8 * s.radius, 1e-5);
  for (const CameraFrame& f : path)
    EXPECT_FLOAT_EQ(f.fov_degrees, 45);
}

TEST(CameraPath, OrbitHas194FramesAtTwoRadiiWithIncreasingSpeed) {
  const BoundingSphere s = sample_sphere();
  const std::vector<CameraFrame> path = orbit_path(s, 60);
  ASSERT_EQ(path.size(), kOrbitFrames);
  EXPECT_EQ(path.size(), 194u);
  EXPECT_NEAR(distance(path.front().eye, s.center), 4 * s.radius, 1e-4);
  for (size_t i = 29; i < path.size(); ++i) {
    EXPECT_NEAR(distance(path[i].eye, s.center), 2 * s.radius, 1e-4) << "frame " << i;
  }
  // Angular steps grow: compare an early and a late step.
  const double early = distance(path[31].eye, path[32].eye);
  const double late = distance(path[190].eye, path[191].eye);
  EXPECT_GT(late, 5 * early);
}

TEST(CameraPath, BuiltInPathsAreDeterministic) {
  const BoundingSphere s = sample_sphere();
  for (const char* name : {"scan", "orbit"}) {
    Result<std::vector<CameraFrame>> a = builtin_path(name, s, 60);
    Result<std::vector<CameraFrame>> b = builtin_path(name, s, 60);
    ASSERT_TRUE(a.is_ok() && b.is_ok());
    ASSERT_EQ(a.value().size(), b.value().size());
    for (size_t i = 0; i < a.value().size(); ++i) {
      EXPECT_EQ(a.value()[i].eye, b.value()[i].eye);
      EXPECT_EQ(a.value()[i].target, b.value()[i].target);
    }
  }
  Result<std::vector<CameraFrame>> bad = builtin_path("zoom", s, 60);
  ASSERT_FALSE(bad.is_ok());
  EXPECT_NE(bad.status().message().find("scan, orbit"), std::string::npos);
}

TEST(CameraPath, CsvReadsFramesSkippingCommentsAndBlanks) {
  Result<std::vector<CameraFrame>> path =
      parse("# recorded\n\n0,0,5, 0,0,0, 0,1,0, 60\r\n 1.5 ,2,3,0,0,0,0,0,1,45\n");
  ASSERT_TRUE(path.is_ok()) << path.status().message();
  ASSERT_EQ(path.value().size(), 2u);
  EXPECT_EQ(path.value()[0].eye, (Vec3f{0, 0, 5}));
  EXPECT_FLOAT_EQ(path.value()[1].eye[0], 1.5f);
  EXPECT_EQ(path.value()[1].up, (Vec3f{0, 0, 1}));
  EXPECT_FLOAT_EQ(path.value()[1].fov_degrees, 45);
}

TEST(CameraPath, CsvRejectsMalformedRowsWithLineNumbers) {
  const std::pair<std::string, std::string> cases[] = {
      {"0,0,5,0,0,0,0,1,0,60\n0,0,5,0,0,0,0,1,0\n", "line 2: 9 fields, expected 10"},
      {"0,0,5,0,0,0,0,1,0,60,1\n", "line 1: more than 10 fields"},
      {"#c\n0,0,x,0,0,0,0,1,0,60\n", "line 2: field 3 is not a finite number"},
      {"0,0,5,0,0,0,0,1,0,nan\n", "line 1: field 10 is not a finite number"},
      {"0,0,5,0,0,0,0,1,0,,\n", "line 1: field 10 is not a finite number"},
      {"0,0,5,0,0,0,0,1,0,180\n", "line 1: fov 180"},
      {"\n\n0,0,0,0,0,0,0,1,0,60\n", "line 3: eye and target coincide"},
      {"0,0,5,0,0,0,0,0,3,60\n", "line 1: up vector is zero or parallel"},
      {"0,0,5,0,0,0,0,0,0,60\n", "line 1: up vector is zero or parallel"},
      {"# only a comment\n", "camera path has no frames"},
      {"", "camera path has no frames"},
      {std::string(5000, ' ') + "\n", "line 1: longer than 4096 bytes"},
  };
  for (const auto& [text, expected] : cases) {
    Result<std::vector<CameraFrame>> path = parse(text);
    ASSERT_FALSE(path.is_ok()) << expected;
    EXPECT_EQ(path.status().kind(), ErrorKind::kInvalidInput);
    EXPECT_NE(path.status().message().find(expected), std::string::npos)
        << path.status().message() << " / expected " << expected;
  }
}

// The JSON form gives the same frames as the CSV form of the same path,
// bare or wrapped in {"frames": ...}, and parse_camera_path tells them apart.
TEST(CameraPath, JsonReadsTheSameFramesAsCsv) {
  const std::string csv = "0,0,5,0,0,0,0,1,0,60\n1,2,3,0,0,0,0,0,1,45.5\n";
  const std::string frames =
      R"([{"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 60},
          {"fov": 45.5, "up": [0, 0, 1], "target": [0, 0.0, 0], "eye": [1, 2, 3e0]}])";
  Result<std::vector<CameraFrame>> expected = parse(csv);
  ASSERT_TRUE(expected.is_ok());
  for (const std::string& text : {frames, "{\"frames\": " + frames + "}", "\n  " + frames}) {
    Result<std::vector<CameraFrame>> path = parse_any(text);
    ASSERT_TRUE(path.is_ok()) << path.status().message();
    ASSERT_EQ(path.value().size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(path.value()[i].eye, expected.value()[i].eye);
      EXPECT_EQ(path.value()[i].target, expected.value()[i].target);
      EXPECT_EQ(path.value()[i].up, expected.value()[i].up);
      EXPECT_EQ(path.value()[i].fov_degrees, expected.value()[i].fov_degrees);
    }
  }
  EXPECT_TRUE(parse_any(csv).is_ok());
}

TEST(CameraPath, JsonRejectsMalformedFramesWithFrameNumbers) {
  const std::string ok = R"({"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 60})";
  const std::pair<std::string, std::string> cases[] = {
      {"[" + ok + ", {\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"up\": [0, 1, 0]}]",
       "frame 2: needs eye, target, up and fov"},
      {R"([{"eye": [0, 0], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 60}])",
       "frame 1: 'eye' has 2 numbers, expected 3"},
      {R"([{"eye": [0, 0, 5, 1], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 60}])",
       "frame 1: 'eye' has more than 3 numbers"},
      {R"([{"eye": "here", "target": [0, 0, 0], "up": [0, 1, 0], "fov": 60}])",
       "frame 1: 'eye' is a string, expected an array of 3 numbers"},
      {R"([{"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": [60]}])",
       "frame 1: 'fov' is an array, expected a number"},
      {R"([{"eye": [0, 0, 5], "eye": [0, 0, 5]}])", "frame 1: 'eye' given twice"},
      {R"([{"eye": [0, 0, 5], "zoom": 2}])", "frame 1: unknown key 'zoom'"},
      {R"([{"eye": [0, 0, 5], "target": [0, 0, 5], "up": [0, 1, 0], "fov": 60}])",
       "frame 1: eye and target coincide"},
      {R"([{"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 1e400}])",
       "not valid JSON"},  // out of double range
      {R"([{"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 200}])",
       "frame 1: fov 200"},
      {"[" + ok + ", 3]", "frame 2: a number where a frame object was expected"},
      {"[[" + ok + "]]", "frame 1: an array where a frame object was expected"},
      {R"({"path": []})", "unknown key 'path' (expected 'frames')"},
      {"[" + ok, "not valid JSON"},
      {"[]", "camera path has no frames"},
      {"{}", "camera path has no frames"},
      {std::string(100000, '['), "where a frame object was expected"},
  };
  for (const auto& [text, expected] : cases) {
    Result<std::vector<CameraFrame>> path = parse_any(text);
    ASSERT_FALSE(path.is_ok()) << expected;
    EXPECT_EQ(path.status().kind(), ErrorKind::kInvalidInput);
    EXPECT_NE(path.status().message().find(expected), std::string::npos)
        << path.status().message() << " / expected " << expected;
  }
}

// Turning a path about the vertical axis keeps every eye's height and
// distance to the axis, turns it by the angle, and keeps up vectors.
TEST(CameraPath, TurnedAboutVerticalRotatesEyesAndTargets) {
  const BoundingSphere s = sample_sphere();
  const std::vector<CameraFrame> path = orbit_path(s, 60);
  const std::vector<CameraFrame> turned = turned_about_vertical(path, s, 90);
  ASSERT_EQ(turned.size(), path.size());
  for (size_t i = 0; i < path.size(); ++i) {
    const float x = path[i].eye[0] - s.center[0], z = path[i].eye[2] - s.center[2];
    EXPECT_NEAR(turned[i].eye[0] - s.center[0], z, 1e-4f);
    EXPECT_NEAR(turned[i].eye[2] - s.center[2], -x, 1e-4f);
    EXPECT_EQ(turned[i].eye[1], path[i].eye[1]);
    EXPECT_EQ(turned[i].up, path[i].up);
    EXPECT_EQ(turned[i].fov_degrees, path[i].fov_degrees);
  }
  const std::vector<CameraFrame> same = turned_about_vertical(path, s, 0);
  EXPECT_EQ(same[5].eye, path[5].eye);
}

TEST(CameraPath, ViewParametersFrustumAndKappa) {
  CameraFrame f;
  f.eye = {0, 0, 10};
  f.target = {0, 0, 0};
  f.fov_degrees = 90;
  Viewport viewport;
  viewport.width = 800;
  viewport.height = 800;
  const ViewParameters view = view_parameters(f, viewport, 0.5f, 2.0f);
  // kappa = 2 tau tan(45 deg) with tau = 2 / 800.
  EXPECT_NEAR(view.kappa, 2 * (2.0 / 800), 1e-7);
  ASSERT_EQ(view.frustum.size(), 5u);
  auto inside = [&](const Vec3f& p) {
    for (const auto& q : view.frustum) {
      if (q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] < -1e-5f) return false;
    }
    return true;
  };
  EXPECT_TRUE(inside({0, 0, 0}));
  EXPECT_TRUE(inside({9, 0, 0}));    // 10 units ahead, 90 deg fov: |x| <= 10
  EXPECT_FALSE(inside({11, 0, 0}));  // right of the frustum
  EXPECT_FALSE(inside({0, -11, 0}));
  EXPECT_FALSE(inside({0, 0, 9.7f}));  // before the near plane
  EXPECT_FALSE(inside({0, 0, 20}));    // behind the eye
}

}  // namespace
}  // namespace lodbake
