#include "lib/meshio/polygon_triangulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

namespace lodbake {
namespace {

// Signed area of a triangle of points in the z = 0 plane (positive: CCW).
double signed_area_xy(const std::vector<Vec3f>& p, const Triangle& t) {
  const Vec3f& a = p[t[0]];
  const Vec3f& b = p[t[1]];
  const Vec3f& c = p[t[2]];
  return 0.5 * ((double{b[0]} - a[0]) * (double{c[1]} - a[1]) -
                (double{b[1]} - a[1]) * (double{c[0]} - a[0]));
}

double polygon_area_xy(const std::vector<Vec3f>& p, const std::vector<uint32_t>& ring) {
  double area = 0;
  for (size_t i = 0; i < ring.size(); ++i) {
    const Vec3f& a = p[ring[i]];
    const Vec3f& b = p[ring[(i + 1) % ring.size()]];
    area += double{a[0]} * b[1] - double{b[0]} * a[1];
  }
  return 0.5 * area;
}

std::vector<uint32_t> iota_ring(size_t n) {
  std::vector<uint32_t> ring(n);
  std::iota(ring.begin(), ring.end(), 0u);
  return ring;
}

struct Split {
  std::vector<Triangle> triangles;
  std::vector<Triangle> slots;
  TriangulationCounts counts;
};

Split split(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& ring) {
  Split s;
  Status status =
      triangulate_polygon(ring.data(), ring.size(), positions, &s.triangles, &s.slots, &s.counts);
  EXPECT_TRUE(status.is_ok()) << status.message();
  EXPECT_EQ(s.triangles.size(), s.slots.size());
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(s.triangles[t][k], ring[s.slots[t][k]]) << "slot maps back to the corner";
  }
  return s;
}

// Every triangle is wound like the (counter-clockwise) polygon, none has zero
// area, and together they cover exactly the polygon's area.
void expect_valid_ccw_triangulation(const std::vector<Vec3f>& p, const std::vector<uint32_t>& ring,
                                    const Split& s) {
  ASSERT_EQ(s.triangles.size(), ring.size() - 2);
  double sum = 0;
  for (const Triangle& t : s.triangles) {
    double a = signed_area_xy(p, t);
    EXPECT_GT(a, 1e-9) << "triangle " << t[0] << " " << t[1] << " " << t[2];
    sum += a;
  }
  EXPECT_NEAR(sum, polygon_area_xy(p, ring), 1e-9);
}

TEST(PolygonTriangulation, TrianglePassesThrough) {
  std::vector<Vec3f> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  Split s = split(p, {2, 0, 1});
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.triangles[0], (Triangle{2, 0, 1}));
  EXPECT_EQ(s.counts.polygons, 0u);
}

