// Choices the papers leave open, stated in docs/simplify.md ("Assets (glTF
// scenes)"):
// - points are scaled to a unit bounding-box diagonal;
// - the priority is the error the collapse adds: vt's quadrics at vs's
//   point and values, the geometric one over vt's area (a mean squared
//   error), the appearance ones of the wedges it gives up left a sum over
//   it (check() says why). Adding vs's own
//   quadrics as well, as Garland & Heckbert's sum does, gave a Hausdorff
//   error 1.2 to 1.5 times larger on the assets at 25%
//   (docs/lab/wedge-weights.md);
// - border and seam edges add a constraint plane through the edge,
//   perpendicular to its face, to both ends (Garland & Heckbert 1998 do so
//   for discontinuities), so a seam keeps its course while it shortens;
// - after a collapse only vs and vt's former neighbours are re-evaluated,
//   and illegal collapses are found when they come up: before calling the
//   mesh blocked every point is offered once more.
#include "lib/simplify/wedge_collapse.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>
#include <utility>

#include "formats/mesh/progressive_mesh.h"
#include "lib/simplify/attribute_quadric.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {
namespace {

enum class Refusal : uint8_t {
  kNone,
  kSeamCorner,
  kBorder,
  kNonManifold,
  kLink,
  kFlip,
  kUvFold,
  kNormal,
  kSeamMismatch,
};

void count(Refusal r, CollapseBlocks* b) {
  switch (r) {
    case Refusal::kSeamCorner:
      ++b->seam_corners;
      break;
    case Refusal::kBorder:
      ++b->border;
      break;
    case Refusal::kNonManifold:
      ++b->non_manifold;
      break;
    case Refusal::kLink:
      ++b->link;
      break;
    case Refusal::kFlip:
      ++b->flip;
      break;
    case Refusal::kUvFold:
      ++b->uv_fold;
      break;
    case Refusal::kNormal:
      ++b->normal;
      break;
    case Refusal::kSeamMismatch:
      ++b->seam_mismatch;
      break;
    case Refusal::kNone:
      break;
  }
}

struct WedgeMove {
  uint32_t from = 0;
  uint32_t to = 0;  // == from: the wedge keeps its values at the survivor's point
};

// One point's cheapest legal collapse, or why it has none.
struct Candidate {
  uint32_t target = kNoVertex;
  double cost = 0;  // with kSeamRelease's penalty when `relaxed`
  Refusal refusal = Refusal::kNone;
  bool relaxed = false;  // moves seams (permissive rules) though the run keeps them
};

// A collapse that moves seams under a seam release costs at most this
// many times the bound: past it, a seam's chart is what the mesh still
// looks like (a textured box stays a box; docs/lab/seam-release.md).
constexpr double kReleaseCap = 3;

// A refused target, and whether under the permissive rules.
uint32_t refused_key(uint32_t target, bool relaxed) {
  return target << 1 | static_cast<uint32_t>(relaxed);
}

struct HeapEntry {
  double cost;
  uint32_t point;
  uint32_t target;
  uint32_t stamp;
  bool relaxed;
  bool operator>(const HeapEntry& o) const {
    if (cost != o.cost) return cost > o.cost;
    if (point != o.point) return point > o.point;
    if (target != o.target) return target > o.target;
    return relaxed > o.relaxed;
  }
};

double uv_area(const Vec2f& a, const Vec2f& b, const Vec2f& c) {
  return (double{b[0]} - a[0]) * (double{c[1]} - a[1]) -
         (double{b[1]} - a[1]) * (double{c[0]} - a[0]);
}

class WedgeCollapser {
 public:
  WedgeCollapser(const WedgeMesh& mesh, const WedgeCollapseOptions& options)
      : in_(mesh), options_(options) {}

