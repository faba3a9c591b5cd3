// Half-edge collapse simplification with Garland-Heckbert quadrics
// (Garland & Heckbert 1997), recording every collapse so that the caller can
// build a progressive mesh (Hoppe 1996; half-edge collapses as in Kim, Lee and
// Kobbelt's view-dependent streaming). Choices where the papers are vague
// (docs/simplify.md has the full discussion):
// - cost: the quadric's weighted MEAN squared distance, Q(p) / sum of weights
//   (like meshoptimizer), so that sqrt(cost) is a distance comparable with
//   the bounding-box diagonal for max_error;
// - boundary: each boundary edge adds the plane through it perpendicular to
//   its face, weighted by boundary_weight * |edge|^2 (an area, like faces);
// - direction: each edge is queued in its cheaper direction; when that one is
//   illegal the other is queued at its own cost; when both are, the edge is
//   "refused" and re-queued as soon as a collapse changes the 1-ring of one of
//   its endpoints;
// - legality: link condition; an interior edge between two boundary vertices
//   is refused; every vertex keeps at least three faces (one on a boundary),
//   which rules out tetrahedron pockets, duplicate faces and vanishing
//   components; no moved face may turn more than max_normal_change_degrees or
//   become (nearly) degenerate;
// - heap: binary heap of (cost, vt, vs) with ties broken by vertex indices,
//   invalidated lazily by per-vertex stamps;
// - adjacency: per-vertex face lists in one flat array; a vertex whose list
//   changes gets a fresh list appended at the end, and the array is compacted
//   when it has grown to four times its live size.
#include "lib/simplify/collapse_engine.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lib/simplify/quadric.h"

namespace lodbake {
namespace simplify_internal {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr uint32_t kAltBit = 0x80000000u;
constexpr double kPi = 3.14159265358979323846;

// 16 bytes, so that more of the heap stays in cache. Stamps only grow, so the
// sum of the two endpoints' stamps identifies "neither changed since".
struct HeapEntry {
  float cost;
  uint32_t vt;
  uint32_t vs;
  uint32_t stamps;  // stamp[vt] + stamp[vs]; high bit: the second direction tried
};

// std heap functions keep the largest on top; "largest" here is the cheapest.
struct HeapOrder {
  bool operator()(const HeapEntry& a, const HeapEntry& b) const {
    if (a.cost != b.cost) return a.cost > b.cost;
    if (a.vt != b.vt) return a.vt > b.vt;
    return a.vs > b.vs;
  }
};

enum class Verdict { kOk, kNotAnEdge, kLink, kFlip, kOther };

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
    start_.resize(n);
    count_.resize(n);
    for (size_t v = 0; v < n; ++v) {
      start_[v] = topology.face_start[v];
      count_[v] = topology.face_start[v + 1] - topology.face_start[v];
    }
    live_refs_ = refs_.size();
    refs_.reserve(refs_.size() * 2 + 16);

    setup_locks(mesh);
    setup_quadrics();
    stamp_.assign(n, 0);
    refused_.assign(n, 0);
    mark_.assign(n, 0);
    cos_limit_ = std::cos(options.max_normal_change_degrees * kPi / 180.0);
  }