TEST(PolygonTriangulation, ConvexQuadIsFanFromFirstCorner) {
  std::vector<Vec3f> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  Split s = split(p, {0, 1, 2, 3});
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(s.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(s.slots[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(s.counts.polygons, 1u);
  EXPECT_EQ(s.counts.ear_clipped, 0u);
}

TEST(PolygonTriangulation, ClockwiseConvexHexagonInTiltedPlaneKeepsWinding) {
  // A regular hexagon in the plane x + y + z = 1, wound clockwise seen from +z.
  std::vector<Vec3f> p;
  for (int i = 0; i < 6; ++i) {
    double a = -i * M_PI / 3;
    float u = static_cast<float>(std::cos(a));
    float v = static_cast<float>(std::sin(a));
    p.push_back({u, v, 1 - u - v});
  }
  Split s = split(p, iota_ring(6));
  ASSERT_EQ(s.triangles.size(), 4u);
  for (uint32_t i = 0; i < 4; ++i)
    EXPECT_EQ(s.triangles[i], (Triangle{0, i + 1, i + 2}));
  for (const Triangle& t : s.triangles)
    EXPECT_LT(signed_area_xy(p, t), 0) << "clockwise like the polygon";
}

TEST(PolygonTriangulation, ConcaveLShape) {
  //  5---4
  //  |   |
  //  |   3---2
  //  |       |
  //  0-------1
  std::vector<Vec3f> p = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  for (size_t start = 0; start < 6; ++start) {
    std::vector<uint32_t> ring;
    for (size_t i = 0; i < 6; ++i)
      ring.push_back(static_cast<uint32_t>((start + i) % 6));
    Split s = split(p, ring);
    expect_valid_ccw_triangulation(p, ring, s);
    EXPECT_EQ(s.counts.ear_clipped, 1u);
    EXPECT_EQ(s.counts.self_intersecting, 0u);
  }
}

TEST(PolygonTriangulation, ConcaveStar) {
  std::vector<Vec3f> p;
  for (int i = 0; i < 10; ++i) {
    double a = i * M_PI / 5;
    double r = i % 2 == 0 ? 3.0 : 1.0;
    p.push_back({static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 5.0f});
  }
  std::vector<uint32_t> ring = iota_ring(10);
  Split s = split(p, ring);
  expect_valid_ccw_triangulation(p, ring, s);
  EXPECT_EQ(s.counts.ear_clipped, 1u);
}

TEST(PolygonTriangulation, CollinearCornerGivesNoZeroAreaTriangle) {
  // Square with an extra corner in the middle of its bottom edge, and a
  // triangle with midpoints on all three edges.
  std::vector<Vec3f> square = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  expect_valid_ccw_triangulation(square, iota_ring(5), split(square, iota_ring(5)));
  std::vector<Vec3f> tri = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}, {0, 2, 0}, {0, 1, 0}};
  expect_valid_ccw_triangulation(tri, iota_ring(6), split(tri, iota_ring(6)));
}

TEST(PolygonTriangulation, RepeatedConsecutiveCornersAreDropped) {
  std::vector<Vec3f> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  Split s = split(p, {0, 1, 1, 2, 3, 0});
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(s.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(s.slots[0], (Triangle{0, 1, 3})) << "slots point at the first of the repeats";
  EXPECT_EQ(s.counts.repeated_corners, 1u);
}

TEST(PolygonTriangulation, TooFewDistinctCornersAreFannedAsStored) {
  std::vector<Vec3f> p = {{0, 0, 0}, {1, 0, 0}};
  Split s = split(p, {0, 1, 0, 1});
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0], (Triangle{0, 1, 0}));
  EXPECT_EQ(s.triangles[1], (Triangle{0, 0, 1}));
  EXPECT_EQ(s.counts.degenerate, 1u);
}

TEST(PolygonTriangulation, ZeroAreaPolygonIsFanned) {
  std::vector<Vec3f> p = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {1.5f, 1.5f, 1.5f}};
  Split s = split(p, iota_ring(5));
  ASSERT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.triangles[2], (Triangle{0, 3, 4}));
  EXPECT_EQ(s.counts.degenerate, 1u);
}

TEST(PolygonTriangulation, NonFiniteCoordinatesAreFannedNotTrusted) {
  std::vector<Vec3f> p = {{0, 0, 0}, {NAN, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  Split s = split(p, iota_ring(4));
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.counts.degenerate, 1u);
}

TEST(PolygonTriangulation, PentagramIsReportedAsSelfIntersecting) {
  std::vector<Vec3f> p;
  for (int i = 0; i < 5; ++i) {
    double a = i * 4 * M_PI / 5;  // every second corner of a pentagon
    p.push_back({static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0});
  }
  Split s = split(p, iota_ring(5));
  EXPECT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.counts.self_intersecting, 1u);
  ImportReport report;
  PolygonTriangulator t;
  std::vector<Triangle> out;
  std::vector<uint32_t> ring = iota_ring(5);
  ASSERT_TRUE(t.triangulate(ring.data(), 5, p, &out, nullptr).is_ok());
  t.add_to_report(&report);
  EXPECT_EQ(report.polygons_triangulated, 1u);
  ASSERT_EQ(report.notes.size(), 1u);
  EXPECT_NE(report.notes[0].find("intersect themselves"), std::string::npos);
}

TEST(PolygonTriangulation, FigureEightWithCancellingAreaIsDegenerate) {
  // Bow-tie quad: its two lobes have opposite signed areas that cancel.
  std::vector<Vec3f> p = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  Split s = split(p, iota_ring(4));
  EXPECT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.counts.degenerate, 1u);
}

