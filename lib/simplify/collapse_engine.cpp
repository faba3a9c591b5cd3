// Half-edge collapse simplification with Garland-Heckbert quadrics
// (Garland & Heckbert 1997), recording every collapse so that the caller can
// build a progressive mesh (Hoppe 1996; half-edge collapses as in Kim, Lee and
// Kobbelt's view-dependent streaming). Choices where the papers are vague
// (docs/simplify.md has the full discussion):
// - cost: the quadric's weighted MEAN squared distance, Q(p) / sum of weights
//   (like meshoptimizer), so that sqrt(cost) is a distance comparable with
//   the bounding-box diagonal for max_error; in half placement only the
//   removed vertex's quadric (the survivor does not move), in optimal
//   placement both;
// - weights: faces by sqrt(area), each boundary edge's plane (through it,
//   perpendicular to its face) by boundary_weight * |edge|: both lengths,
//   as in meshoptimizer, whose border weight 10 is the default;
// - order: passes, as in meshoptimizer. Each pass lists every edge once in
//   its cheaper direction, sorts the list by cost (stable radix sort, so ties
//   keep the listing order: triangle order) and walks it, collapsing every
//   legal edge neither of whose endpoints was touched earlier in the pass.
//   Untouched endpoints keep their quadrics and positions, so each listed cost
//   is exact when it is applied and the costs within a pass increase. A pass
//   ends at a cost limit (1.5 times the cost of the candidate at the pass's
//   collapse goal, moved on by each refusal) so that cheap edges of the next
//   pass come before expensive ones of this one; an edge refused in one pass
//   is listed again in the next;
// - direction: when the cheaper direction is illegal the other is tried at
//   its own cost, only if that is within the pass's limit (even before the
//   pass's minimum share is reached: the reverse of a cheap collapse can be
//   arbitrarily dear);
// - cracks: a boundary vertex at the same position as another one costs at
//   least the squared edge length to remove (the crack it opens);
// - legality: link condition; an interior edge between two boundary vertices
//   is refused, and a boundary vertex is removed only along a boundary edge
//   (meshoptimizer's collapse table), so a border never caves in; every vertex keeps at least three
//   faces (one on a boundary), which rules out tetrahedron pockets, duplicate faces and vanishing
//   components; no moved face may turn more than max_normal_change_degrees or
//   become (nearly) degenerate;
// - adjacency: per-vertex face lists in one flat array, rebuilt at each pass
//   (an untouched vertex's list only loses faces during the pass).
#include "lib/simplify/collapse_engine.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "lib/simplify/quadric.h"