  Result<WedgeCollapseResult> run() {
    LODBAKE_RETURN_IF_ERROR(set_up());
    WedgeCollapseResult result;
    std::priority_queue<HeapEntry, std::vector<HeapEntry>, std::greater<HeapEntry>> heap;
    auto push = [&](uint32_t v) {
      ++stamp_[v];
      const Candidate c = best_collapse(v, false);
      if (c.target != kNoVertex) heap.push({c.cost, v, c.target, stamp_[v], c.relaxed});
    };
    for (uint32_t v = 0; v < points_.size(); ++v)
      if (!faces_[v].empty()) push(v);

    const uint64_t start = live_;
    size_t next = 0;
    bool stopped_by_error = false;
    bool swept = false;  // every point offered again since the last collapse
    std::vector<WedgeMove> moves;
    std::vector<uint32_t> touched;
    while (next < options_.targets.size()) {
      if (live_ <= options_.targets[next]) {
        result.levels.push_back(level());
        ++next;
        continue;
      }
      if (heap.empty()) {
        // A point whose every candidate was refused leaves the heap until a
        // collapse touches it; one that only its second ring changed may
        // have become legal. Before calling the mesh blocked, every point
        // is offered once more.
        if (swept) break;
        swept = true;
        for (uint32_t v = 0; v < points_.size(); ++v) {
          if (faces_[v].empty()) continue;
          refused_[v].clear();
          push(v);
        }
        continue;
      }
      const HeapEntry top = heap.top();
      heap.pop();
      if (top.stamp != stamp_[top.point] || faces_[top.point].empty()) continue;
      if (options_.max_error &&
          std::sqrt(top.cost - (top.relaxed ? release_penalty_ : 0)) > *options_.max_error) {
        stopped_by_error = true;
        break;
      }
      double cost = 0;
      if (check(top.point, top.target, &cost, &moves, true, permissive_or(top.relaxed)) !=
          Refusal::kNone) {
        refused_[top.point].push_back(refused_key(top.target, top.relaxed));
        push(top.point);
        continue;
      }
      if (options_.record) record(top.point, top.target, cost, &result);
      // Whose candidates the collapse can change: vs (its quadrics and
      // faces) and vt's neighbours (their faces now meet vs). vs's other
      // neighbours keep their faces, quadrics and costs; a collapse of
      // theirs the new neighbourhood makes illegal is refused when it comes
      // up.
      touched.clear();
      neighbours(top.point, &touched);
      collapse(top.point, top.target, moves);
      swept = false;
      ++result.collapses;
      result.max_collapse_error = std::max(result.max_collapse_error, std::sqrt(cost));
      for (uint32_t v : touched) {
        refused_[v].clear();
        push(v);
      }
      if (options_.progress && (result.collapses & 4095) == 0 && start > 0)
        options_.progress(static_cast<double>(start - live_) / static_cast<double>(start));
    }
    if (next < options_.targets.size() && !stopped_by_error) {
      CollapseBlocks blocks;
      for (uint32_t v = 0; v < points_.size(); ++v) {
        if (faces_[v].empty()) continue;
        const Candidate c = best_collapse(v, true);
        if (c.target == kNoVertex) count(c.refusal, &blocks);
      }
      result.blocked = blocks;
    }
    result.stopped_by_error = stopped_by_error;
    while (next++ < options_.targets.size())
      result.levels.push_back(level());
    return result;
  }

 private:
  Status set_up() {
    const size_t n = in_.points.size();
    const size_t wedges = in_.wedge_point.size();
    if (in_.corner_wedge.size() != in_.triangles.size() || in_.value_offset.size() != wedges + 1 ||
        in_.value_offset.back() != in_.values.size() || in_.uv_sets < 1 ||
        in_.uv_sets > WedgeMesh::kMaxUvSets || in_.uv.size() != wedges * in_.uv_sets ||
        in_.normal.size() != wedges || in_.has_uv.size() != wedges ||
        in_.has_normal.size() != wedges)
      return Status(ErrorKind::kInvalidInput, "the wedge mesh's arrays do not match");
    Vec3d lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const Vec3d& p : in_.points)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    const Vec3d extent = sub(hi, lo);
    const double diagonal = n == 0 ? 0 : std::sqrt(dot(extent, extent));
    const double scale = diagonal > 0 ? 1 / diagonal : 1;
    points_.resize(n);
    for (size_t v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k)
        points_[v][k] = (in_.points[v][k] - lo[k]) * scale;

