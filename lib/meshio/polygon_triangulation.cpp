// Polygon triangulation for the mesh readers: ear clipping in the plane of
// the polygon's Newell normal (M. Newell's normal of a non-planar polygon, as
// in Sutherland, Sproull and Schumacker 1974; ear clipping after Meisters
// 1975, "Polygons have ears", with the reflex-vertex-only containment test
// of D. Eberly, "Triangulation by Ear Clipping").
//
// Choices where the input is not a simple planar polygon:
// - Triangles (n == 3) pass through unchanged, even degenerate ones: the
//   mesh check reports them and --repair removes them.
// - Consecutive corners repeating an index (cyclically) are dropped first;
//   they only add zero-length edges. If fewer than 3 corners remain, the
//   stored corners are fanned as they are (degenerate triangles that the
//   mesh check reports) rather than dropped silently.
// - The polygon is projected onto the coordinate plane most orthogonal to
//   its Newell normal, oriented so that it winds counter-clockwise there;
//   the output triangles therefore keep the polygon's winding. When the
//   Newell normal is zero (collinear or coincident corners, or a figure
//   whose signed areas cancel) or not finite, the polygon is fanned.
// - Strictly convex polygons are fanned from their first corner, (0, i, i+1),
//   in linear time; so are non-convex polygons of more than
//   kMaxEarClipCorners corners, or whose quadratic cost would exceed the
//   work budget (kEarClipWorkAllowance plus kEarClipWorkPerCorner per corner
//   seen), so the total work stays linear in the input.
// - Ear tips must be strictly convex, so a corner lying on the line through
//   its neighbours is never the tip of a zero-area triangle while another
//   choice exists. Vertices at the same position as one of the ear's corners
//   do not block it, which lets "slit" polygons (a ring cut open along an
//   edge walked in both directions) be clipped.
// - Non-convex polygons are tested for edges that cross (O(n^2), bounded by
//   kMaxEarClipCorners); such a polygon is still ear-clipped but counted in
//   self_intersecting, since its triangles may overlap.
// - When no ear is left before the polygon is done (it intersects itself),
//   the corners still left are fanned from the first of them and the polygon
//   is counted in fallback_fanned. The readers turn all counts into notes of
//   the import report, so such output is never silently wrong.
#include "lib/meshio/polygon_triangulation.h"

#include <cmath>
#include <string>

namespace lodbake {
namespace {

enum : uint8_t {
  kRemoved = 1,   // clipped off
  kConvex = 2,    // strictly convex corner
  kEarKnown = 4,  // kEar below is up to date
  kEar = 8,
  kInReflex = 16,  // listed in reflex_
};

struct Vec3d {
  double x, y, z;
};

Vec3d to_double(const Vec3f& p) {
  return {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])};
}

}  // namespace

void PolygonTriangulator::emit(uint32_t a, uint32_t b, uint32_t c, const uint32_t* corners,
                               std::vector<Triangle>* out,
                               std::vector<Triangle>* corner_slots) const {
  out->push_back({corners[a], corners[b], corners[c]});
  if (corner_slots != nullptr) corner_slots->push_back({a, b, c});
}

void PolygonTriangulator::fan(const std::vector<uint32_t>& ring, const uint32_t* corners,
                              std::vector<Triangle>* out,
                              std::vector<Triangle>* corner_slots) const {
  for (size_t i = 1; i + 1 < ring.size(); ++i)
    emit(ring[0], ring[i], ring[i + 1], corners, out, corner_slots);
}