namespace lodbake {
namespace simplify_internal {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;
// A pass may run past its cost limit until it has removed this fraction of
// its triangle goal, so that a pass whose cheap edges are all illegal still
// makes progress (meshoptimizer's rule).
constexpr uint64_t kMinPassShare = 6;
// The pass's cost limit, as a multiple of the cost of the candidate at its
// collapse goal: many candidates are skipped because a neighbour was
// collapsed first, so the goal's own cost would stop the pass too early.
constexpr double kPassLimitFactor = 1.5;

// One edge listed for a pass, in its cheaper direction: vt into vs.
struct Candidate {
  float cost;
  uint32_t vt;
  uint32_t vs;
};

// Stable LSD radix sort on the cost's bits (costs are finite and never
// negative, so their IEEE bits order like unsigned integers). Stability makes
// ties keep the listing order, which is deterministic.
void sort_by_cost(std::vector<Candidate>& items, std::vector<Candidate>& scratch) {
  constexpr int kDigitBits = 11;
  constexpr uint32_t kBuckets = 1u << kDigitBits;
  scratch.resize(items.size());
  std::vector<uint32_t> histogram(kBuckets);
  for (int shift = 0; shift < 32; shift += kDigitBits) {
    std::fill(histogram.begin(), histogram.end(), 0);
    auto digit = [shift](const Candidate& c) {
      uint32_t bits;
      std::memcpy(&bits, &c.cost, sizeof bits);
      return (bits >> shift) & (kBuckets - 1);
    };
    for (const Candidate& c : items)
      ++histogram[digit(c)];
    uint32_t sum = 0;
    for (uint32_t& h : histogram) {
      const uint32_t count = h;
      h = sum;
      sum += count;
    }
    for (const Candidate& c : items)
      scratch[histogram[digit(c)]++] = c;
    items.swap(scratch);
  }
}

enum class Verdict { kOk, kNotAnEdge, kTooCostly, kLink, kFlip, kOther };

Vec3d to_d(const Vec3f& p) {
  return {p[0], p[1], p[2]};
}

Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int corner_of(const Triangle& t, uint32_t v) {
  return t[0] == v ? 0 : (t[1] == v ? 1 : 2);
}

// True when corner values a and b of `attr` differ.
bool values_differ(const MeshAttribute& attr, uint32_t a, uint32_t b) {
  if (a == b) return false;
  for (uint32_t c = 0; c < attr.components; ++c) {
    if (attr.values[size_t{a} * attr.components + c] !=
        attr.values[size_t{b} * attr.components + c]) {
      return true;
    }
  }
  return false;
}

class Engine {
 public:
  Engine(const TriangleMesh& mesh, MeshTopology topology, const SimplifyOptions& options,
         const EngineSettings& settings)
      : options_(options), settings_(settings) {
    const size_t n = mesh.positions.size();
    state_.positions = mesh.positions;
    state_.triangles = mesh.triangles;
    state_.triangle_alive.assign(mesh.triangles.size(), 1);
    state_.vertex_alive.assign(n, 1);
    state_.normals = mesh.normals;
    state_.texcoords = mesh.texcoords;
    triangle_count_ = mesh.triangles.size();
    state_.stats.input_triangles = triangle_count_;

    boundary_ = std::move(topology.boundary);
    refs_ = std::move(topology.faces);
    start_ = std::move(topology.face_start);
    count_.resize(n);
    for (size_t v = 0; v < n; ++v)
      count_[v] = start_[v + 1] - start_[v];

    setup_locks(mesh);
    setup_quadrics();
    locked_.assign(n, 0);
    max_cost_float_ = static_cast<float>(settings.max_cost);
    if (max_cost_float_ < settings.max_cost) {
      max_cost_float_ = std::nextafter(max_cost_float_, std::numeric_limits<float>::infinity());
    }
    cos_limit_ = std::cos(options.max_normal_change_degrees * kPi / 180.0);
  }

  EngineState run() {
    const uint64_t target = settings_.target_triangles;
    live_triangles_.resize(state_.triangles.size());
    for (uint32_t f = 0; f < live_triangles_.size(); ++f)
      live_triangles_[f] = f;
    while (triangle_count_ > target) {
      list_candidates();
      sort_by_cost(candidates_, scratch_);
      if (run_pass() == 0) break;
    }
    state_.stats.output_triangles = triangle_count_;
    return std::move(state_);
  }

 private:
  // ---- setup ----

  void setup_locks(const TriangleMesh& mesh) {
    const size_t n = mesh.positions.size();
    no_remove_.assign(n, 0);
    no_keep_.assign(n, 0);
    fixed_.assign(n, 0);
    if (options_.lock_border) {
      for (size_t v = 0; v < n; ++v) {
        if (boundary_[v]) no_remove_[v] = fixed_[v] = 1;
      }
    }
    mark_coincident_boundary_vertices();
    // A vertex whose corners carry different attribute values lies on a seam:
    // removing or moving it would drag one side's values across the other,
    // so without `permissive` it is locked entirely.
    for (const MeshAttribute* attr : {&mesh.normals, &mesh.texcoords}) {
      if (attr->binding != AttributeBinding::kPerCorner) continue;
      seam_attrs_.push_back(attr == &mesh.normals ? &state_.normals : &state_.texcoords);
      if (options_.permissive) continue;
      for (size_t v = 0; v < n; ++v) {
        if (count_[v] == 0) continue;
        const uint32_t first = refs_[start_[v]];
        const uint32_t ref = attr->corners[first][corner_of(mesh.triangles[first], v)];
        for (uint32_t i = start_[v] + 1; i < start_[v] + count_[v]; ++i) {
          const uint32_t f = refs_[i];
          if (values_differ(*attr, ref, attr->corners[f][corner_of(mesh.triangles[f], v)])) {
            no_remove_[v] = no_keep_[v] = fixed_[v] = 1;
            break;
          }
        }
      }
    }
  }

