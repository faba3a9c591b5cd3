// The wedge collapse engine on meshes built to show one behaviour each:
// seams keep their course, texture charts do not fold, the attribute error
// steers the collapses, seam corners hold a mesh and say so.
#include "lib/simplify/wedge_collapse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace lodbake {
namespace {

using UvOf = std::function<Vec2f(double x, double y)>;

// A flat n x n grid of unit squares in z = 0, counter-clockwise seen from
// +z. Each point has one wedge with uv_of(x, y), except that the points on
// the column x = seam_column (when given) have a second wedge for the
// faces right of it, with uv_of(x, y) shifted by 10 in u.
WedgeMesh grid(int n, const UvOf& uv_of, int seam_column = -1, double weight = 1.0) {
  WedgeMesh m;
  auto point = [n](int x, int y) { return static_cast<uint32_t>(y * (n + 1) + x); };
  m.value_offset.push_back(0);
  auto add_wedge = [&](uint32_t p, Vec2f uv) {
    m.wedge_point.push_back(p);
    m.values.push_back(static_cast<float>(weight * uv[0]));
    m.values.push_back(static_cast<float>(weight * uv[1]));
    m.value_offset.push_back(static_cast<uint32_t>(m.values.size()));
    m.uv.push_back(uv);
    m.normal.push_back({0, 0, 1});
    m.has_uv.push_back(1);
    m.has_normal.push_back(1);
    return static_cast<uint32_t>(m.wedge_point.size() - 1);
  };
  std::vector<uint32_t> left(static_cast<size_t>((n + 1) * (n + 1))), right(left.size());
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      m.points.push_back({double(x), double(y), 0});
      const Vec2f uv = uv_of(x, y);
      left[point(x, y)] = right[point(x, y)] = add_wedge(point(x, y), uv);
      if (x == seam_column) right[point(x, y)] = add_wedge(point(x, y), {uv[0] + 10, uv[1]});
    }
  auto add = [&](int ax, int ay, int bx, int by, int cx, int cy, bool is_right) {
    const std::vector<uint32_t>& w = is_right ? right : left;
    m.triangles.push_back({point(ax, ay), point(bx, by), point(cx, cy)});
    m.corner_wedge.push_back({w[point(ax, ay)], w[point(bx, by)], w[point(cx, cy)]});
  };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const bool is_right = seam_column >= 0 && x >= seam_column;
      add(x, y, x + 1, y, x + 1, y + 1, is_right);
      add(x, y, x + 1, y + 1, x, y + 1, is_right);
    }
  return m;
}

Vec2f linear_uv(double x, double y) {
  return {static_cast<float>(x / 16), static_cast<float>(y / 16)};
}

double uv_area(const WedgeMesh& m, const std::array<uint32_t, 3>& w) {
  const Vec2f &a = m.uv[w[0]], &b = m.uv[w[1]], &c = m.uv[w[2]];
  return (double{b[0]} - a[0]) * (double{c[1]} - a[1]) -
         (double{b[1]} - a[1]) * (double{c[0]} - a[0]);
}

TEST(WedgeCollapse, ReachesItsTargetsOnASeamlessGrid) {
  const WedgeMesh m = grid(16, linear_uv);
  WedgeCollapseOptions options;
  options.targets = {256, 51};
  Result<WedgeCollapseResult> r = collapse_wedges(m, options);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  ASSERT_EQ(r.value().levels.size(), 2u);
  EXPECT_LE(r.value().levels[0].triangles.size(), 256u);
  EXPECT_GT(r.value().levels[0].triangles.size(), 250u);
  EXPECT_LE(r.value().levels[1].triangles.size(), 51u);
  EXPECT_FALSE(r.value().blocked.has_value());
  // A corner's wedge is always one of its point's.
  for (const WedgeLevel& level : r.value().levels)
    for (size_t f = 0; f < level.triangles.size(); ++f)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(level.wedge_point[level.corner_wedge[f][k]], level.triangles[f][k]);
}