Status PolygonTriangulator::triangulate(const uint32_t* corners, size_t n,
                                        const std::vector<Vec3f>& positions,
                                        std::vector<Triangle>* out,
                                        std::vector<Triangle>* corner_slots) {
  if (n < 3) return invalid_input("face has " + std::to_string(n) + " corners, at least 3 needed");
  for (size_t i = 0; i < n; ++i) {
    if (corners[i] >= positions.size())
      return invalid_input("face index " + std::to_string(corners[i]) + " out of range (" +
                           std::to_string(positions.size()) + " vertices)");
  }
  if (n == 3) {
    emit(0, 1, 2, corners, out, corner_slots);
    return Status::ok();
  }
  ++counts_.polygons;
  work_budget_ += kEarClipWorkPerCorner * n;

  ring_.clear();
  for (size_t i = 0; i < n; ++i) {
    if (ring_.empty() || corners[ring_.back()] != corners[i])
      ring_.push_back(static_cast<uint32_t>(i));
  }
  while (ring_.size() > 1 && corners[ring_.back()] == corners[ring_.front()])
    ring_.pop_back();
  if (ring_.size() != n) ++counts_.repeated_corners;
  if (ring_.size() < 3) {
    ++counts_.degenerate;
    ring_.clear();
    for (size_t i = 0; i < n; ++i)
      ring_.push_back(static_cast<uint32_t>(i));
    fan(ring_, corners, out, corner_slots);
    return Status::ok();
  }
  const size_t m = ring_.size();
  if (m == 3) {
    fan(ring_, corners, out, corner_slots);
    return Status::ok();
  }

  // Newell normal, relative to the first corner for precision.
  const Vec3d origin = to_double(positions[corners[ring_[0]]]);
  double normal[3] = {0, 0, 0};
  double perimeter = 0;
  for (size_t i = 0; i < m; ++i) {
    Vec3d a = to_double(positions[corners[ring_[i]]]);
    Vec3d b = to_double(positions[corners[ring_[(i + 1) % m]]]);
    a = {a.x - origin.x, a.y - origin.y, a.z - origin.z};
    b = {b.x - origin.x, b.y - origin.y, b.z - origin.z};
    normal[0] += (a.y - b.y) * (a.z + b.z);
    normal[1] += (a.z - b.z) * (a.x + b.x);
    normal[2] += (a.x - b.x) * (a.y + b.y);
    perimeter += std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
                           (b.z - a.z) * (b.z - a.z));
  }
  const double normal_length =
      std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  // The normal's length is twice the area; compare it with the perimeter so
  // the test does not depend on the model's scale. The negated comparison
  // also sends NaN and infinite coordinates here.
  if (!(normal_length > 1e-12 * perimeter * perimeter) || !std::isfinite(normal_length)) {
    ++counts_.degenerate;
    fan(ring_, corners, out, corner_slots);
    return Status::ok();
  }

  int axis = 0;
  if (std::fabs(normal[1]) > std::fabs(normal[axis])) axis = 1;
  if (std::fabs(normal[2]) > std::fabs(normal[axis])) axis = 2;
  // (u, v, axis) is a right-handed frame, so a polygon whose normal points
  // along +axis winds counter-clockwise in (u, v); swap u and v otherwise.
  int u_axis = (axis + 1) % 3;
  int v_axis = (axis + 2) % 3;
  if (normal[axis] < 0) std::swap(u_axis, v_axis);
  points_.resize(m);
  for (size_t i = 0; i < m; ++i) {
    const Vec3f& p = positions[corners[ring_[i]]];
    points_[i] = {static_cast<double>(p[u_axis]), static_cast<double>(p[v_axis])};
  }

  if (is_convex_ring()) {
    fan(ring_, corners, out, corner_slots);
    return Status::ok();
  }
  const uint64_t cost = uint64_t{m} * m;
  if (m > kMaxEarClipCorners || cost > work_budget_) {
    ++counts_.oversized_fanned;
    fan(ring_, corners, out, corner_slots);
    return Status::ok();
  }
  work_budget_ -= cost;
  if (has_crossing_edges()) ++counts_.self_intersecting;
  if (ear_clip(corners, out, corner_slots)) {
    ++counts_.ear_clipped;
  } else {
    ++counts_.fallback_fanned;
    fan(ring_, corners, out, corner_slots);
  }
  return Status::ok();
}