  // Boundary vertices sharing their position with another boundary vertex
  // sit on an unwelded seam (two sheets meeting along a crack). Removing one
  // moves its sheet's border while the twin stays, opening the crack by up to
  // the edge's length, which the quadric (planes of tiny fringe faces,
  // averaged away) does not see: the cost of removing one is at least the
  // squared edge length, and in optimal placement they never move.
  // meshoptimizer welds by position and moves such twins in pairs (its Seam
  // kind); a PM records single vertices. Sorted by position then index:
  // deterministic.
  void mark_coincident_boundary_vertices() {
    coincident_.assign(boundary_.size(), 0);
    std::vector<uint32_t> order;
    for (uint32_t v = 0; v < boundary_.size(); ++v) {
      if (boundary_[v] && count_[v] > 0) order.push_back(v);
    }
    const std::vector<Vec3f>& pos = state_.positions;
    std::sort(order.begin(), order.end(), [&pos](uint32_t a, uint32_t b) {
      return pos[a] < pos[b] || (pos[a] == pos[b] && a < b);
    });
    for (size_t i = 1; i < order.size(); ++i) {
      if (pos[order[i]] != pos[order[i - 1]]) continue;
      for (uint32_t v : {order[i], order[i - 1]}) {
        coincident_[v] = fixed_[v] = 1;
      }
    }
  }

  void setup_quadrics() {
    const size_t n = state_.positions.size();
    quadric_.assign(n, Quadric());
    const double bw = options_.boundary_weight;
    for (const Triangle& t : state_.triangles) {
      const Vec3d p0 = to_d(state_.positions[t[0]]);
      const Vec3d p1 = to_d(state_.positions[t[1]]);
      const Vec3d p2 = to_d(state_.positions[t[2]]);
      // Weighted by sqrt(area), a length (meshoptimizer's choice): area
      // weights let a few large faces outvote many small ones in a vertex's
      // mean error, and a small curved feature then looks flat.
      Quadric q = Quadric::from_triangle(p0, p1, p2);
      if (q.weight > 0) q *= std::sqrt(q.weight) / q.weight;
      for (uint32_t v : t)
        quadric_[v] += q;
      if (!(bw > 0) || (!boundary_[t[0]] && !boundary_[t[1]] && !boundary_[t[2]])) continue;
      const Vec3d normal = cross(sub(p1, p0), sub(p2, p0));
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = t[k];
        const uint32_t b = t[(k + 1) % 3];
        if (!is_boundary_half_edge(a, b)) continue;
        const Vec3d pa = to_d(state_.positions[a]);
        const Vec3d e = sub(to_d(state_.positions[b]), pa);
        Vec3d pn = cross(e, normal);
        const double len = std::sqrt(dot(pn, pn));
        if (!(len > 0)) continue;
        pn = {pn[0] / len, pn[1] / len, pn[2] / len};
        const Quadric bq = Quadric::from_plane(pn, -dot(pn, pa), bw * std::sqrt(dot(e, e)));
        quadric_[a] += bq;
        quadric_[b] += bq;
      }
    }
  }

  // True when no face has the half-edge b->a (so a->b lies on the boundary).
  bool is_boundary_half_edge(uint32_t a, uint32_t b) const {
    for (uint32_t i = start_[b], end = start_[b] + count_[b]; i < end; ++i) {
      const Triangle& t = state_.triangles[refs_[i]];
      if (t[(corner_of(t, b) + 1) % 3] == a) return false;
    }
    return true;
  }