    triangles_ = in_.triangles;
    corner_wedge_ = in_.corner_wedge;
    wedge_point_ = in_.wedge_point;
    faces_.assign(n, {});
    for (uint32_t t = 0; t < triangles_.size(); ++t) {
      const Triangle& tri = triangles_[t];
      for (int k = 0; k < 3; ++k) {
        const uint32_t w = corner_wedge_[t][k];
        if (tri[k] >= n || w >= wedges || wedge_point_[w] != tri[k])
          return Status(ErrorKind::kInvalidInput,
                        "triangle " + std::to_string(t) + " has a corner out of range");
        if (values_of(w) != values_of(corner_wedge_[t][0]))
          return Status(ErrorKind::kInvalidInput,
                        "triangle " + std::to_string(t) + " mixes attribute layouts");
      }
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
        return Status(ErrorKind::kInvalidInput,
                      "triangle " + std::to_string(t) + " repeats a point");
      for (int k = 0; k < 3; ++k)
        faces_[tri[k]].push_back(t);
    }
    live_ = triangles_.size();
    triangle_alive_.assign(triangles_.size(), 1);
    stamp_.assign(n, 0);
    refused_.assign(n, {});

    geometric_.assign(n, Quadric());
    wedge_quadric_.assign(wedges, Quadric());
    component_.assign(in_.values.size(), ComponentTerms{});
    for (uint32_t t = 0; t < triangles_.size(); ++t) {
      const Triangle& tri = triangles_[t];
      const Vec3d p[3] = {points_[tri[0]], points_[tri[1]], points_[tri[2]]};
      const Quadric q = Quadric::from_triangle(p[0], p[1], p[2]);
      for (int k = 0; k < 3; ++k)
        geometric_[tri[k]] += q;
      const Vec3d nrm = cross(sub(p[1], p[0]), sub(p[2], p[0]));
      const double len = std::sqrt(dot(nrm, nrm));
      if (!(len > 0)) continue;
      const Vec3d unit{nrm[0] / len, nrm[1] / len, nrm[2] / len};
      const uint32_t components = values_of(corner_wedge_[t][0]);
      for (uint32_t j = 0; j < components; ++j) {
        const double s[3] = {value(corner_wedge_[t][0], j), value(corner_wedge_[t][1], j),
                             value(corner_wedge_[t][2], j)};
        for (int k = 0; k < 3; ++k) {
          const uint32_t w = corner_wedge_[t][k];
          add_attribute_term(&wedge_quadric_[w], &component_[in_.value_offset[w] + j], p, s, unit,
                             0.5 * len);
        }
      }
    }
    add_constraint_planes();
    cos_limit_ = std::cos(options_.max_normal_change_degrees * M_PI / 180.0);
    if (options_.seam_release && !options_.permissive) {
      if (!(*options_.seam_release >= 0))
        return Status(ErrorKind::kInvalidInput, "the seam release bound is not an error >= 0");
      releases_ = std::isfinite(*options_.seam_release);
      release_penalty_ = *options_.seam_release * *options_.seam_release;
      const double cap = kReleaseCap * *options_.seam_release;
      release_cap_ = cap * cap;
    }
    return Status::ok();
  }

  uint32_t values_of(uint32_t w) const { return in_.value_offset[w + 1] - in_.value_offset[w]; }
  double value(uint32_t w, uint32_t j) const { return in_.values[in_.value_offset[w] + j]; }