TEST(PolygonTriangulation, StuckEarClippingFallsBackToFan) {
  // A self-intersecting hexagon (found by a random search) in which, after
  // the first ear, every remaining convex corner's ear holds another corner.
  std::vector<Vec3f> p = {{0, 5, 0}, {3, 1, 0}, {18, 14, 0}, {2, 12, 0}, {8, 14, 0}, {20, 8, 0}};
  Split s = split(p, iota_ring(6));
  EXPECT_EQ(s.triangles.size(), 4u) << "still n - 2 triangles";
  EXPECT_EQ(s.counts.self_intersecting, 1u);
  EXPECT_EQ(s.counts.fallback_fanned, 1u);
  EXPECT_EQ(s.counts.ear_clipped, 0u);
  PolygonTriangulator t;
  std::vector<Triangle> out;
  std::vector<uint32_t> ring = iota_ring(6);
  ASSERT_TRUE(t.triangulate(ring.data(), 6, p, &out, nullptr).is_ok());
  EXPECT_EQ(out, s.triangles) << "deterministic";
  ImportReport report;
  t.add_to_report(&report);
  ASSERT_EQ(report.notes.size(), 2u);
  EXPECT_NE(report.notes[1].find("ear clipping could not finish"), std::string::npos);
}

TEST(PolygonTriangulation, SlitRingIsClippedWithoutOverlap) {
  // Square ring cut open along the edge 0-4 (outer square 0..3 CCW, inner
  // square 4..7 CW), the slit edge walked both ways: a weakly simple polygon.
  std::vector<Vec3f> p = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0},
                          {1, 1, 0}, {1, 3, 0}, {3, 3, 0}, {3, 1, 0}};
  std::vector<uint32_t> ring = {0, 1, 2, 3, 0, 4, 5, 6, 7, 4};
  Split s = split(p, ring);
  ASSERT_EQ(s.triangles.size(), 8u);
  EXPECT_EQ(s.counts.fallback_fanned, 0u);
  EXPECT_EQ(s.counts.self_intersecting, 0u);
  double sum = 0;
  for (const Triangle& t : s.triangles) {
    double a = signed_area_xy(p, t);
    EXPECT_GE(a, 0);
    sum += a;
  }
  EXPECT_NEAR(sum, 16.0 - 4.0, 1e-9) << "the triangles cover the ring exactly once";
}

TEST(PolygonTriangulation, OversizedConcavePolygonIsFannedAndCounted) {
  const size_t n = kMaxEarClipCorners + 2;
  std::vector<Vec3f> p;
  for (size_t i = 0; i < n; ++i) {
    double a = 2 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    double r = i % 2 == 0 ? 2.0 : 1.0;
    p.push_back({static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0});
  }
  Split s = split(p, iota_ring(n));
  EXPECT_EQ(s.triangles.size(), n - 2);
  EXPECT_EQ(s.counts.oversized_fanned, 1u);
}

TEST(PolygonTriangulation, WorkBudgetBoundsEarClippingOverAFile) {
  // A 100-corner star costs 100 * 100 steps and earns 64 * 100. With no
  // fixed allowance the budget after each polygon runs 6400 (fanned), 2800,
  // 9200 (fanned), 5600, 2000, 8400 (fanned), 4800, 1200, 7600 (fanned),
  // 4000: six clipped, four fanned, as the 64 steps per corner pay for.
  std::vector<Vec3f> p;
  for (int i = 0; i < 100; ++i) {
    double a = 2 * M_PI * i / 100;
    double r = i % 2 == 0 ? 2.0 : 1.0;
    p.push_back({static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0});
  }
  std::vector<uint32_t> ring = iota_ring(100);
  PolygonTriangulator t(0);
  std::vector<Triangle> out;
  for (int i = 0; i < 10; ++i)
    ASSERT_TRUE(t.triangulate(ring.data(), ring.size(), p, &out, nullptr).is_ok());
  EXPECT_EQ(out.size(), 10u * 98);
  EXPECT_EQ(t.counts().ear_clipped, 6u);
  EXPECT_EQ(t.counts().oversized_fanned, 4u);
  ImportReport report;
  t.add_to_report(&report);
  ASSERT_EQ(report.notes.size(), 1u);
  EXPECT_NE(report.notes[0].find("exceed the ear-clipping work limit"), std::string::npos);
}

TEST(PolygonTriangulation, RejectsShortFacesAndBadIndices) {
  std::vector<Vec3f> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<Triangle> out;
  uint32_t two[] = {0, 1};
  Status short_face = triangulate_polygon(two, 2, p, &out, nullptr);
  EXPECT_FALSE(short_face.is_ok());
  EXPECT_NE(short_face.message().find("at least 3"), std::string::npos);
  uint32_t bad[] = {0, 1, 7};
  Status range = triangulate_polygon(bad, 3, p, &out, nullptr);
  EXPECT_FALSE(range.is_ok());
  EXPECT_NE(range.message().find("out of range"), std::string::npos);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace lodbake