  // ---- the passes ----

  // Every live edge once, in its cheaper direction. A half-edge a->b stands
  // for its edge when a < b or when b->a does not exist (a boundary edge).
  void list_candidates() {
    rebuild_adjacency();
    candidates_.clear();
    for (uint32_t f : live_triangles_) {
      const Triangle& t = state_.triangles[f];
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = t[k];
        const uint32_t b = t[(k + 1) % 3];
        const bool boundary_edge = boundary_[a] && boundary_[b] && is_boundary_half_edge(a, b);
        if (a > b && !boundary_edge) continue;
        // An interior edge between two boundary vertices would pinch the
        // surface; along any other interior edge a boundary vertex may only
        // be the survivor (meshoptimizer's collapse table: a border vertex
        // moves only along the border).
        if (!boundary_edge && boundary_[a] && boundary_[b]) continue;
        add_candidate(a, b, boundary_edge);
      }
    }
  }

  // Fresh face lists of the live triangles, in triangle order. Within a pass
  // a list only loses faces until its vertex is touched (faces move only to
  // the survivor, which is then locked), so the lists of untouched vertices
  // stay exact without appending, and touched ones are not read again.
  void rebuild_adjacency() {
    size_t live = 0;
    for (uint32_t f : live_triangles_) {
      if (state_.triangle_alive[f]) live_triangles_[live++] = f;
    }
    live_triangles_.resize(live);
    const size_t n = count_.size();
    uint32_t sum = 0;
    for (size_t v = 0; v < n; ++v) {
      start_[v] = sum;
      sum += count_[v];
    }
    start_[n] = sum;
    refs_.resize(sum);
    fill_.assign(start_.begin(), start_.end() - 1);
    for (uint32_t f : live_triangles_) {
      for (uint32_t v : state_.triangles[f])
        refs_[fill_[v]++] = f;
    }
  }

  // Walks the sorted candidates; returns the number of collapses made.
  uint64_t run_pass() {
    ++pass_;
    const uint64_t target = settings_.target_triangles;
    const uint64_t goal = triangle_count_ - target;  // triangles this pass may remove
    // The candidate whose cost sets the limit: the goal's collapse count (most
    // remove two triangles), moved on by every refused candidate, which does
    // not count towards the goal (as in meshoptimizer).
    size_t goal_index = goal / 2;
    auto limit = [&] {
      return goal_index < candidates_.size() ? kPassLimitFactor * candidates_[goal_index].cost
                                             : kInfinity;
    };
    const uint64_t before = triangle_count_;
    uint64_t collapses = 0;
    for (size_t i = 0; i < candidates_.size(); ++i) {
      prefetch_candidate(i);
      const Candidate& c = candidates_[i];
      if (triangle_count_ <= target || c.cost > max_cost_float_) break;
      const bool past_limit = before - triangle_count_ > goal / kMinPassShare;
      if (c.cost > limit() && past_limit) break;
      if (locked_[c.vt] == pass_ || locked_[c.vs] == pass_) continue;
      Verdict verdict = try_collapse(c.vt, c.vs);
      if (verdict == Verdict::kLink || verdict == Verdict::kFlip || verdict == Verdict::kOther) {
        // The other direction, when it fits in this pass.
        const double reverse = cost(c.vs, c.vt);
        if (reverse <= limit()) verdict = try_collapse(c.vs, c.vt);
      }
      if (verdict == Verdict::kOk) {
        ++collapses;
      } else {
        ++goal_index;
      }
    }
    return collapses;
  }

