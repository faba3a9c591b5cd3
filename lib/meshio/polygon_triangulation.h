// Splitting one polygonal face (OBJ, OFF and PLY faces with more than three
// corners) into triangles that keep its winding. See polygon_triangulation.cpp
// for the method and what happens to degenerate and self-intersecting faces.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {

/// Polygons with more corners than this are ear-clipped only when they are
/// convex (then they are fanned in linear time); others are fanned as they
/// are and counted in oversized_fanned, which bounds the work per polygon.
constexpr size_t kMaxEarClipCorners = 1024;

/// Ear clipping a non-convex polygon of m corners costs about m * m steps.
/// A triangulator spends at most this many steps plus kEarClipWorkPerCorner
/// per polygon corner it has seen; polygons that would exceed that are
/// fanned and counted in oversized_fanned. This keeps the work linear in the
/// input size for hostile files (thousands of large star-shaped polygons)
/// while every real mesh stays far below it.
constexpr uint64_t kEarClipWorkAllowance = uint64_t{1} << 27;
constexpr uint64_t kEarClipWorkPerCorner = 64;

/// What happened to the polygons (faces with more than 3 corners) seen so far.
struct TriangulationCounts {
  uint64_t polygons = 0;          // faces with more than 3 corners
  uint64_t ear_clipped = 0;       // non-convex ones split by ear clipping
  uint64_t repeated_corners = 0;  // had consecutive repeats of an index, dropped first
  uint64_t degenerate = 0;        // zero area or < 3 distinct corners: fanned, triangles degenerate
  uint64_t self_intersecting = 0;  // non-convex with edges that cross: triangles may overlap
  uint64_t fallback_fanned = 0;    // ear clipping got stuck (self-intersecting): rest fanned
  uint64_t oversized_fanned = 0;   // non-convex, over the corner or work limit: fanned
};

/// Triangulates polygons one after the other, reusing its scratch memory and
/// counting outcomes. Not thread-safe; use one per reader.
class PolygonTriangulator {
 public:
  /// `work_allowance`: the fixed part of the ear-clipping work budget.
  explicit PolygonTriangulator(uint64_t work_allowance = kEarClipWorkAllowance)
      : work_budget_(work_allowance) {}

  /// Appends the triangles of the polygon with `n` corners `corners[0..n)`
  /// (vertex indices into `positions`) to `out`, wound like the polygon: n - 2
  /// triangles, or fewer when consecutive corners repeat an index. A convex
  /// polygon gives the fan (0, i, i + 1). When `corner_slots` is not null,
  /// appends for every output triangle which input corners (0..n-1) its three
  /// corners came from, so per-corner attributes can follow.
  /// \pre every corners[i] < positions.size() (checked: kInvalidInput).
  /// \return kInvalidInput when n < 3 or an index is out of range.
  Status triangulate(const uint32_t* corners, size_t n, const std::vector<Vec3f>& positions,
                     std::vector<Triangle>* out, std::vector<Triangle>* corner_slots);

  const TriangulationCounts& counts() const { return counts_; }

  /// Adds counts().polygons to report->polygons_triangulated and one note per
  /// non-zero unusual outcome (repeated corners, degenerate, fallback fans).
  void add_to_report(ImportReport* report) const;

 private:
  struct Point2 {
    double u, v;
  };
  void emit(uint32_t a, uint32_t b, uint32_t c, const uint32_t* corners, std::vector<Triangle>* out,
            std::vector<Triangle>* corner_slots) const;
  // Fan (ring[0], ring[i], ring[i+1]) over slots ring_.
  void fan(const std::vector<uint32_t>& ring, const uint32_t* corners, std::vector<Triangle>* out,
           std::vector<Triangle>* corner_slots) const;
  bool is_convex_ring() const;
  // True when two non-adjacent edges of ring_ cross at a point inside both.
  bool has_crossing_edges() const;
  // Ear clipping over ring_/points_; false when it got stuck (the rest is
  // then fanned by the caller from the slots left in ring_).
  bool ear_clip(const uint32_t* corners, std::vector<Triangle>* out,
                std::vector<Triangle>* corner_slots);

  TriangulationCounts counts_;
  uint64_t work_budget_;
  std::vector<uint32_t> ring_;  // input slots after dropping repeated corners
  std::vector<Point2> points_;  // ring_'s positions projected to 2D (counter-clockwise)
  std::vector<uint32_t> prev_, next_;
  std::vector<uint8_t> state_;    // ear clipping: per ring position
  std::vector<uint32_t> reflex_;  // ring positions that were not strictly convex
};

/// One-shot form of PolygonTriangulator::triangulate(); adds to `counts`
/// when it is not null.
Status triangulate_polygon(const uint32_t* corners, size_t n, const std::vector<Vec3f>& positions,
                           std::vector<Triangle>* out, std::vector<Triangle>* corner_slots,
                           TriangulationCounts* counts = nullptr);

}  // namespace lodbake