  // Border and seam edges, each once (from its first face in index order).
  void add_constraint_planes() {
    std::vector<uint32_t> shared;
    for (uint32_t t = 0; t < triangles_.size(); ++t) {
      const Triangle& tri = triangles_[t];
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = tri[k], b = tri[(k + 1) % 3];
        edge_faces(a, b, &shared);
        if (shared.front() != t) continue;
        if (shared.size() == 2 && !is_seam(a, b, shared[0], shared[1])) continue;
        const Vec3d e = sub(points_[b], points_[a]);
        const Vec3d nrm = cross(e, sub(points_[tri[(k + 2) % 3]], points_[a]));
        Vec3d plane = cross(e, nrm);
        const double len = std::sqrt(dot(plane, plane));
        if (!(len > 0)) continue;
        plane = {plane[0] / len, plane[1] / len, plane[2] / len};
        Quadric q = Quadric::from_plane(plane, -dot(plane, points_[a]),
                                        options_.boundary_weight * dot(e, e));
        // The cost is a mean over the faces' area: a constraint adds error,
        // not area (counted, it would make border points look cheap).
        q.weight = 0;
        geometric_[a] += q;
        geometric_[b] += q;
      }
    }
  }

  // The live faces holding both a and b, in index order.
  void edge_faces(uint32_t a, uint32_t b, std::vector<uint32_t>* out) const {
    out->clear();
    for (uint32_t f : faces_[a]) {
      const Triangle& t = triangles_[f];
      if (t[0] == b || t[1] == b || t[2] == b) out->push_back(f);
    }
    std::sort(out->begin(), out->end());
  }

  uint32_t wedge_at(uint32_t f, uint32_t v) const {
    return corner_wedge_[f][corner_of(triangles_[f], v)];
  }

  bool is_seam(uint32_t a, uint32_t b, uint32_t f1, uint32_t f2) const {
    return wedge_at(f1, a) != wedge_at(f2, a) || wedge_at(f1, b) != wedge_at(f2, b);
  }

  // Appends v's neighbours, sorted and unique, to `out`.
  void neighbours(uint32_t v, std::vector<uint32_t>* out) const {
    const size_t first = out->size();
    for (uint32_t f : faces_[v])
      for (uint32_t u : triangles_[f])
        if (u != v) out->push_back(u);
    std::sort(out->begin() + first, out->end());
    out->erase(std::unique(out->begin() + first, out->end()), out->end());
  }

  // The collapses v may make: all its neighbours, the ends of its two crease
  // edges, or none (with the reason).
  Refusal allowed_targets(uint32_t v, bool permissive, std::vector<uint32_t>* targets,
                          bool* on_seam) {
    targets->clear();
    *on_seam = false;
    around_.clear();
    neighbours(v, &around_);
    uint32_t borders = 0, seams = 0;
    creases_.clear();
    for (uint32_t u : around_) {
      edge_faces(v, u, &shared_);
      if (shared_.size() > 2) return Refusal::kNonManifold;
      if (shared_.size() == 1) {
        ++borders;
        creases_.push_back(u);
      } else if (is_seam(v, u, shared_[0], shared_[1])) {
        ++seams;
        if (!permissive) creases_.push_back(u);
      }
    }
    if (borders > 0 && options_.lock_border) return Refusal::kBorder;
    if (seams > 0) *on_seam = true;
    const uint32_t crease = borders + (permissive ? 0 : seams);
    if (crease == 0) {
      *targets = around_;
      return Refusal::kNone;
    }
    if (crease != 2 || (borders != 0 && borders != 2)) return Refusal::kSeamCorner;
    *targets = creases_;
    return Refusal::kNone;
  }

  bool permissive_or(bool relaxed) const { return options_.permissive || relaxed; }

  // v's cheapest collapse; with `legality`, its cheapest legal one, else
  // its cheapest not yet refused since its neighbourhood last changed.
  // With a seam release, a point on a seam also offers its cheapest
  // collapse under the permissive rules at its cost plus the penalty: it
  // comes up only when keeping the seams costs more than the bound.
  Candidate best_collapse(uint32_t v, bool legality) {
    bool on_seam = false;
    Candidate best = best_collapse_under(v, legality, options_.permissive, &on_seam);
    if (!releases_ || !on_seam) return best;
    bool ignored = false;
    Candidate relaxed = best_collapse_under(v, legality, true, &ignored);
    if (relaxed.target == kNoVertex || relaxed.cost > release_cap_) return best;
    relaxed.cost += release_penalty_;
    relaxed.relaxed = true;
    return best.target == kNoVertex || relaxed.cost < best.cost ? relaxed : best;
  }

  Candidate best_collapse_under(uint32_t v, bool legality, bool permissive, bool* on_seam) {
    Candidate best;
    best.refusal = allowed_targets(v, permissive, &targets_, on_seam);
    if (best.refusal != Refusal::kNone) return best;
    best.refusal = Refusal::kLink;  // a point with no neighbour (cannot happen with faces)
    bool refused = false;
    const std::vector<uint32_t>& refused_targets = refused_[v];
    for (uint32_t u : targets_) {
      if (!legality &&
          std::find(refused_targets.begin(), refused_targets.end(),
                    refused_key(u, permissive && !options_.permissive)) != refused_targets.end())
        continue;
      double cost = 0;
      const Refusal r = check(v, u, &cost, &moves_, legality, permissive);
      if (r != Refusal::kNone) {
        if (!refused) best.refusal = r;
        refused = true;
        continue;
      }
      if (best.target == kNoVertex || cost < best.cost) {
        best.target = u;
        best.cost = cost;
      }
    }
    if (best.target != kNoVertex) best.refusal = Refusal::kNone;
    return best;
  }

  // The wedge moves and the cost of collapsing vt into vs, and with
  // `legality` whether the mesh stays valid. The heap orders collapses by
  // cost alone; legality is checked when one comes up (most never do).
  Refusal check(uint32_t vt, uint32_t vs, double* cost, std::vector<WedgeMove>* moves,
                bool legality, bool permissive) {
    moves->clear();
    removed_.clear();
    moved_.clear();
    for (uint32_t f : faces_[vt]) {
      const Triangle& t = triangles_[f];
      (t[0] == vs || t[1] == vs || t[2] == vs ? removed_ : moved_).push_back(f);
    }
    if (removed_.empty() || removed_.size() > 2) return Refusal::kNonManifold;
    if (moved_.empty()) return Refusal::kLink;  // the last face of a piece

    for (uint32_t f : removed_) {
      const uint32_t from = wedge_at(f, vt), to = wedge_at(f, vs);
      for (const WedgeMove& m : *moves)
        if (m.from == from && m.to != to) return Refusal::kSeamMismatch;
      moves->push_back({from, to});
    }
    auto target_of = [&](uint32_t w) {
      for (const WedgeMove& m : *moves)
        if (m.from == w) return m.to;
      return kNoVertex;
    };
    for (uint32_t f : moved_) {
      const uint32_t w = wedge_at(f, vt);
      if (target_of(w) != kNoVertex) continue;
      if (!permissive) return Refusal::kSeamMismatch;
      moves->push_back({w, w});
    }

    const Vec3d& to = points_[vs];
    // The error this collapse adds: vt's quadrics (the faces it moves and
    // the wedges it gives up) at vs's point and values. vs's own quadrics
    // are the error of earlier collapses; they count when vs is removed.
    // The geometric part is a mean over vt's area; the appearance part is
    // left a sum over it, so that an attribute difference of 1 over a
    // distance d costs about what a distance d does (as meshoptimizer
    // weighs them): appearance counts more as the triangles grow.
    const Quadric& qt = geometric_[vt];
    double geometric = qt.evaluate(to);
    double appearance = 0;
    for (const WedgeMove& m : *moves) {
      const uint32_t first = in_.value_offset[m.from];
      const uint32_t target_first = in_.value_offset[m.to];
      appearance += evaluate_position_part(wedge_quadric_[m.from], to);
      for (uint32_t j = 0; j < values_of(m.from); ++j)
        appearance += evaluate_component(component_[first + j], to, in_.values[target_first + j]);
    }
    *cost = (qt.weight > 0 ? geometric / qt.weight : 0) + std::max(appearance, 0.0);
    if (!legality) return Refusal::kNone;

    // Link condition: the common neighbours are the removed faces' third points.
    opposite_.clear();
    for (uint32_t f : removed_)
      for (uint32_t u : triangles_[f])
        if (u != vt && u != vs) opposite_.push_back(u);
    std::sort(opposite_.begin(), opposite_.end());
    around_.clear();
    neighbours(vt, &around_);
    other_.clear();
    neighbours(vs, &other_);
    common_.clear();
    std::set_intersection(around_.begin(), around_.end(), other_.begin(), other_.end(),
                          std::back_inserter(common_));
    if (common_ != opposite_) return Refusal::kLink;
    // Two border points joined by an interior edge would pinch the border:
    // vt on a border only moves along it (allowed_targets), so removed_ has
    // one face there, and vs on a border keeps its border.

    for (uint32_t f : moved_) {
      const Triangle& t = triangles_[f];
      const int k = corner_of(t, vt);
      const uint32_t b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      if (b == vs || c == vs) continue;
      // A face that would repeat one of vs's: a pocket closing.
      if (std::binary_search(other_.begin(), other_.end(), b) &&
          std::binary_search(other_.begin(), other_.end(), c) && has_face(vs, b, c))
        return Refusal::kLink;
      Vec3d new_normal{};
      if (!keeps_orientation(points_[vt], points_[b], points_[c], to, cos_limit_, &new_normal))
        return Refusal::kFlip;
      const uint32_t w = corner_wedge_[f][k], nw = target_of(w);
      const uint32_t wb = corner_wedge_[f][(k + 1) % 3], wc = corner_wedge_[f][(k + 2) % 3];
      const uint32_t sets = in_.uv_sets;
      for (uint32_t set = 0; set < sets; ++set) {
        if (!(in_.has_uv[w] >> set & 1)) continue;
        const Vec2f* uv = in_.uv.data() + set;
        const double before = uv_area(uv[w * sets], uv[wb * sets], uv[wc * sets]);
        const double after = uv_area(uv[nw * sets], uv[wb * sets], uv[wc * sets]);
        if (before != 0 && !(before > 0 ? after > 0 : after < 0)) return Refusal::kUvFold;
      }
      if (in_.has_normal[w]) {
        const Vec3d old_normal = cross(sub(points_[b], points_[vt]), sub(points_[c], points_[vt]));
        for (uint32_t corner : {nw, wb, wc}) {
          const Vec3d n{in_.normal[corner][0], in_.normal[corner][1], in_.normal[corner][2]};
          const uint32_t was = corner == nw ? w : corner;
          const Vec3d n_was{in_.normal[was][0], in_.normal[was][1], in_.normal[was][2]};
          if (dot(n, new_normal) < 0 && dot(n_was, old_normal) >= 0) return Refusal::kNormal;
        }
      }
    }

    return Refusal::kNone;
  }

  bool has_face(uint32_t a, uint32_t b, uint32_t c) const {
    for (uint32_t f : faces_[a]) {
      const Triangle& t = triangles_[f];
      const bool hb = t[0] == b || t[1] == b || t[2] == b;
      const bool hc = t[0] == c || t[1] == c || t[2] == c;
      if (hb && hc) return true;
    }
    return false;
  }

  void record(uint32_t vt, uint32_t vs, double cost, WedgeCollapseResult* result) const {
    WedgeCollapseRecord r;
    r.vt = vt;
    r.vs = vs;
    r.error = static_cast<float>(std::sqrt(cost));
    r.moved_begin = static_cast<uint32_t>(result->moved_faces.size());
    for (uint32_t f : faces_[vt]) {
      const Triangle& t = triangles_[f];
      const int k = corner_of(t, vt);
      const std::array<uint32_t, 3>& w = corner_wedge_[f];
      if (t[(k + 2) % 3] == vs) {  // (vs, vt, vl)
        r.vl = t[(k + 1) % 3];
        r.left = {w[(k + 2) % 3], w[k], w[(k + 1) % 3]};
        r.left_face = f;
      } else if (t[(k + 1) % 3] == vs) {  // (vt, vs, vr)
        r.vr = t[(k + 2) % 3];
        r.right = {w[k], w[(k + 1) % 3], w[(k + 2) % 3]};
        r.right_face = f;
      } else {
        result->moved_faces.push_back(f);
        result->moved_wedges.push_back(w[k]);
      }
    }
    r.moved_end = static_cast<uint32_t>(result->moved_faces.size());
    result->log.push_back(r);
  }

  void collapse(uint32_t vt, uint32_t vs, const std::vector<WedgeMove>& moves) {
    const std::vector<uint32_t> faces = faces_[vt];
    for (uint32_t f : faces) {
      Triangle& t = triangles_[f];
      if (t[0] == vs || t[1] == vs || t[2] == vs) {
        for (uint32_t u : t) {
          if (u == vt) continue;
          std::vector<uint32_t>& list = faces_[u];
          list.erase(std::find(list.begin(), list.end(), f));
        }
        triangle_alive_[f] = 0;
        --live_;
        continue;
      }
      const int k = corner_of(t, vt);
      t[k] = vs;
      for (const WedgeMove& m : moves)
        if (m.from == corner_wedge_[f][k]) {
          corner_wedge_[f][k] = m.to;
          break;
        }
      faces_[vs].push_back(f);
    }
    faces_[vt].clear();
    geometric_[vs] += geometric_[vt];
    for (const WedgeMove& m : moves) {
      if (m.to == m.from) {
        wedge_point_[m.from] = vs;
        continue;
      }
      const uint32_t first = in_.value_offset[m.from];
      const uint32_t target_first = in_.value_offset[m.to];
      wedge_quadric_[m.to] += wedge_quadric_[m.from];
      for (uint32_t j = 0; j < values_of(m.from); ++j)
        component_[target_first + j] += component_[first + j];
    }
  }

  WedgeLevel level() const {
    WedgeLevel out;
    for (uint32_t f = 0; f < triangles_.size(); ++f) {
      if (!triangle_alive_[f]) continue;
      out.triangles.push_back(triangles_[f]);
      out.faces.push_back(f);
      out.corner_wedge.push_back(corner_wedge_[f]);
    }
    out.wedge_point = wedge_point_;
    return out;
  }

  const WedgeMesh& in_;
  const WedgeCollapseOptions& options_;
  std::vector<Vec3d> points_;  // scaled to a unit diagonal
  std::vector<Triangle> triangles_;
  std::vector<std::array<uint32_t, 3>> corner_wedge_;
  std::vector<uint32_t> wedge_point_;
  std::vector<std::vector<uint32_t>> faces_;  // live faces of each point
  std::vector<Quadric> geometric_;
  std::vector<Quadric> wedge_quadric_;     // the p parts of each wedge's terms
  std::vector<ComponentTerms> component_;  // per wedge value (in_.value_offset)
  std::vector<uint8_t> triangle_alive_;
  std::vector<uint32_t> stamp_;
  // The collapses found illegal since each point's neighbourhood changed.
  std::vector<std::vector<uint32_t>> refused_;  // refused_key()s since v's last change
  bool releases_ = false;       // seam_release applies (a bound, and not permissive)
  double release_penalty_ = 0;  // seam_release squared, in the costs' units
  double release_cap_ = 0;      // the largest cost of a collapse that moves seams
  uint64_t live_ = 0;
  double cos_limit_ = -1;
  // Scratch lists, kept to avoid allocating per evaluation.
  std::vector<uint32_t> around_, other_, common_, opposite_, creases_, shared_, removed_, moved_,
      targets_;
  std::vector<WedgeMove> moves_;
};

}  // namespace

Result<WedgeCollapseResult> collapse_wedges(const WedgeMesh& mesh,
                                            const WedgeCollapseOptions& options) {
  for (size_t i = 1; i < options.targets.size(); ++i)
    if (options.targets[i] > options.targets[i - 1])
      return Status(ErrorKind::kInvalidInput, "the targets are not in decreasing order");
  WedgeCollapser collapser(mesh, options);
  return collapser.run();
}

}  // namespace lodbake