  // The walk visits the mesh in cost order, i.e. at random: ask for the data
  // of the candidates a few steps ahead in two stages (the second needs
  // what the first fetched).
  void prefetch_candidate(size_t i) {
    constexpr size_t kFar = 16;
    constexpr size_t kNear = 6;
    if (i + kFar < candidates_.size()) {
      const Candidate& c = candidates_[i + kFar];
      __builtin_prefetch(&locked_[c.vt]);
      __builtin_prefetch(&locked_[c.vs]);
      __builtin_prefetch(&start_[c.vt]);
      __builtin_prefetch(&count_[c.vt]);
      __builtin_prefetch(&start_[c.vs]);
      __builtin_prefetch(&quadric_[c.vt]);
    }
    if (i + kNear < candidates_.size()) {
      const Candidate& c = candidates_[i + kNear];
      __builtin_prefetch(&refs_[start_[c.vt]]);
      __builtin_prefetch(&refs_[start_[c.vs]]);
      __builtin_prefetch(&state_.positions[c.vs]);
    }
  }

  // Collapses vt into vs when the cost and the legality checks allow it.
  Verdict try_collapse(uint32_t vt, uint32_t vs) {
    // The listed cost is rounded to float; the stop test uses the exact one.
    const double exact_cost = cost(vt, vs);
    if (!(exact_cost <= settings_.max_cost)) return Verdict::kTooCostly;
    const Vec3f p = placement(vt, vs);
    const Verdict verdict = check(vt, vs, p);
    switch (verdict) {
      case Verdict::kOk:
        collapse(vt, vs, p, exact_cost);
        report_progress();
        break;
      case Verdict::kLink:
        ++state_.stats.refused_link;
        break;
      case Verdict::kFlip:
        ++state_.stats.refused_flip;
        break;
      case Verdict::kOther:
        ++state_.stats.refused_other;
        break;
      case Verdict::kNotAnEdge:
      case Verdict::kTooCostly:
        break;
    }
    return verdict;
  }

  void report_progress() {
    if (!options_.progress || ++since_progress_ < 4096) return;
    since_progress_ = 0;
    const uint64_t target = settings_.target_triangles;
    const uint64_t input = state_.stats.input_triangles;
    const uint64_t to_remove = input > target ? input - target : 1;
    options_.progress(static_cast<double>(input - triangle_count_) /
                      static_cast<double>(to_remove));
  }

  // ---- costs ----

  // Where vs ends up when vt collapses into it.
  Vec3f placement(uint32_t vt, uint32_t vs) const {
    if (options_.placement == Placement::kHalf || fixed_[vs]) return state_.positions[vs];
    const Quadric q = quadric_[vt] + quadric_[vs];
    Vec3d p;
    if (q.minimizer(&p)) {
      const Vec3f pf{static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
      if (std::isfinite(pf[0]) && std::isfinite(pf[1]) && std::isfinite(pf[2])) return pf;
    }
    const Vec3f& a = state_.positions[vs];
    const Vec3f& b = state_.positions[vt];
    const Vec3f mid{0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), 0.5f * (a[2] + b[2])};
    const double ea = q.evaluate(to_d(a));
    const double eb = q.evaluate(to_d(b));
    const double em = q.evaluate(to_d(mid));
    if (ea <= eb && ea <= em) return a;
    return eb <= em ? b : mid;
  }

  // The cost of collapsing vt into vs, infinite when the locks forbid it.
  double cost(uint32_t vt, uint32_t vs) const {
    if (no_remove_[vt] || no_keep_[vs]) return kInfinity;

    // Evaluating both quadrics at p is cheaper than summing them first.
    const Quadric& qt = quadric_[vt];
    const Quadric& qs = quadric_[vs];
    // Half placement: the error vt's quadric sees at vs, as a mean over vt's
    // own weight. Adding vs's quadric (and weight) would let a survivor with a
    // large weight (long boundary edges, many merged vertices) dilute the
    // error of a small vertex; vs does not move, so its own planes gain no
    // error from this collapse (meshoptimizer ranks collapses the same way).
    if (options_.placement == Placement::kHalf) {
      const double e = qt.weight > 0 ? qt.evaluate(to_d(state_.positions[vs])) / qt.weight : 0;
      if (!coincident_[vt]) return e;
      const Vec3d d = sub(to_d(state_.positions[vt]), to_d(state_.positions[vs]));
      return std::max(e, dot(d, d));
    }
    // Optimal placement moves both endpoints: both quadrics count.
    const Vec3d p = to_d(placement(vt, vs));
    const double weight = qt.weight + qs.weight;
    return weight > 0 ? (qt.evaluate(p) + qs.evaluate(p)) / weight : 0;
  }