TEST(WedgeCollapse, ASeamKeepsItsCourseAndBothSidesTheirWedges) {
  const int n = 16, seam = 7;
  const WedgeMesh m = grid(n, linear_uv, seam);
  WedgeCollapseOptions options;
  options.targets = {40};
  Result<WedgeCollapseResult> r = collapse_wedges(m, options);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const WedgeLevel& level = r.value().levels.at(0);
  EXPECT_LE(level.triangles.size(), 40u);
  for (size_t f = 0; f < level.triangles.size(); ++f) {
    // No face straddles the seam's line, and a face's corners on it keep
    // the wedge of its side (the right side's have u >= 10).
    double min_x = 1e9, max_x = -1e9;
    for (int k = 0; k < 3; ++k) {
      const double x = m.points[level.triangles[f][k]][0];
      min_x = std::min(min_x, x);
      max_x = std::max(max_x, x);
    }
    EXPECT_TRUE(max_x <= seam || min_x >= seam) << "face " << f;
    for (int k = 0; k < 3; ++k) {
      if (m.points[level.triangles[f][k]][0] != seam) continue;
      EXPECT_EQ(m.uv[level.corner_wedge[f][k]][0] >= 10, min_x >= seam) << "face " << f;
    }
  }
}

TEST(WedgeCollapse, NoTextureChartFolds) {
  // A wavy parametrisation: a corner moved far along it would fold.
  const WedgeMesh m = grid(20, [](double x, double y) {
    return Vec2f{static_cast<float>(x / 20 + 0.04 * std::sin(y)),
                 static_cast<float>(y / 20 + 0.04 * std::sin(x * 1.3))};
  });
  for (const auto& w : m.corner_wedge)
    ASSERT_GT(uv_area(m, w), 0);
  WedgeCollapseOptions options;
  options.targets = {20};
  Result<WedgeCollapseResult> r = collapse_wedges(m, options);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const WedgeLevel& level = r.value().levels.at(0);
  ASSERT_FALSE(level.triangles.empty());
  for (const auto& w : level.corner_wedge)
    EXPECT_GT(uv_area(m, w), 0);
}

// The grid of linear_uv() with a second texture coordinate set, wavy and
// not in the error, so that only the fold check holds it; `check_second`
// false leaves set 1 out of the checks (its has_uv bit clear).
WedgeMesh grid_with_wavy_second_set(bool check_second) {
  WedgeMesh m = grid(20, linear_uv);
  std::vector<Vec2f> uv;
  for (size_t w = 0; w < m.wedge_point.size(); ++w) {
    const Vec3d& p = m.points[m.wedge_point[w]];
    uv.push_back(m.uv[w]);
    uv.push_back({static_cast<float>(p[0] / 20 + 0.04 * std::sin(p[1])),
                  static_cast<float>(p[1] / 20 + 0.04 * std::sin(p[0] * 1.3))});
    m.has_uv[w] = check_second ? 3 : 1;
  }
  m.uv = std::move(uv);
  m.uv_sets = 2;
  return m;
}

// Faces of `level` whose second set's signed area is not positive.
size_t folded_in_second_set(const WedgeMesh& m, const WedgeLevel& level) {
  size_t folded = 0;
  for (const auto& w : level.corner_wedge) {
    const Vec2f &a = m.uv[w[0] * 2 + 1], &b = m.uv[w[1] * 2 + 1], &c = m.uv[w[2] * 2 + 1];
    const double area = (double{b[0]} - a[0]) * (double{c[1]} - a[1]) -
                        (double{b[1]} - a[1]) * (double{c[0]} - a[0]);
    folded += area > 0 ? 0 : 1;
  }
  return folded;
}

TEST(WedgeCollapse, NoChartFoldsInAnyTextureCoordinateSet) {
  WedgeCollapseOptions options;
  options.targets = {20};
  // Unchecked, the collapses steered by set 0 alone fold set 1: the case
  // the check has to catch.
  const WedgeMesh unchecked = grid_with_wavy_second_set(false);
  Result<WedgeCollapseResult> folded = collapse_wedges(unchecked, options);
  ASSERT_TRUE(folded.is_ok()) << folded.status().message();
  EXPECT_GT(folded_in_second_set(unchecked, folded.value().levels.at(0)), 0u);

  const WedgeMesh checked = grid_with_wavy_second_set(true);
  Result<WedgeCollapseResult> kept = collapse_wedges(checked, options);
  ASSERT_TRUE(kept.is_ok()) << kept.status().message();
  const WedgeLevel& level = kept.value().levels.at(0);
  ASSERT_FALSE(level.triangles.empty());
  EXPECT_EQ(folded_in_second_set(checked, level), 0u);
}

