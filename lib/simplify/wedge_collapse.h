// Half-edge collapses over a mesh with wedges (Hoppe 1996): a point owns one
// or more wedges, each a set of attribute values (normal, texture
// coordinates, colours, a material's vertex), and each triangle corner uses
// one wedge of its point. The cost of a collapse is the geometric quadric
// error (Garland & Heckbert 1997) plus the appearance quadrics of the wedges
// it moves (attribute_quadric.h), so a texture seam or a material border
// costs what it distorts. How seams behave, and what --permissive changes:
// docs/simplify.md, "Assets (glTF scenes)".
//
// A seam edge is an interior edge whose two faces give one of its ends
// different wedges, or an edge between two materials; a border edge has one
// face. A point on no seam and no border may collapse into any neighbour; a
// point on exactly two seam or border edges (a seam passing through) only
// along one of them, both sides together; any other seam or border point (a
// seam corner) stays, unless `permissive`. Each wedge of the removed point
// takes the wedge of the survivor it meets across a removed face; a wedge
// that meets none (a seam moving, permissive only) keeps its values at the
// survivor's point.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/simplify/quadric.h"

namespace lodbake {

struct WedgeMesh {
  std::vector<Vec3d> points;
  std::vector<Triangle> triangles;                    // point ids, counter-clockwise
  std::vector<std::array<uint32_t, 3>> corner_wedge;  // per triangle corner
  // Per wedge: its point, and its error attributes, already weighted (a
  // difference of 1 in a value costs like a distance of 1 diagonal), as
  // values[offset[w] .. offset[w + 1]). The three wedges of a triangle have
  // the same number of values (one material, one layout).
  std::vector<uint32_t> wedge_point;
  std::vector<uint32_t> value_offset;  // wedges + 1 entries
  std::vector<float> values;
  // Per wedge, for the legality checks: its texture coordinate sets
  // (TEXCOORD_0 .. TEXCOORD_{uv_sets - 1}; set s of wedge w at
  // uv[w * uv_sets + s], present when bit s of has_uv[w] is set) and its
  // NORMAL when has_normal (one material's wedges all have them or not).
  // Every set is checked for folds: a second set (a light map, a detail
  // texture) folds as visibly as the first.
  static constexpr uint32_t kMaxUvSets = 8;
  uint32_t uv_sets = 1;
  std::vector<Vec2f> uv;
  std::vector<Vec3f> normal;
  std::vector<uint8_t> has_uv;
  std::vector<uint8_t> has_normal;

  size_t wedge_count() const { return wedge_point.size(); }
};

struct WedgeCollapseOptions {
  std::vector<uint64_t> targets;    // triangle counts to stop at, in decreasing order
  std::optional<double> max_error;  // relative to the diagonal, like SimplifyOptions
  double boundary_weight = 10.0;    // border and seam constraint planes: this * edge length^2
  bool lock_border = false;
  bool permissive = false;
  // Without `permissive`: seams stay while a collapse that keeps them costs
  // at most this error (relative to the diagonal); past it, a point on a
  // seam may also collapse under the permissive rules, its error counted
  // plus this bound, so seams move only where keeping them costs more. A
  // collapse that moves seams may itself cost at most 3 times the bound.
  // Unset or infinite: seams never move.
  std::optional<double> seam_release;
  double max_normal_change_degrees = 150.0;
  // Also keep the log of every collapse (what a progressive mesh with
  // wedges is recorded from, lib/simplify/wedge_pm.h).
  bool record = false;
  std::function<void(double)> progress;
};

// One applied collapse: point vt merged into vs, the faces (vs, vt, vl) and
// (vt, vs, vr) removed (a missing one: kNoVertex), with their corner wedges
// in that order, and the wedge each moved face had at vt.
struct WedgeCollapseRecord {
  uint32_t vt = 0;
  uint32_t vs = 0;
  uint32_t vl = kNoVertex;
  uint32_t vr = kNoVertex;
  std::array<uint32_t, 3> left{};   // wedges of (vs, vt, vl)
  std::array<uint32_t, 3> right{};  // wedges of (vt, vs, vr)
  uint32_t left_face = kNoVertex;   // the removed faces' indices in the input
  uint32_t right_face = kNoVertex;
  uint32_t moved_begin = 0;  // into WedgeCollapseResult::moved_faces / moved_wedges
  uint32_t moved_end = 0;
  float error = 0;  // the collapse's error, relative to the diagonal
};

// Why a point could not be removed when the collapses stopped.
struct CollapseBlocks {
  uint64_t seam_corners = 0;   // a point where seams or borders meet or end
  uint64_t border = 0;         // lock_border
  uint64_t non_manifold = 0;   // an edge with more than two faces
  uint64_t link = 0;           // the collapse would make the mesh non-manifold
  uint64_t flip = 0;           // a face would flip or degenerate
  uint64_t uv_fold = 0;        // a texture chart would fold
  uint64_t normal = 0;         // a corner's normal would face against its face
  uint64_t seam_mismatch = 0;  // the two sides of a seam do not meet one wedge each
};

// A mesh at one target: live triangles with their corner wedges, and the
// point each wedge sits at (a wedge moved by a permissive collapse sits at
// the survivor's point).
struct WedgeLevel {
  std::vector<Triangle> triangles;
  std::vector<uint32_t> faces;  // the input index of each triangle
  std::vector<std::array<uint32_t, 3>> corner_wedge;
  std::vector<uint32_t> wedge_point;
};

struct WedgeCollapseResult {
  std::vector<WedgeLevel> levels;  // one per target reached or stopped short of
  uint64_t collapses = 0;
  double max_collapse_error = 0;  // relative to the diagonal
  // The next collapse would have cost more than max_error: the levels not
  // reached are the mesh where it stopped.
  bool stopped_by_error = false;
  // Filled when no legal collapse was left above a target: what held the
  // remaining points (each counted once, by the reason its first collapse
  // was refused).
  std::optional<CollapseBlocks> blocked;
  // With `record`: the collapses in order, and per collapse the faces it
  // moved from vt to vs with their wedge at vt before it.
  std::vector<WedgeCollapseRecord> log;
  std::vector<uint32_t> moved_faces;
  std::vector<uint32_t> moved_wedges;
};

/// Collapses `mesh` down to each target in turn.
/// \pre every triangle's points are distinct and in range, corner wedges are
///      wedges of the corner's point; edges may have any number of faces
///      (points on an edge with more than two never move).
/// Deterministic: ties are broken by point index.
Result<WedgeCollapseResult> collapse_wedges(const WedgeMesh& mesh,
                                            const WedgeCollapseOptions& options);

}  // namespace lodbake