  void add_candidate(uint32_t a, uint32_t b, bool boundary_edge) {
    // removing a, keeping b
    const double ab = !boundary_edge && boundary_[a] ? kInfinity : cost(a, b);
    const double ba = !boundary_edge && boundary_[b] ? kInfinity : cost(b, a);
    if (!(ab < kInfinity) && !(ba < kInfinity)) return;
    const auto fab = static_cast<float>(ab);
    const auto fba = static_cast<float>(ba);
    // On equal costs remove the larger index, except in optimal placement
    // where both directions end at the same point: keep the endpoint nearer
    // to it (the smaller index on ties).
    bool remove_a = fab < fba || (fab == fba && a > b);
    if (fab == fba && options_.placement == Placement::kOptimal) {
      const Vec3d pd = to_d(placement(a, b));
      const Vec3d da = sub(pd, to_d(state_.positions[a]));
      const Vec3d db = sub(pd, to_d(state_.positions[b]));
      const double la = dot(da, da);
      const double lb = dot(db, db);
      remove_a = lb < la || (lb == la && b < a);
    }
    candidates_.push_back(remove_a ? Candidate{fab, a, b} : Candidate{fba, b, a});
  }

  // ---- legality ----

  Verdict check(uint32_t vt, uint32_t vs, const Vec3f& p) {
    uint32_t shared = 0;
    uint32_t vl = kNoVertex;
    uint32_t vr = kNoVertex;
    const std::vector<Triangle>& tris = state_.triangles;
    // vt's neighbours, gathered while looking for the shared faces: every
    // face's next vertex, and on a boundary also the previous ones (one
    // neighbour there has no face after it). Small arrays compared pairwise
    // beat marking a vertex-sized array, whose writes miss the cache.
    ring_.clear();
    const bool vt_boundary = boundary_[vt];
    for (uint32_t i = start_[vt], end = start_[vt] + count_[vt]; i < end; ++i) {
      const Triangle& t = tris[refs_[i]];
      const int k = corner_of(t, vt);
      const uint32_t next = t[(k + 1) % 3];
      const uint32_t prev = t[(k + 2) % 3];
      ring_.push_back(next);
      if (vt_boundary) ring_.push_back(prev);
      if (prev == vs) {
        vl = next;  // the face (vs, vt, vl)
        ++shared;
      } else if (next == vs) {
        vr = prev;  // the face (vt, vs, vr)
        ++shared;
      }
    }
    if (shared == 0) return Verdict::kNotAnEdge;
    const bool edge_boundary = shared == 1;
    if (!edge_boundary && vt_boundary && boundary_[vs]) return Verdict::kLink;
    if (!edge_boundary && vt_boundary) return Verdict::kOther;
    const bool vs_boundary_after = vt_boundary || boundary_[vs];
    if (count_[vs] + count_[vt] - 2 * shared < (vs_boundary_after ? 1u : 3u)) {
      return Verdict::kOther;
    }
    for (uint32_t w : {vl, vr}) {
      if (w != kNoVertex && count_[w] - 1 < (boundary_[w] ? 1u : 3u)) return Verdict::kOther;
    }
    // Link condition: the only common neighbours are the wing vertices.
    const bool vs_boundary = boundary_[vs];
    for (uint32_t i = start_[vs], end = start_[vs] + count_[vs]; i < end; ++i) {
      const Triangle& t = tris[refs_[i]];
      const int k = corner_of(t, vs);
      for (int step = 1; step <= (vs_boundary ? 2 : 1); ++step) {
        const uint32_t w = t[(k + step) % 3];
        if (w == vt || w == vl || w == vr) continue;
        if (std::find(ring_.begin(), ring_.end(), w) != ring_.end()) return Verdict::kLink;
      }
    }
    if (!faces_keep_orientation(vt, vs, p)) return Verdict::kFlip;
    if (options_.placement == Placement::kOptimal && !faces_keep_orientation(vs, vt, p)) {
      return Verdict::kFlip;
    }
    return Verdict::kOk;
  }