TEST(WedgeCollapse, RefusesTextureCoordinateSetsThatDoNotMatch) {
  WedgeMesh m = grid_with_wavy_second_set(true);
  m.uv.pop_back();
  EXPECT_FALSE(collapse_wedges(m, WedgeCollapseOptions{}).is_ok());
  m = grid_with_wavy_second_set(true);
  m.uv_sets = WedgeMesh::kMaxUvSets + 1;
  EXPECT_FALSE(collapse_wedges(m, WedgeCollapseOptions{}).is_ok());
}

// Points kept inside the square [lo, hi]^2 of a flat grid whose texture is
// linear except for a bump there.
size_t kept_in_bump(double weight) {
  const WedgeMesh m = grid(
      24,
      [](double x, double y) {
        const double r2 = (x - 12) * (x - 12) + (y - 12) * (y - 12);
        return Vec2f{static_cast<float>(x / 24 + 0.2 * std::exp(-r2 / 8)),
                     static_cast<float>(y / 24)};
      },
      -1, weight);
  WedgeCollapseOptions options;
  options.targets = {200};
  Result<WedgeCollapseResult> r = collapse_wedges(m, options);
  EXPECT_TRUE(r.is_ok());
  if (!r.is_ok()) return 0;
  std::vector<uint8_t> used(m.points.size(), 0);
  for (const Triangle& t : r.value().levels.at(0).triangles)
    for (uint32_t v : t)
      used[v] = 1;
  size_t kept = 0;
  for (size_t v = 0; v < m.points.size(); ++v)
    if (used[v] && std::fabs(m.points[v][0] - 12) <= 4 && std::fabs(m.points[v][1] - 12) <= 4)
      ++kept;
  return kept;
}

TEST(WedgeCollapse, TheAttributeErrorKeepsPointsWhereTheTextureBends) {
  // Flat: the geometry costs nothing anywhere; only the texture's error
  // tells the bump from the rest.
  const size_t without = kept_in_bump(0.0);
  const size_t with = kept_in_bump(1.0);
  EXPECT_GT(with, without + 5) << "with " << with << ", without " << without;
}

// A unit cube whose six faces are six texture charts: every corner is a
// seam corner.
WedgeMesh cube() {
  WedgeMesh m;
  for (int i = 0; i < 8; ++i)
    m.points.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  const Vec2f corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.value_offset.push_back(0);
  for (const auto& q : quads) {
    uint32_t w[4];
    for (int k = 0; k < 4; ++k) {
      w[k] = static_cast<uint32_t>(m.wedge_point.size());
      m.wedge_point.push_back(static_cast<uint32_t>(q[k]));
      m.values.insert(m.values.end(), {corners[k][0], corners[k][1]});
      m.value_offset.push_back(static_cast<uint32_t>(m.values.size()));
      m.uv.push_back(corners[k]);
      m.normal.push_back({});
      m.has_uv.push_back(1);
      m.has_normal.push_back(0);
    }
    m.triangles.push_back({uint32_t(q[0]), uint32_t(q[1]), uint32_t(q[2])});
    m.corner_wedge.push_back({w[0], w[1], w[2]});
    m.triangles.push_back({uint32_t(q[0]), uint32_t(q[2]), uint32_t(q[3])});
    m.corner_wedge.push_back({w[0], w[2], w[3]});
  }
  return m;
}

TEST(WedgeCollapse, SeamCornersHoldTheMeshAndSaySo) {
  WedgeCollapseOptions options;
  options.targets = {2};
  Result<WedgeCollapseResult> locked = collapse_wedges(cube(), options);
  ASSERT_TRUE(locked.is_ok()) << locked.status().message();
  EXPECT_EQ(locked.value().levels.at(0).triangles.size(), 12u);
  ASSERT_TRUE(locked.value().blocked.has_value());
  EXPECT_EQ(locked.value().blocked->seam_corners, 8u);

  options.permissive = true;
  Result<WedgeCollapseResult> moved = collapse_wedges(cube(), options);
  ASSERT_TRUE(moved.is_ok()) << moved.status().message();
  EXPECT_LT(moved.value().levels.at(0).triangles.size(), 12u);
  // A wedge of a removed corner keeps its values at the survivor.
  size_t moved_wedges = 0;
  const WedgeMesh in = cube();
  for (size_t w = 0; w < in.wedge_point.size(); ++w)
    moved_wedges += moved.value().levels[0].wedge_point[w] != in.wedge_point[w] ? 1 : 0;
  EXPECT_GT(moved_wedges, 0u);
}