  EngineState run() {
    push_initial_edges();
    const uint64_t target = settings_.target_triangles;
    const uint64_t to_remove = triangle_count_ > target ? triangle_count_ - target : 0;
    uint64_t since_progress = 0;
    while (!heap_.empty() && triangle_count_ > target) {
      std::pop_heap(heap_.begin(), heap_.end(), HeapOrder());
      const HeapEntry e = heap_.back();
      heap_.pop_back();
      const uint32_t vt = e.vt;
      const uint32_t vs = e.vs;
      if (!state_.vertex_alive[vt] || !state_.vertex_alive[vs] ||
          stamp_[vt] + stamp_[vs] != (e.stamps & ~kAltBit)) {
        continue;
      }
      // The queued cost is rounded to float; the stop test uses the exact one.
      const double exact_cost = cost(vt, vs);
      if (exact_cost > settings_.max_cost) break;
      const Vec3f p = placement(vt, vs);
      const Verdict verdict = check(vt, vs, p);
      if (verdict == Verdict::kOk) {
        collapse(vt, vs, p, exact_cost);
        if (options_.progress && ++since_progress == 4096) {
          since_progress = 0;
          options_.progress(static_cast<double>(state_.stats.input_triangles - triangle_count_) /
                            static_cast<double>(to_remove));
        }
        continue;
      }
      if (verdict == Verdict::kNotAnEdge) continue;
      if (verdict == Verdict::kLink) ++state_.stats.refused_link;
      if (verdict == Verdict::kFlip) ++state_.stats.refused_flip;
      if (verdict == Verdict::kOther) ++state_.stats.refused_other;
      if (!(e.stamps & kAltBit)) {
        const double reverse = cost(vs, vt);
        if (reverse < kInfinity) {
          push({static_cast<float>(reverse), vs, vt, (stamp_[vs] + stamp_[vt]) | kAltBit});
          continue;
        }
      }
      refused_[vt] = 1;
      refused_[vs] = 1;
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

  void setup_quadrics() {
    const size_t n = state_.positions.size();
    quadric_.assign(n, Quadric());
    const double bw = options_.boundary_weight;
    for (const Triangle& t : state_.triangles) {
      const Vec3d p0 = to_d(state_.positions[t[0]]);
      const Vec3d p1 = to_d(state_.positions[t[1]]);
      const Vec3d p2 = to_d(state_.positions[t[2]]);
      const Quadric q = Quadric::from_triangle(p0, p1, p2);
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
        const Quadric bq = Quadric::from_plane(pn, -dot(pn, pa), bw * dot(e, e));
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

  void push_initial_edges() {
    const uint32_t n = static_cast<uint32_t>(state_.positions.size());
    heap_.reserve(size_t{3} * state_.triangles.size() / 2 + 16);
    for (uint32_t v = 0; v < n; ++v) {
      const uint32_t id = ++mark_id_;
      for (uint32_t i = start_[v], end = start_[v] + count_[v]; i < end; ++i) {
        for (uint32_t w : state_.triangles[refs_[i]]) {
          if (w <= v || mark_[w] == id) continue;
          mark_[w] = id;
          push_edge(v, w, false);
        }
      }
    }
    std::make_heap(heap_.begin(), heap_.end(), HeapOrder());
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
    const Vec3d p =
        to_d(options_.placement == Placement::kHalf ? state_.positions[vs] : placement(vt, vs));
    const double weight = qt.weight + qs.weight;
    return weight > 0 ? (qt.evaluate(p) + qs.evaluate(p)) / weight : 0;
  }

  void push(const HeapEntry& e) {
    heap_.push_back(e);
    std::push_heap(heap_.begin(), heap_.end(), HeapOrder());
  }

  void push_edge(uint32_t a, uint32_t b, bool heapify) {
    const double ab = cost(a, b);  // removing a, keeping b
    const double ba = cost(b, a);
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
    const uint32_t stamps = stamp_[a] + stamp_[b];
    const HeapEntry e = remove_a ? HeapEntry{fab, a, b, stamps} : HeapEntry{fba, b, a, stamps};
    if (heapify) {
      push(e);
    } else {
      heap_.push_back(e);
    }
  }

  // ---- legality ----

  Verdict check(uint32_t vt, uint32_t vs, const Vec3f& p) {
    uint32_t shared = 0;
    uint32_t vl = kNoVertex;
    uint32_t vr = kNoVertex;
    const std::vector<Triangle>& tris = state_.triangles;
    for (uint32_t i = start_[vt], end = start_[vt] + count_[vt]; i < end; ++i) {
      const Triangle& t = tris[refs_[i]];
      const int k = corner_of(t, vs);
      if (t[k] != vs) continue;
      ++shared;
      if (t[(k + 1) % 3] == vt) {
        vl = t[(k + 2) % 3];
      } else {
        vr = t[(k + 1) % 3];
      }
    }
    if (shared == 0) return Verdict::kNotAnEdge;
    const bool edge_boundary = shared == 1;
    if (!edge_boundary && boundary_[vt] && boundary_[vs]) return Verdict::kLink;
    const bool vs_boundary_after = boundary_[vt] || boundary_[vs];
    if (count_[vs] + count_[vt] - 2 * shared < (vs_boundary_after ? 1u : 3u)) {
      return Verdict::kOther;
    }
    for (uint32_t w : {vl, vr}) {
      if (w != kNoVertex && count_[w] - 1 < (boundary_[w] ? 1u : 3u)) return Verdict::kOther;
    }
    // Link condition: the only common neighbours are the wing vertices.
    const uint32_t id = ++mark_id_;
    for (uint32_t i = start_[vs], end = start_[vs] + count_[vs]; i < end; ++i) {
      for (uint32_t w : tris[refs_[i]])
        mark_[w] = id;
    }
    for (uint32_t i = start_[vt], end = start_[vt] + count_[vt]; i < end; ++i) {
      for (uint32_t w : tris[refs_[i]]) {
        if (mark_[w] == id && w != vs && w != vt && w != vl && w != vr) return Verdict::kLink;
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
      remove_face(third, f);
    }

    if (refs_.size() + count_[vs] + count_[vt] > 4 * live_refs_ + 64) compact_refs();
    const uint32_t new_start = static_cast<uint32_t>(refs_.size());
    for (uint32_t i = start_[vs], end = start_[vs] + count_[vs]; i < end; ++i) {
      const uint32_t f = refs_[i];
      if (state_.triangle_alive[f]) refs_.push_back(f);
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
      refs_.push_back(f);
    }
    live_refs_ -= count_[vs] + count_[vt];
    start_[vs] = new_start;
    count_[vs] = static_cast<uint32_t>(refs_.size()) - new_start;
    live_refs_ += count_[vs];
    count_[vt] = 0;
    state_.vertex_alive[vt] = 0;

    quadric_[vs] += quadric_[vt];
    boundary_[vs] = boundary_[vs] | boundary_[vt];
    if (options_.placement == Placement::kOptimal) move_vertex(vt, vs, p);
    state_.log.push_back(rec);
    ++state_.stats.collapses;
    const double relative = settings_.diagonal > 0 ? rec.error / settings_.diagonal : 0;
    state_.stats.max_collapse_error = std::max(state_.stats.max_collapse_error, relative);

    requeue_around(vs);
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
        --live_refs_;
        return;
      }
    }
  }

  void compact_refs() {
    std::vector<uint32_t> packed;
    packed.reserve(2 * live_refs_ + 64);
    for (size_t v = 0; v < start_.size(); ++v) {
      const uint32_t begin = start_[v];
      start_[v] = static_cast<uint32_t>(packed.size());
      packed.insert(packed.end(), refs_.begin() + begin, refs_.begin() + begin + count_[v]);
    }
    refs_.swap(packed);
  }

  // vs changed: its edges get new costs. Neighbours holding a refused edge
  // may have become collapsible, so their edges are queued again too.
  void requeue_around(uint32_t vs) {
    ++stamp_[vs];
    refused_[vs] = 0;
    neighbours_.clear();
    const uint32_t id = ++mark_id_;
    mark_[vs] = id;
    for (uint32_t i = start_[vs], end = start_[vs] + count_[vs]; i < end; ++i) {
      for (uint32_t w : state_.triangles[refs_[i]]) {
        if (mark_[w] == id) continue;
        mark_[w] = id;
        neighbours_.push_back(w);
      }
    }
    retry_.clear();
    for (uint32_t w : neighbours_) {
      if (!refused_[w]) continue;
      refused_[w] = 0;
      ++stamp_[w];
      retry_.push_back(w);
    }
    for (uint32_t w : neighbours_)
      push_edge(vs, w, true);
    for (uint32_t w : retry_) {
      const uint32_t wid = ++mark_id_;
      mark_[w] = wid;
      mark_[vs] = wid;
      for (uint32_t i = start_[w], end = start_[w] + count_[w]; i < end; ++i) {
        for (uint32_t x : state_.triangles[refs_[i]]) {
          if (mark_[x] == wid) continue;
          mark_[x] = wid;
          push_edge(w, x, true);
        }
      }
    }
  }

  const SimplifyOptions& options_;
  const EngineSettings& settings_;
  EngineState state_;
  uint64_t triangle_count_ = 0;

  std::vector<uint32_t> refs_;
  std::vector<uint32_t> start_;
  std::vector<uint32_t> count_;
  size_t live_refs_ = 0;
  std::vector<uint8_t> boundary_;
  std::vector<uint8_t> no_remove_;
  std::vector<uint8_t> no_keep_;
  std::vector<uint8_t> fixed_;
  std::vector<MeshAttribute*> seam_attrs_;
  std::vector<Quadric> quadric_;
  std::vector<uint32_t> stamp_;
  std::vector<uint8_t> refused_;
  std::vector<uint32_t> mark_;
  uint32_t mark_id_ = 0;
  std::vector<HeapEntry> heap_;
  std::vector<uint32_t> neighbours_;
  std::vector<uint32_t> retry_;
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