  // Moving vertex v to p: does every face of v not containing `other` keep
  // its orientation within the threshold and stay non-degenerate?
  bool faces_keep_orientation(uint32_t v, uint32_t other, const Vec3f& p) const {
    const Vec3d pd = to_d(p);
    for (uint32_t i = start_[v], end = start_[v] + count_[v]; i < end; ++i) {
      const Triangle& t = state_.triangles[refs_[i]];
      if (t[0] == other || t[1] == other || t[2] == other) continue;
      const int k = corner_of(t, v);
      const Vec3d a = to_d(state_.positions[t[k]]);
      const Vec3d b = to_d(state_.positions[t[(k + 1) % 3]]);
      const Vec3d c = to_d(state_.positions[t[(k + 2) % 3]]);
      const Vec3d eb = sub(b, pd);
      const Vec3d ec = sub(c, pd);
      const Vec3d n_new = cross(eb, ec);
      const double len_new = dot(n_new, n_new);
      // Nearly degenerate: the sine of the angle at p below 1e-10.
      if (!(len_new > 1e-20 * dot(eb, eb) * dot(ec, ec))) return false;
      const Vec3d n_old = cross(sub(b, a), sub(c, a));
      const double len_old = dot(n_old, n_old);
      if (!(len_old > 0)) continue;
      if (dot(n_old, n_new) < cos_limit_ * std::sqrt(len_old * len_new)) return false;
    }
    return true;
  }

  // ---- the collapse ----

  void collapse(uint32_t vt, uint32_t vs, const Vec3f& p, double cost_value) {
    std::vector<Triangle>& tris = state_.triangles;
    CollapseRecord rec;
    rec.vt = vt;
    rec.vs = vs;
    rec.vt_position = state_.positions[vt];
    rec.vs_position = state_.positions[vs];
    rec.error = static_cast<float>(std::sqrt(cost_value));

    // The attribute value index the corners moving to vs take (seams only).
    uint32_t vs_face = refs_[start_[vs]];
    uint32_t removed = 0;
    for (uint32_t i = start_[vt], end = start_[vt] + count_[vt]; i < end; ++i) {
      const uint32_t f = refs_[i];
      const Triangle& t = tris[f];
      const int k = corner_of(t, vs);
      if (t[k] != vs) continue;
      const uint32_t third = t[(k + 1) % 3] == vt ? t[(k + 2) % 3] : t[(k + 1) % 3];
      if (t[(k + 1) % 3] == vt) {
        rec.vl = third;
      } else {
        rec.vr = third;
      }
      state_.triangle_alive[f] = 0;
      --triangle_count_;
      ++removed;
      // A touched wing's list is stale anyway; only its face count matters.
      if (locked_[third] == pass_) {
        --count_[third];
      } else {
        remove_face(third, f);
      }
    }

    for (uint32_t i = start_[vt], end = start_[vt] + count_[vt]; i < end; ++i) {
      const uint32_t f = refs_[i];
      if (!state_.triangle_alive[f]) continue;
      const int k = corner_of(tris[f], vt);
      tris[f][k] = vs;
      if (!options_.permissive) {
        for (MeshAttribute* attr : seam_attrs_) {
          attr->corners[f][k] = attr->corners[vs_face][corner_of(tris[vs_face], vs)];
        }
      }
    }
    count_[vs] += count_[vt] - 2 * removed;
    count_[vt] = 0;
    state_.vertex_alive[vt] = 0;

    quadric_[vs] += quadric_[vt];
    boundary_[vs] = boundary_[vs] | boundary_[vt];
    if (options_.placement == Placement::kOptimal) move_vertex(vt, vs, p);
    state_.log.push_back(rec);
    ++state_.stats.collapses;
    const double relative = settings_.diagonal > 0 ? rec.error / settings_.diagonal : 0;
    state_.stats.max_collapse_error = std::max(state_.stats.max_collapse_error, relative);

    // Their quadrics (and vs's faces) changed: the costs listed for their
    // other edges are stale until the next pass.
    locked_[vt] = pass_;
    locked_[vs] = pass_;
  }