TEST(WedgeCollapse, ASeamReleaseLeavesCheapCollapsesAsTheyAre) {
  // A flat grid with a seam: collapses that keep it cost nothing, so with a
  // release bound the run is the locked run.
  const WedgeMesh m = grid(16, linear_uv, 5);
  WedgeCollapseOptions locked;
  locked.targets = {200, 60};
  WedgeCollapseOptions released = locked;
  released.seam_release = 0.01;
  Result<WedgeCollapseResult> a = collapse_wedges(m, locked);
  Result<WedgeCollapseResult> b = collapse_wedges(m, released);
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a.value().levels.at(i).triangles, b.value().levels.at(i).triangles);
    EXPECT_EQ(a.value().levels.at(i).corner_wedge, b.value().levels.at(i).corner_wedge);
  }
}

TEST(WedgeCollapse, ABoxStaysABoxUnderASeamRelease) {
  // Every collapse of a textured cube moves a chart by half its size: far
  // more than the release's cap, so the seams hold as they do locked.
  WedgeCollapseOptions options;
  options.targets = {2};
  options.seam_release = 0.01;
  Result<WedgeCollapseResult> r = collapse_wedges(cube(), options);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().levels.at(0).triangles.size(), 12u);
  options.seam_release = 1.0;
  Result<WedgeCollapseResult> loose = collapse_wedges(cube(), options);
  ASSERT_TRUE(loose.is_ok());
  EXPECT_LT(loose.value().levels.at(0).triangles.size(), 12u);
  // An infinite bound is no release.
  options.seam_release = HUGE_VAL;
  Result<WedgeCollapseResult> never = collapse_wedges(cube(), options);
  ASSERT_TRUE(never.is_ok());
  EXPECT_EQ(never.value().levels.at(0).triangles.size(), 12u);
  options.seam_release = -1.0;
  EXPECT_FALSE(collapse_wedges(cube(), options).is_ok());
}

TEST(WedgeCollapse, Deterministic) {
  const WedgeMesh m = grid(12, linear_uv, 5);
  WedgeCollapseOptions options;
  options.targets = {100, 30};
  Result<WedgeCollapseResult> a = collapse_wedges(m, options);
  Result<WedgeCollapseResult> b = collapse_wedges(m, options);
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a.value().levels[i].triangles, b.value().levels[i].triangles);
    EXPECT_EQ(a.value().levels[i].corner_wedge, b.value().levels[i].corner_wedge);
  }
}

TEST(WedgeCollapse, StopsAtTheErrorBoundWithoutCallingItBlocked) {
  const WedgeMesh m = grid(12, [](double x, double y) {
    return Vec2f{static_cast<float>(x * x / 144), static_cast<float>(y / 12)};
  });
  WedgeCollapseOptions options;
  options.targets = {0};
  options.max_error = 1e-4;
  Result<WedgeCollapseResult> r = collapse_wedges(m, options);
  ASSERT_TRUE(r.is_ok());
  EXPECT_TRUE(r.value().stopped_by_error);
  EXPECT_FALSE(r.value().blocked.has_value());
  EXPECT_LE(r.value().max_collapse_error, 1e-4);
  EXPECT_GT(r.value().levels.at(0).triangles.size(), 2u);
}

TEST(WedgeCollapse, RefusesBrokenInput) {
  WedgeMesh m = grid(2, linear_uv);
  m.triangles[0][1] = m.triangles[0][0];
  m.corner_wedge[0][1] = m.corner_wedge[0][0];
  Result<WedgeCollapseResult> repeated = collapse_wedges(m, {});
  ASSERT_FALSE(repeated.is_ok());
  EXPECT_EQ(repeated.status().kind(), ErrorKind::kInvalidInput);

  WedgeMesh other = grid(2, linear_uv);
  other.corner_wedge[0][0] = other.corner_wedge[0][1];  // a wedge of another point
  EXPECT_FALSE(collapse_wedges(other, {}).is_ok());

  WedgeCollapseOptions increasing;
  increasing.targets = {2, 4};
  EXPECT_FALSE(collapse_wedges(grid(2, linear_uv), increasing).is_ok());
}

}  // namespace
}  // namespace lodbake