namespace {

// Twice the signed area of (a, b, c); positive when they turn left.
template <typename P>
double cross(const P& a, const P& b, const P& c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

// -1, 0 or +1.
int sign(double x) {
  return (x > 0) - (x < 0);
}

}  // namespace

bool PolygonTriangulator::is_convex_ring() const {
  const size_t m = points_.size();
  int du_changes = 0;
  int dv_changes = 0;
  int last_du = 0;
  int last_dv = 0;
  int first_du = 0;
  int first_dv = 0;
  for (size_t i = 0; i < m; ++i) {
    const Point2& a = points_[i];
    const Point2& b = points_[(i + 1) % m];
    const Point2& c = points_[(i + 2) % m];
    if (!(cross(a, b, c) > 0)) return false;
    // A strictly left-turning polygon that winds k times changes the sign of
    // each edge-direction component 2k times; convex means k == 1.
    const int du = sign(b.u - a.u);
    const int dv = sign(b.v - a.v);
    if (du != 0) {
      if (first_du == 0) first_du = du;
      if (last_du != 0 && du != last_du) ++du_changes;
      last_du = du;
    }
    if (dv != 0) {
      if (first_dv == 0) first_dv = dv;
      if (last_dv != 0 && dv != last_dv) ++dv_changes;
      last_dv = dv;
    }
  }
  if (last_du != first_du) ++du_changes;
  if (last_dv != first_dv) ++dv_changes;
  return du_changes <= 2 && dv_changes <= 2;
}

bool PolygonTriangulator::has_crossing_edges() const {
  const size_t m = points_.size();
  for (size_t i = 0; i < m; ++i) {
    const Point2& a = points_[i];
    const Point2& b = points_[(i + 1) % m];
    // Edges sharing a corner with edge i are skipped: they meet at it.
    for (size_t j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;
      const Point2& c = points_[j];
      const Point2& d = points_[(j + 1) % m];
      if (sign(cross(a, b, c)) * sign(cross(a, b, d)) < 0 &&
          sign(cross(c, d, a)) * sign(cross(c, d, b)) < 0)
        return true;
    }
  }
  return false;
}

bool PolygonTriangulator::ear_clip(const uint32_t* corners, std::vector<Triangle>* out,
                                   std::vector<Triangle>* corner_slots) {
  const size_t m = ring_.size();
  prev_.resize(m);
  next_.resize(m);
  state_.assign(m, 0);
  reflex_.clear();
  for (size_t i = 0; i < m; ++i) {
    prev_[i] = static_cast<uint32_t>((i + m - 1) % m);
    next_[i] = static_cast<uint32_t>((i + 1) % m);
  }
  auto classify = [&](uint32_t i) {
    state_[i] &= static_cast<uint8_t>(~(kConvex | kEarKnown | kEar));
    if (cross(points_[prev_[i]], points_[i], points_[next_[i]]) > 0) {
      state_[i] |= kConvex;
    } else if (!(state_[i] & kInReflex)) {
      state_[i] |= kInReflex;
      reflex_.push_back(i);
    }
  };
  auto same_point = [](const Point2& a, const Point2& b) { return a.u == b.u && a.v == b.v; };
  auto is_ear = [&](uint32_t i) {
    if (!(state_[i] & kConvex)) return false;
    const uint32_t p = prev_[i];
    const uint32_t q = next_[i];
    const Point2& a = points_[p];
    const Point2& b = points_[i];
    const Point2& c = points_[q];
    for (uint32_t r : reflex_) {
      if ((state_[r] & (kRemoved | kConvex)) || r == p || r == i || r == q) continue;
      const Point2& x = points_[r];
      if (same_point(x, a) || same_point(x, b) || same_point(x, c)) continue;
      if (cross(a, b, x) >= 0 && cross(b, c, x) >= 0 && cross(c, a, x) >= 0) return false;
    }
    return true;
  };
  for (uint32_t i = 0; i < m; ++i)
    classify(i);

  // Starting at corner 1 makes the first candidate ear (0, 1, 2), and moving
  // on to the next corner after each clip keeps corner 0 as the apex for as
  // long as possible, so nearly convex polygons come out close to a fan.
  size_t remaining = m;
  uint32_t cursor = 1;
  size_t idle = 0;
  bool cache_cleared = false;
  while (remaining > 3) {
    if (!(state_[cursor] & kEarKnown)) {
      state_[cursor] |= kEarKnown;
      if (is_ear(cursor)) state_[cursor] |= kEar;
    }
    if (state_[cursor] & kEar) {
      const uint32_t p = prev_[cursor];
      const uint32_t q = next_[cursor];
      emit(ring_[p], ring_[cursor], ring_[q], corners, out, corner_slots);
      state_[cursor] |= kRemoved;
      next_[p] = q;
      prev_[q] = p;
      --remaining;
      classify(p);
      classify(q);
      cursor = q;
      idle = 0;
      continue;
    }
    cursor = next_[cursor];
    if (++idle > remaining) {
      // Cached "not an ear" answers are exact for simple polygons; for
      // others, re-examine every corner once before giving up.
      if (cache_cleared) break;
      cache_cleared = true;
      idle = 0;
      for (uint8_t& s : state_)
        s &= static_cast<uint8_t>(~(kEarKnown | kEar));
    }
  }
  if (remaining == 3) {
    emit(ring_[prev_[cursor]], ring_[cursor], ring_[next_[cursor]], corners, out, corner_slots);
    return true;
  }
  // Stuck: leave the corners still present in ring_, in their original order.
  size_t kept = 0;
  for (size_t i = 0; i < m; ++i) {
    if (!(state_[i] & kRemoved)) ring_[kept++] = ring_[i];
  }
  ring_.resize(kept);
  return false;
}

void PolygonTriangulator::add_to_report(ImportReport* report) const {
  report->polygons_triangulated += counts_.polygons;
  auto note = [&](uint64_t count, const char* text) {
    if (count != 0) report->notes.push_back(std::to_string(count) + " " + text);
  };
  note(counts_.repeated_corners,
       "polygons repeat an index in consecutive corners; the repeats were dropped before "
       "splitting them");
  note(counts_.degenerate,
       "polygons have zero area (collinear or coincident corners); they were split as a fan of "
       "degenerate triangles");
  note(counts_.self_intersecting,
       "polygons intersect themselves (edges cross); their triangles may overlap");
  note(counts_.fallback_fanned,
       "polygons intersect themselves so ear clipping could not finish; their remaining corners "
       "were split as a fan, whose triangles may overlap");
  note(counts_.oversized_fanned,
       ("non-convex polygons have more than " + std::to_string(kMaxEarClipCorners) +
        " corners or exceed the ear-clipping work limit; they were split as a fan, whose "
        "triangles may overlap")
           .c_str());
}

Status triangulate_polygon(const uint32_t* corners, size_t n, const std::vector<Vec3f>& positions,
                           std::vector<Triangle>* out, std::vector<Triangle>* corner_slots,
                           TriangulationCounts* counts) {
  PolygonTriangulator triangulator;
  Status status = triangulator.triangulate(corners, n, positions, out, corner_slots);
  if (counts != nullptr) {
    const TriangulationCounts& c = triangulator.counts();
    counts->polygons += c.polygons;
    counts->ear_clipped += c.ear_clipped;
    counts->repeated_corners += c.repeated_corners;
    counts->degenerate += c.degenerate;
    counts->self_intersecting += c.self_intersecting;
    counts->fallback_fanned += c.fallback_fanned;
    counts->oversized_fanned += c.oversized_fanned;
  }
  return status;
}

}  // namespace lodbake