  // Optimal placement: vs moves to p and its per-vertex attributes are
  // interpolated along the edge at p's projection.
  void move_vertex(uint32_t vt, uint32_t vs, const Vec3f& p) {
    const Vec3d a = to_d(state_.positions[vs]);
    const Vec3d e = sub(to_d(state_.positions[vt]), a);
    const double len = dot(e, e);
    double s = len > 0 ? dot(sub(to_d(p), a), e) / len : 0.5;
    s = std::min(1.0, std::max(0.0, s));
    state_.positions[vs] = p;
    for (MeshAttribute* attr : {&state_.normals, &state_.texcoords}) {
      if (attr->binding != AttributeBinding::kPerVertex) continue;
      const uint32_t c = attr->components;
      float* dst = &attr->values[size_t{vs} * c];
      const float* src = &attr->values[size_t{vt} * c];
      double norm = 0;
      for (uint32_t i = 0; i < c; ++i) {
        dst[i] = static_cast<float>((1 - s) * dst[i] + s * src[i]);
        norm += double{dst[i]} * dst[i];
      }
      if (attr == &state_.normals && norm > 0) {
        const double inv = 1 / std::sqrt(norm);
        for (uint32_t i = 0; i < c; ++i)
          dst[i] = static_cast<float>(dst[i] * inv);
      }
    }
  }

  void remove_face(uint32_t v, uint32_t f) {
    const uint32_t begin = start_[v];
    const uint32_t end = begin + count_[v];
    for (uint32_t i = begin; i < end; ++i) {
      if (refs_[i] == f) {
        refs_[i] = refs_[end - 1];
        --count_[v];
        return;
      }
    }
  }

  const SimplifyOptions& options_;
  const EngineSettings& settings_;
  EngineState state_;
  uint64_t triangle_count_ = 0;

  // Per-vertex face lists, rebuilt at each pass: the faces of v are
  // refs_[start_[v] .. start_[v] + count_[v]) while v is untouched in the
  // pass; count_[v] is always its live face count.
  std::vector<uint32_t> refs_;
  std::vector<uint32_t> start_;
  std::vector<uint32_t> count_;
  std::vector<uint32_t> fill_;
  std::vector<uint8_t> boundary_;
  std::vector<uint8_t> no_remove_;
  std::vector<uint8_t> no_keep_;
  std::vector<uint8_t> fixed_;
  std::vector<uint8_t> coincident_;  // boundary vertex with a twin at its position
  std::vector<MeshAttribute*> seam_attrs_;
  std::vector<Quadric> quadric_;
  std::vector<uint32_t> ring_;            // check()'s scratch: vt's neighbours
  std::vector<uint32_t> live_triangles_;  // a superset, filtered at each listing
  std::vector<Candidate> candidates_;
  std::vector<Candidate> scratch_;
  std::vector<uint32_t> locked_;  // the pass in which the vertex was last touched
  uint32_t pass_ = 0;
  float max_cost_float_ = 0;  // settings_.max_cost rounded up to float
  uint64_t since_progress_ = 0;
  double cos_limit_ = -1;
};

}  // namespace

EngineState run_collapse_engine(const TriangleMesh& mesh, MeshTopology topology,
                                const SimplifyOptions& options, const EngineSettings& settings) {
  Engine engine(mesh, std::move(topology), options, settings);
  return engine.run();
}

}  // namespace simplify_internal
}  // namespace lodbake
