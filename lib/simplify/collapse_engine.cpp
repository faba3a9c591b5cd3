// Half-edge collapse simplification with Garland-Heckbert quadrics
// (Garland & Heckbert 1997), recording every collapse so that the caller can
// build a progressive mesh (Hoppe 1996; half-edge collapses as in Kim, Lee and
// Kobbelt's view-dependent streaming). Choices where the papers are vague
// (docs/simplify.md has the full discussion):
// - error: the quadric's weighted MEAN squared distance, Q(p) / sum of
//   weights (like meshoptimizer), so that sqrt(error) is a distance
//   comparable with the bounding-box diagonal for max_error; in half
//   placement only the removed vertex's quadric (the survivor does not
//   move), in optimal placement both;
// - cost, the rank: in half placement the error; in optimal placement the
//   sum Q(p) (Garland and Heckbert's, and CGAL's), so that vertices standing
//   for many faces move late;
// - weights: half placement, faces by sqrt(area), each boundary edge's plane
//   (through it, perpendicular to its face) by boundary_weight * |edge|:
//   both lengths, as in meshoptimizer, whose border weight 10 is the
//   default; optimal placement, faces by 1 and boundary planes by
//   boundary_weight, as in the paper and CGAL;
// - order: passes, as in meshoptimizer. Each pass lists every edge once in
//   its cheaper direction, sorts the list by cost (stable radix sort on the
//   upper 21 bits of the float cost, so ties keep the listing order:
//   triangle order) and walks it, collapsing every
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
// - height guard (SimplifyOptions::height_guard, half placement): vt may not
//   lie farther from the plane of a moved face than the pass's error scale
//   allows. The cost is a mean over vt's faces, which one face tilting away
//   from the surface (a chord across a thin feature or a curved border)
//   hardly moves; vt's height above that face bounds how far it strays;
// - adjacency: per-vertex corner lists (the next and previous vertex of each
//   face) in one flat array, rebuilt at each pass; a collapse only maps vt to
//   vs (alias_), lists read during the pass go through that map, and the
//   triangles are rewritten in one sweep before the next pass. The walk is
//   bound by cache misses, so what it reads of a vertex sits in one record.
#include "lib/simplify/collapse_engine.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>

#ifdef __GLIBC__
#include <malloc.h>
#endif
#ifdef __linux__
#include <sys/mman.h>
#include <unistd.h>
#endif

#include "lib/simplify/face_quadrics.h"
#include "lib/simplify/quadric.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {
namespace simplify_internal {
namespace {

// Gives the pages of v's storage past its size back to the system, keeping
// the capacity (a page touched again reads as zeros, and every element is
// written before it is read): the per-pass lists shrink in place, and their
// first pass's pages would otherwise stay resident to the end.
template <typename T>
void release_tail(std::vector<T>* v) {
#ifdef __linux__
  const auto page = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
  const uintptr_t begin =
      (reinterpret_cast<uintptr_t>(v->data() + v->size()) + page - 1) & ~(page - 1);
  const uintptr_t end = reinterpret_cast<uintptr_t>(v->data() + v->capacity()) & ~(page - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_DONTNEED);
#else
  (void)v;
#endif
}

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
// The listing, in triangle order, asks for the vertex records and quadrics of the triangle this
// many places ahead. The renumbered vertices follow the triangles, but the few thousand vertices
// between a triangle's newest and oldest one (a scan line's worth) are more
// than the hardware prefetcher follows: on the dragon the listing took 7 %
// less time with it, measured with 4, 8, 16 and 32 (16 kept; the others
// within 2 %).
constexpr size_t kListAhead = 16;
// Below this many live triangles the listing runs on one thread: starting
// the second costs more than it saves.
constexpr size_t kParallelListing = 8192;
// Likewise for the quadric set-up, in triangles.
constexpr size_t kParallelQuadrics = 8192;
// Below this many vertices the walk does not prefetch: the engine's data
// (about 180 bytes per vertex) then stay in the last-level cache, and the
// prefetching's own loads and lock tests cost more than they hide (bunny
// and armadillo: 4-5 % of the walk's time). On the dragon the walk takes
// 1.75 times as long without it.
constexpr size_t kPrefetchWalkVertices = size_t{1} << 16;

// One edge listed for a pass, in its cheaper direction, in 8 bytes rather
// than 12 (a cost and both vertex ids: 6 bytes per input triangle of the
// engine's peak): the half-edge it was listed as, whose vertices the walk
// reads from the triangle (the triangles do not change during a pass), and
// the cost's float bits with the direction in the sign bit (costs are never
// negative, so the bit is free).
struct Candidate {
  static constexpr uint32_t kReversed = 0x80000000u;  // vt is the half-edge's end
  uint32_t bits;                                      // the cost's float bits, kReversed or'ed in
  uint32_t half_edge;  // 3 * face + k: from the face's corner k to corner k + 1

  float cost() const {
    const uint32_t b = bits & ~kReversed;
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
  }
};

// The candidates of a pass, sorted by cost on demand. The order is that of
// a stable radix sort on the cost's bits (costs are never negative, so their
// IEEE bits order like unsigned integers), and stability makes ties keep the
// listing order, which is deterministic. The 10 lowest mantissa bits are
// left out: costs within a relative 2^-13 of each other keep their listing
// order. Of the remaining bits, the upper 11 are sorted for the whole list
// at the pass start; the lower 11 of each upper bucket only when the walk
// reaches it. A pass walks about a third of its candidates, so most of the
// second step of a full sort was never needed.
//
// The listing order is the order of the candidates' half-edges (3 * face +
// corner: the live triangles are listed in increasing order, in parts that
// are consecutive ranges of them), and no two candidates share a half-edge.
// So sorting by (key, half-edge) with any sort gives the stable sort's
// order, and the sort works in place: an American flag sort of the upper
// digit over the whole list, std::sort of each bucket by (key, half-edge).
// The stable sort it replaces permuted a 4-byte index per candidate (6
// bytes per input triangle of the peak) and the walk read the candidates
// through them at random; now it reads them in order.
//
// The listing comes in parts, each with its own region of items_, so that
// the threads list at once; sort_upper() joins the regions.
class CandidateList {
 public:
  // Empties the list for at most `max_count[p]` candidates in part p.
  void clear(const std::vector<size_t>& max_count) {
    const size_t parts = max_count.size();
    part_start_.resize(parts);
    part_size_.assign(parts, 0);
    size_t total = 0;
    for (size_t p = 0; p < parts; ++p) {
      part_start_[p] = total;
      total += max_count[p];
    }
    reserve(&items_, total);
    size_ = 0;
  }

  // Called by part p's thread only. The digits are counted afterwards, in
  // sort_upper(): counted here, each increment's address waited for the
  // candidate's cost, and the counts of successive candidates (often the
  // same bucket) through memory serialised the listing (bunny: a quarter of
  // its time).
  void push_back(size_t p, const Candidate& c) {
    items_.data[part_start_[p] + part_size_[p]++] = c;
  }
  size_t size() const { return size_; }
  void release() {
    items_ = Buffer<Candidate>();
    size_ = 0;
  }

  // Joins the parts' regions and groups the candidates by the upper digit,
  // in place.
  void sort_upper() {
    Candidate* items = items_.data.get();
    size_t listed = 0;
    for (size_t p = 0; p < part_size_.size(); ++p) {
      if (part_start_[p] != listed) {
        std::copy(items + part_start_[p], items + part_start_[p] + part_size_[p], items + listed);
      }
      listed += part_size_[p];
    }
    size_ = listed;
    uint32_t count[kBuckets] = {};
    for (size_t i = 0; i < listed; ++i)
      ++count[upper(items[i])];
    uint32_t sum = 0;
    for (uint32_t b = 0; b < kBuckets; ++b) {
      bucket_end_[b] = sum;
      sum += count[b];
    }
    bucket_end_[kBuckets] = sum;
    // bucket_end_[b] now is the start of bucket b, bucket_end_[b + 1] its end.
    uint32_t next[kBuckets];
    std::copy(bucket_end_, bucket_end_ + kBuckets, next);
    for (uint32_t b = 0; b < kBuckets; ++b) {
      const uint32_t end = bucket_end_[b + 1];
      while (next[b] < end) {
        Candidate c = items[next[b]];
        uint32_t d = upper(c);
        while (d != b) {
          std::swap(c, items[next[d]++]);
          d = upper(c);
        }
        items[next[b]++] = c;
      }
    }
    next_bucket_ = 0;
    sorted_end_ = 0;
  }

  // The i-th candidate in cost order, i < size().
  const Candidate& operator[](size_t i) {
    while (i >= sorted_end_)
      sort_next_bucket();
    return items_.data[i];
  }

  // Asks for the i-th candidate in cost order (the walk's look-ahead).
  void prefetch(size_t i) const {
    if (i < size_) __builtin_prefetch(&items_.data[i]);
  }

 private:
  static constexpr int kIgnoredBits = 10;
  static constexpr int kDigitBits = 11;
  static constexpr uint32_t kBuckets = 1u << kDigitBits;

  // A buffer that is only grown, never value-initialised: every element is
  // written before it is read.
  template <typename T>
  struct Buffer {
    std::unique_ptr<T[]> data;
    size_t capacity = 0;
  };
  // A buffer more than twice too large is replaced, so that its unused
  // pages do not stay resident.
  template <typename T>
  static void reserve(Buffer<T>* buffer, size_t count) {
    if (buffer->capacity >= count && buffer->capacity / 2 <= count) return;
    buffer->data.reset();
    buffer->data.reset(new T[count]);
    buffer->capacity = count;
  }

  static uint32_t key(const Candidate& c) {
    return (c.bits & ~Candidate::kReversed) >> kIgnoredBits;
  }
  static uint32_t upper(const Candidate& c) { return (key(c) >> kDigitBits) & (kBuckets - 1); }
  // The full order: key, then listing order (the half-edge).
  static uint64_t rank(const Candidate& c) { return uint64_t{key(c)} << 32 | c.half_edge; }

  // Sorts the next upper bucket in place.
  void sort_next_bucket() {
    const uint32_t begin = bucket_end_[next_bucket_];
    const uint32_t end = bucket_end_[next_bucket_ + 1];
    ++next_bucket_;
    Candidate* items = items_.data.get();
    std::sort(items + begin, items + end,
              [](const Candidate& a, const Candidate& b) { return rank(a) < rank(b); });
    sorted_end_ = end;
  }

  std::vector<size_t> part_start_;  // each part's region of items_ while listing
  std::vector<size_t> part_size_;
  Buffer<Candidate> items_;  // the parts' listings, then the sorted list
  size_t size_ = 0;
  uint32_t bucket_end_[kBuckets + 1] = {};
  uint32_t next_bucket_ = 0;
  size_t sorted_end_ = 0;
};

// Vertex flags (VertexInfo::flags).
constexpr uint32_t kBoundary = 1;     // has a boundary edge
constexpr uint32_t kNoRemove = 2;     // never removed (locked border, seam)
constexpr uint32_t kNoKeep = 4;       // never the survivor (seam)
constexpr uint32_t kFixed = 8;        // never moves (optimal placement)
constexpr uint32_t kCoincident = 16;  // boundary vertex with a twin at its position

// What the walk reads of a vertex, in one 32-byte record (two per cache
// line): the walk visits vertices in cost order, i.e. at random, and
// separate arrays cost one cache miss each.
struct alignas(32) VertexInfo {
  Vec3f position;      // current position (moved ones in optimal mode)
  uint32_t start = 0;  // its corners: corners_[start, start + size), listed at the pass start
  uint32_t size = 0;
  uint32_t count = 0;  // its live face count, always exact
  uint32_t flags = 0;
  uint32_t input_id = 0;  // breaks ties between vertices (EngineSettings::input_ids)
};

// A face around a vertex, as the vertices after and before it: enough for
// the link condition, the wing vertices and the normal test, read from one
// contiguous list instead of from the scattered triangles.
using Corner = FanCorner;

// 96 bytes, so that a quadric spans two cache lines, never three. The
// padding holds 1 / weight: the listing then multiplies where it divided
// (two divisions per candidate were the largest single cost of its quadric
// evaluations); a weight changes once per collapse, a cost is evaluated
// about six times per vertex and pass.
struct alignas(32) AlignedQuadric {
  Quadric q;
  double inverse_weight = 0;  // 0 when the weight is 0, so the mean error is 0

  void add(const Quadric& o) {
    q += o;
    update_inverse_weight();
  }
  void update_inverse_weight() { inverse_weight = q.weight > 0 ? 1.0 / q.weight : 0.0; }
};

enum class Verdict { kOk, kNotAnEdge, kTooCostly, kLink, kFlip, kOther, kHeight };

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

// Optimal placement: the minimiser of an edge's summed quadric. The sum, and
// so the point, is the same for both directions of the edge, so the listing
// and the walk solve it once per edge and pass it on. Not `ok` in half
// placement, when both endpoints are fixed, and when the system is singular
// or ill conditioned or the point is not finite in float.
struct Minimiser {
  bool ok = false;
  Vec3f p{};
};

class Engine {
 public:
  // The mesh's arrays become the state's (the walk keeps the positions in
  // vinfo_, and the state's positions are written back at the end).
  Engine(TriangleMesh mesh, MeshTopology topology, const SimplifyOptions& options,
         const EngineSettings& settings)
      : options_(options), settings_(settings), threads_(*settings.threads) {
    const size_t n = mesh.positions.size();
    state_.positions = std::move(mesh.positions);
    state_.triangles = std::move(mesh.triangles);
    state_.triangle_alive.assign(state_.triangles.size(), 1);
    state_.vertex_alive.assign(n, 1);
    state_.normals = std::move(mesh.normals);
    state_.texcoords = std::move(mesh.texcoords);
    triangle_count_ = state_.triangles.size();
    state_.stats.input_triangles = triangle_count_;
    // At most one collapse per vertex; growing the log by doubling would copy
    // it (a reserved page costs no memory until a record is written to it).
    state_.log.reserve(n);
    if (options.placement == Placement::kOptimal) state_.moved_positions.reserve(2 * n);

    vinfo_.resize(n);
    for (size_t v = 0; v < n; ++v) {
      VertexInfo& info = vinfo_[v];
      info.position = state_.positions[v];
      info.start = topology.face_start[v];
      info.count = topology.face_start[v + 1] - topology.face_start[v];
      info.size = info.count;
      info.flags = topology.boundary[v] ? kBoundary : 0;
      info.input_id = settings.input_ids ? (*settings.input_ids)[v] : static_cast<uint32_t>(v);
    }
    // vinfo_ holds the input ids now; run() gives them back (2 bytes per
    // triangle of the peak).
    if (settings.input_ids) *settings.input_ids = std::vector<uint32_t>();
    alias_.resize(n);
    for (uint32_t v = 0; v < n; ++v)
      alias_[v] = v;
    locked_.assign(n, 0);
    // live_triangles_ and live_vertices_ stay empty until the first
    // finish_pass() (lists_made_): every triangle is live until then.

    setup_locks(topology);
    // The first pass's corner lists are the topology's.
    corners_ = std::move(topology.corners);
    if (!seam_attrs_.empty()) faces_ = std::move(topology.faces);
    setup_quadrics();
    // The walk reads and moves the positions in vinfo_; run() writes them
    // back once the walk's arrays are gone, so that the two copies never
    // coexist with them (6 bytes per triangle of the peak).
    state_.positions = std::vector<Vec3f>();
    topology.face_start = std::vector<uint32_t>();
    topology.boundary = std::vector<uint8_t>();
    // The import's and the set-up's freed heap (the input mesh, the
    // renumbering, the adjacency's offsets, the positions) stays resident
    // otherwise: glibc returns only the heap's top, and the walk's arrays
    // are too large to reuse it (25 MiB of the peak of a 3.5M-triangle mesh).
#ifdef __GLIBC__
    malloc_trim(0);
#endif
    // The walk stops at the first listed cost above max_cost; in optimal
    // placement a cost is an error times a weight, so only try_collapse()
    // can tell, and every candidate is tried.
    max_cost_float_ = options.placement == Placement::kHalf
                          ? static_cast<float>(settings.max_cost)
                          : std::numeric_limits<float>::infinity();
    if (max_cost_float_ < settings.max_cost) {
      max_cost_float_ = std::nextafter(max_cost_float_, std::numeric_limits<float>::infinity());
    }
    cos_limit_ = std::cos(options.max_normal_change_degrees * kPi / 180.0);
    height_guard_ = options.height_guard && options.placement == Placement::kHalf;
    prefetch_walk_ = n >= kPrefetchWalkVertices;
  }

  EngineState run() {
    const uint64_t target = settings_.target_triangles;
    while (triangle_count_ > target) {
      if (pass_ > 0) finish_pass(/*rebuild=*/true);
      list_candidates();
      candidates_.sort_upper();
      const uint64_t collapses = run_pass();
      // The next pass lists fewer edges: the buffers are made afresh, so
      // that the pages of this pass's list are not resident with the next
      // pass's corner lists and the log (the peak was the third pass's start).
      candidates_.release();
      if (collapses == 0) break;
    }
    finish_pass(/*rebuild=*/false);
    state_.stats.output_triangles = triangle_count_;
    state_.stats.passes = pass_;
    release_walk_arrays();
    state_.positions.resize(vinfo_.size());
    for (size_t v = 0; v < vinfo_.size(); ++v)
      state_.positions[v] = vinfo_[v].position;
    if (settings_.input_ids) {
      settings_.input_ids->resize(vinfo_.size());
      for (size_t v = 0; v < vinfo_.size(); ++v)
        (*settings_.input_ids)[v] = vinfo_[v].input_id;
    }
    return std::move(state_);
  }

 private:
  bool is_set(uint32_t v, uint32_t flag) const {
    return (vinfo_[v].flags & flag) != 0;
  }

  size_t live_triangle_count() const {
    return lists_made_ ? live_triangles_.size() : state_.triangles.size();
  }
  uint32_t live_triangle(size_t i) const {
    return lists_made_ ? live_triangles_[i] : static_cast<uint32_t>(i);
  }

  // A candidate's vertices, from its half-edge's triangle.
  struct Ends {
    uint32_t vt, vs;
  };
  Ends ends(const Candidate& c) const {
    const Triangle& t = state_.triangles[c.half_edge / 3];
    const uint32_t k = c.half_edge % 3;
    const uint32_t a = t[k];
    const uint32_t b = t[k == 2 ? 0 : k + 1];
    return (c.bits & Candidate::kReversed) != 0 ? Ends{b, a} : Ends{a, b};
  }
  // Vertex order for ties: the input's.
  bool precedes(uint32_t a, uint32_t b) const {
    return vinfo_[a].input_id < vinfo_[b].input_id;
  }

  // The arrays only the walk reads, freed before the state's positions are
  // written back: the peak is then the walk's, not the walk's plus them.
  void release_walk_arrays() {
    candidates_.release();
    quadric_ = std::vector<AlignedQuadric>();
    corners_ = std::vector<Corner>();
    faces_ = std::vector<uint32_t>();
    live_triangles_ = std::vector<uint32_t>();
    live_vertices_ = std::vector<uint32_t>();
  }

  // ---- setup ----

  void setup_locks(const MeshTopology& topology) {
    const size_t n = vinfo_.size();
    const std::vector<Triangle>& triangles = state_.triangles;
    if (options_.lock_border) {
      for (size_t v = 0; v < n; ++v) {
        if (is_set(v, kBoundary)) vinfo_[v].flags |= kNoRemove | kFixed;
      }
    }
    if (!options_.locked_vertices.empty()) {
      for (size_t v = 0; v < n; ++v) {
        if (options_.locked_vertices[vinfo_[v].input_id]) vinfo_[v].flags |= kNoRemove | kFixed;
      }
    }
    mark_coincident_boundary_vertices();
    // A vertex whose corners carry different attribute values lies on a seam:
    // removing or moving it would drag one side's values across the other,
    // so without `permissive` it is locked entirely.
    for (MeshAttribute* attr : {&state_.normals, &state_.texcoords}) {
      if (attr->binding != AttributeBinding::kPerCorner) continue;
      seam_attrs_.push_back(attr);
      seam_value_.emplace_back(n, 0);
      if (options_.permissive) continue;
      const std::vector<uint32_t>& start = topology.face_start;
      for (size_t v = 0; v < n; ++v) {
        if (start[v] == start[v + 1]) continue;
        const uint32_t first = topology.faces[start[v]];
        const uint32_t ref = attr->corners[first][corner_of(triangles[first], v)];
        for (uint32_t i = start[v] + 1; i < start[v + 1]; ++i) {
          const uint32_t f = topology.faces[i];
          if (values_differ(*attr, ref, attr->corners[f][corner_of(triangles[f], v)])) {
            vinfo_[v].flags |= kNoRemove | kNoKeep | kFixed;
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
    std::vector<uint32_t> order;
    for (uint32_t v = 0; v < vinfo_.size(); ++v) {
      if (is_set(v, kBoundary) && vinfo_[v].count > 0) order.push_back(v);
    }
    const std::vector<Vec3f>& pos = state_.positions;
    std::sort(order.begin(), order.end(), [this, &pos](uint32_t a, uint32_t b) {
      return pos[a] < pos[b] || (pos[a] == pos[b] && precedes(a, b));
    });
    for (size_t i = 1; i < order.size(); ++i) {
      if (pos[order[i]] != pos[order[i - 1]]) continue;
      for (uint32_t v : {order[i], order[i - 1]}) {
        vinfo_[v].flags |= kCoincident | kFixed;
      }
    }
  }

  // Each vertex sums its faces' quadrics (and its boundary edges') in
  // triangle order. Each part owns a range of the vertices, walks all
  // triangles and adds only to its own vertices, so every sum is made in
  // the same order for any number of parts (a triangle with vertices in
  // several ranges has its quadric computed once for each).
  void setup_quadrics() {
    const size_t n = state_.positions.size();
    quadric_.assign(n, AlignedQuadric());
    const size_t parts = threads_.parts(state_.triangles.size(), kParallelQuadrics / 2);
    threads_.for_each_part(parts, [this, n, parts](size_t p) {
      const IndexRange owned = part_range(n, parts, p);
      add_quadrics(static_cast<uint32_t>(owned.begin), static_cast<uint32_t>(owned.end));
    });
  }

  void add_quadrics(uint32_t lo, uint32_t hi) {
    auto owned = [lo, hi](uint32_t v) { return v >= lo && v < hi; };
    const double bw = options_.boundary_weight;
    // Half placement ranks by a mean over sqrt-area weights, as meshoptimizer
    // does; optimal placement by Garland and Heckbert's sum over unit
    // weights, as CGAL does (see cost()).
    const bool unit = options_.placement == Placement::kOptimal;
    const BoundaryWeighting weighting =
        unit ? BoundaryWeighting::kPerEdge : BoundaryWeighting::kTimesLength;
    for (const Triangle& t : state_.triangles) {
      if (!owned(t[0]) && !owned(t[1]) && !owned(t[2])) continue;
      const Vec3d p0 = to_d(state_.positions[t[0]]);
      const Vec3d p1 = to_d(state_.positions[t[1]]);
      const Vec3d p2 = to_d(state_.positions[t[2]]);
      const Quadric q =
          unit ? unit_triangle_quadric(p0, p1, p2) : sqrt_area_triangle_quadric(p0, p1, p2);
      for (uint32_t v : t) {
        if (owned(v)) quadric_[v].q += q;
      }
      if (!(bw > 0) ||
          (!is_set(t[0], kBoundary) && !is_set(t[1], kBoundary) && !is_set(t[2], kBoundary)))
        continue;
      const Vec3d normal = cross(sub(p1, p0), sub(p2, p0));
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = t[k];
        const uint32_t b = t[(k + 1) % 3];
        if (!(owned(a) || owned(b)) || !is_boundary_half_edge(a, b)) continue;
        Quadric bq;
        if (!boundary_edge_quadric(to_d(state_.positions[a]), to_d(state_.positions[b]), normal, bw,
                                   weighting, &bq))
          continue;
        if (owned(a)) quadric_[a].q += bq;
        if (owned(b)) quadric_[b].q += bq;
      }
    }
    for (uint32_t v = lo; v < hi; ++v)
      quadric_[v].update_inverse_weight();
  }

  // True when no face has the half-edge b->a (so a->b lies on the boundary).
  bool is_boundary_half_edge(uint32_t a, uint32_t b) const {
    const VertexInfo& info = vinfo_[b];
    for (uint32_t i = info.start, end = info.start + info.size; i < end; ++i) {
      if (corners_[i].next == a) return false;
    }
    return true;
  }

  // ---- the passes ----

  // Every live edge once, in its cheaper direction. A half-edge a->b stands
  // for its edge when a precedes b or when b->a does not exist (a boundary
  // edge). In parts, consecutive ranges of the live triangles, listed at
  // once (everything they read is constant during the listing).
  void list_candidates() {
    const size_t live = live_triangle_count();
    const size_t parts = threads_.parts(live, kParallelListing / 2);
    std::vector<size_t> max_count(parts);
    for (size_t p = 0; p < parts; ++p) {
      const IndexRange range = part_range(live, parts, p);
      max_count[p] = 3 * (range.end - range.begin);
    }
    candidates_.clear(max_count);
    threads_.for_each_part(parts, [&](size_t p) {
      const IndexRange range = part_range(live, parts, p);
      list_candidates(p, range.begin, range.end);
    });
  }

  // In two steps per batch of triangles, so that no branch depends on a
  // cost: first the half-edges that stand for an edge (integer tests, each
  // half-edge written and kept by advancing the end), then their costs. A
  // branch on the comparison of two costs is mispredicted about half the
  // time and waits for both quadric evaluations, which stalled every
  // candidate behind it; without it the evaluations of successive
  // candidates overlap (bunny: a fifth less time per candidate).
  void list_candidates(size_t part, size_t begin, size_t end) {
    struct Edge {
      uint32_t a, b;
      uint32_t half_edge;
      bool boundary;
    };
    constexpr size_t kBatch = 64;
    Edge edges[3 * kBatch];
    for (size_t batch = begin; batch < end; batch += kBatch) {
      const size_t batch_end = std::min(end, batch + kBatch);
      size_t count = 0;
      for (size_t i = batch; i < batch_end; ++i) {
        if (i + kListAhead < end) {
          for (uint32_t v : state_.triangles[live_triangle(i + kListAhead)]) {
            __builtin_prefetch(&vinfo_[v]);
            prefetch_quadric(v);
          }
        }
        const uint32_t f = live_triangle(i);
        const Triangle& t = state_.triangles[f];
        for (uint32_t k = 0; k < 3; ++k) {
          const uint32_t a = t[k];
          const uint32_t b = t[k == 2 ? 0 : k + 1];
          const bool both_boundary = (vinfo_[a].flags & vinfo_[b].flags & kBoundary) != 0;
          const bool boundary_edge = both_boundary && is_boundary_half_edge(a, b);
          // An interior edge between two boundary vertices would pinch the
          // surface; along any other interior edge a boundary vertex may
          // only be the survivor (meshoptimizer's collapse table: a border
          // vertex moves only along the border).
          const bool stands = boundary_edge | precedes(a, b);
          edges[count] = {a, b, 3 * f + k, boundary_edge};
          count += stands & (boundary_edge | !both_boundary);
        }
      }
      for (size_t j = 0; j < count; ++j)
        add_candidate(part, edges[j].a, edges[j].b, edges[j].half_edge, edges[j].boundary);
    }
  }

  // Between two passes, in one sweep over the vertices and one over the
  // triangles (each step needs only what the sweeps before it wrote):
  // - the quadric sums of the pass's collapses. A pass locks both ends of a
  //   collapse, so each survivor took exactly one vertex in it and no
  //   quadric of a locked vertex is read until the next pass: the sums can
  //   wait for this sweep in vertex order (vt's survivor is one of its
  //   neighbours, nearby in the renumbered order) instead of costing the
  //   walk two more quadrics, four cache lines, per collapse at random
  //   places. Each sum is one addition, so the result is the same;
  // - the triangles rewritten. The collapses of a pass leave them as they
  //   were: a removed vertex is mapped to its survivor (alias_) and the
  //   triangles are rewritten here, in one sequential sweep, rather than at
  //   each collapse, whose faces lie scattered in memory. Faces holding a
  //   vertex twice died in the pass;
  // - fresh corner lists of the live triangles, in triangle order (the face
  //   counts are exact, so the lists' places are known before the sweep).
  //   Within a pass the lists of untouched vertices keep their dead faces
  //   and name removed vertices, which alias_ maps to their survivors; the
  //   lists of touched vertices are not read again until the next rebuild.
  // The last pass is followed by the triangle rewrite alone (`rebuild`
  // false).
  //
  // The parts share the work: first each sums the quadrics of a range of
  // the live vertices and rewrites a range of the live triangles, the kept
  // triangles then joined in part order; then, once the list places are
  // known, each fills the corner lists of a range of the live vertices,
  // walking all kept triangles and writing only its own vertices' corners,
  // so every list is in triangle order for any number of parts.
  void finish_pass(bool rebuild) {
    const bool faces = rebuild && !seam_attrs_.empty();
    const size_t live = live_triangle_count();
    const size_t live_v = lists_made_ ? live_vertices_.size() : vinfo_.size();
    const size_t parts = threads_.parts(live, kParallelListing / 2);
    std::vector<size_t> kept_triangles(parts);
    threads_.for_each_part(parts, [&](size_t p) {
      if (rebuild) {
        const IndexRange vertices = part_range(live_v, parts, p);
        for (size_t i = vertices.begin; i < vertices.end; ++i) {
          const auto v = static_cast<uint32_t>(lists_made_ ? live_vertices_[i] : i);
          if (!locked_[v]) continue;
          if (alias_[v] != v) quadric_[alias_[v]].add(quadric_[v].q);
          locked_[v] = 0;
        }
      }
      const IndexRange triangles = part_range(live, parts, p);
      kept_triangles[p] = rewrite_triangles(triangles.begin, triangles.end);
    });
    size_t kept_total = kept_triangles[0];
    for (size_t p = 1; p < parts; ++p) {
      if (!lists_made_) {
        kept_total += kept_triangles[p];
        continue;
      }
      const auto from =
          live_triangles_.begin() + static_cast<std::ptrdiff_t>(part_range(live, parts, p).begin);
      std::copy(from, from + static_cast<std::ptrdiff_t>(kept_triangles[p]),
                live_triangles_.begin() + static_cast<std::ptrdiff_t>(kept_total));
      kept_total += kept_triangles[p];
    }
    if (!lists_made_) {
      // The first list, sized to the survivors of the first pass.
      live_triangles_.reserve(kept_total);
      for (uint32_t f = 0; f < state_.triangles.size(); ++f) {
        if (state_.triangle_alive[f]) live_triangles_.push_back(f);
      }
    }
    live_triangles_.resize(kept_total);
    release_tail(&live_triangles_);
    if (!rebuild) {
      lists_made_ = true;
      return;
    }

    // Only the vertices that had faces at the pass start: the others are
    // never read again (at 1 % the last passes would sweep 100 times as
    // many records as they use).
    uint32_t sum = 0;
    size_t kept = 0;
    auto place = [this, &sum](uint32_t v) {
      VertexInfo& info = vinfo_[v];
      if (info.count == 0) return false;
      info.start = sum;
      info.size = 0;  // counts the corners filled in below, up to `count`
      sum += info.count;
      return true;
    };
    if (lists_made_) {
      for (const uint32_t v : live_vertices_) {
        if (place(v)) live_vertices_[kept++] = v;
      }
      live_vertices_.resize(kept);
      release_tail(&live_vertices_);
    } else {
      // The first list, sized to the vertices with faces (a vertex never
      // gains its first face).
      for (const VertexInfo& info : vinfo_)
        kept += info.count > 0 ? 1 : 0;
      live_vertices_.reserve(kept);
      for (uint32_t v = 0; v < vinfo_.size(); ++v) {
        if (place(v)) live_vertices_.push_back(v);
      }
      lists_made_ = true;
    }
    // The lists shrink pass by pass: their unused pages go back.
    corners_.resize(sum);
    release_tail(&corners_);
    if (faces) {
      faces_.resize(sum);
      release_tail(&faces_);
    }
    // live_vertices_ is in id order, so a range of it is a range of ids.
    threads_.for_each_part(parts, [&](size_t p) {
      const IndexRange owned = part_range(kept, parts, p);
      if (owned.begin == owned.end) return;
      const uint32_t lo = p == 0 ? 0 : live_vertices_[owned.begin];
      const uint32_t hi =
          owned.end == kept ? std::numeric_limits<uint32_t>::max() : live_vertices_[owned.end];
      for (const uint32_t f : live_triangles_) {
        const Triangle& t = state_.triangles[f];
        for (int k = 0; k < 3; ++k) {
          if (t[k] < lo || t[k] >= hi) continue;
          VertexInfo& info = vinfo_[t[k]];
          const uint32_t slot = info.start + info.size++;
          corners_[slot] = {t[(k + 1) % 3], t[(k + 2) % 3]};
          if (faces) faces_[slot] = f;
        }
      }
    });
  }

  // Rewrites live_triangles_[begin, end) through alias_, drops the faces
  // (before the lists are made: triangles begin to end, only counted)
  // that died in the pass and keeps the others at the front of the range;
  // returns how many it kept.
  size_t rewrite_triangles(size_t begin, size_t end) {
    std::vector<Triangle>& tris = state_.triangles;
    size_t live = begin;
    for (size_t i = begin; i < end; ++i) {
      const uint32_t f = live_triangle(i);
      Triangle& t = tris[f];
      const Triangle old = t;
      for (uint32_t& v : t)
        v = alias_[v];
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
        state_.triangle_alive[f] = 0;
        continue;
      }
      if (lists_made_) live_triangles_[live] = f;
      ++live;
      if (seam_attrs_.empty() || options_.permissive || t == old) continue;
      // Corners moved from vt take vs's (unique) value, so no new seam appears.
      for (int k = 0; k < 3; ++k) {
        if (t[k] == old[k]) continue;
        for (size_t a = 0; a < seam_attrs_.size(); ++a)
          seam_attrs_[a]->corners[f][k] = seam_value_[a][old[k]];
      }
    }
    return live - begin;
  }

  // Walks the sorted candidates; returns the number of collapses made.
  uint64_t run_pass() {
    ++pass_;
    const uint64_t target = settings_.target_triangles;
    const uint64_t goal = triangle_count_ - target;  // triangles this pass may remove
    // The candidate whose cost sets the limit: the goal's collapse count (most
    // remove two triangles), moved on by every refused candidate, which does
    // not count towards the goal (as in meshoptimizer); height refusals only
    // once the pass has its minimum share (below).
    size_t goal_index = goal / 2;
    auto limit = [&] {
      return goal_index < candidates_.size() ? kPassLimitFactor * candidates_[goal_index].cost()
                                             : kInfinity;
    };
    const uint64_t before = triangle_count_;
    uint64_t collapses = 0;
    height_scale_ = 0;
    for (size_t i = 0; i < candidates_.size(); ++i) {
      if (prefetch_walk_) prefetch_candidate(i);
      const Candidate& candidate = candidates_[i];
      const float listed_cost = candidate.cost();
      if (triangle_count_ <= target || listed_cost > max_cost_float_) break;
      const bool past_limit = before - triangle_count_ > goal / kMinPassShare;
      const double pass_limit = limit();
      if (listed_cost > pass_limit && past_limit) break;
      const Ends c = ends(candidate);
      if (locked_[c.vt] | locked_[c.vs]) continue;
      // The guard's scale follows the limit; once refusals have moved the
      // limit past the list's end it keeps the last finite one, and a pass
      // that never had one holds each collapse to its own cost.
      const double scale = std::min(pass_limit, settings_.max_cost);
      if (scale < kInfinity) height_scale_ = scale;
      // The listed cost is rounded to float; the stop test uses the exact one.
      // A refused try changes nothing, so the reverse shares the minimiser.
      const Minimiser m = minimiser(c.vt, c.vs);
      Verdict verdict = try_collapse(c.vt, c.vs, cost(c.vt, c.vs, m), m);
      if (verdict == Verdict::kLink || verdict == Verdict::kFlip || verdict == Verdict::kOther ||
          verdict == Verdict::kHeight) {
        // The other direction, when it fits in this pass.
        const double reverse = cost(c.vs, c.vt, m);
        if (reverse <= limit()) verdict = try_collapse(c.vs, c.vt, reverse, m);
      }
      if (verdict == Verdict::kOk) {
        ++collapses;
      } else if (verdict != Verdict::kHeight || past_limit) {
        // Height refusals move the limit on only once the pass has its
        // minimum share: early in a pass the limit is low, and moving it
        // for each of them would let the pass run on into costlier edges
        // whose faces the guard then allows.
        ++goal_index;
      }
    }
    return collapses;
  }

  // The walk visits the mesh in cost order, i.e. at random: ask for the data
  // of the candidates a few steps ahead in five stages (each needs what the
  // one before fetched; the first, the candidate itself, lies in order, the
  // second, its triangle, holds its vertices). Candidates already locked
  // will be skipped: locks are only set during a pass, so they are left out.
  void prefetch_candidate(size_t i) {
    constexpr size_t kCandidate = 40;
    constexpr size_t kTriangle = 32;
    constexpr size_t kFar = 24;
    constexpr size_t kMid = 12;
    constexpr size_t kNear = 6;
    const size_t size = candidates_.size();
    if (i + kCandidate < size) candidates_.prefetch(i + kCandidate);
    if (i + kTriangle < size) {
      __builtin_prefetch(&state_.triangles[candidates_[i + kTriangle].half_edge / 3]);
    }
    if (i + kFar < size) {
      const Ends c = ends(candidates_[i + kFar]);
      if (!(locked_[c.vt] | locked_[c.vs])) {
        __builtin_prefetch(&vinfo_[c.vt]);
        __builtin_prefetch(&vinfo_[c.vs]);
        prefetch_quadric(c.vt);
        // vs's quadric is only read in optimal placement (see finish_pass()).
        if (options_.placement == Placement::kOptimal) prefetch_quadric(c.vs);
      }
    }
    if (i + kMid < size) {
      const Ends c = ends(candidates_[i + kMid]);
      if (!(locked_[c.vt] | locked_[c.vs])) {
        for (uint32_t v : {c.vt, c.vs}) {
          const char* list = reinterpret_cast<const char*>(&corners_[vinfo_[v].start]);
          __builtin_prefetch(list);
          __builtin_prefetch(list + vinfo_[v].size * sizeof(Corner) - 1);
        }
      }
    }
    if (i + kNear < size) {
      const Ends c = ends(candidates_[i + kNear]);
      if (!(locked_[c.vt] | locked_[c.vs])) {
        const VertexInfo& info = vinfo_[c.vt];
        for (uint32_t k = info.start, end = info.start + info.size; k < end; ++k)
          __builtin_prefetch(&vinfo_[corners_[k].next]);
      }
    }
  }

  // A quadric spans two cache lines.
  void prefetch_quadric(uint32_t v) const {
    const char* q = reinterpret_cast<const char*>(&quadric_[v]);
    __builtin_prefetch(q);
    __builtin_prefetch(q + 64);
  }

  // Collapses vt into vs, whose cost() is `exact_cost`, when the cost and
  // the legality checks allow it; m is minimiser(vt, vs).
  Verdict try_collapse(uint32_t vt, uint32_t vs, double exact_cost, const Minimiser& m) {
    const double error = collapse_error(vt, vs, exact_cost);
    if (!(error <= settings_.max_cost)) return Verdict::kTooCostly;
    const Vec3f p = placement(vt, vs, m);
    // On a plane the costs and the heights are both the rounding of the
    // positions, so the guard needs no floor of its own
    // (Simplify.HeightGuardSimplifiesATiltedPlane).
    height_bound_ = height_guard_
                        ? options_.height_guard_factor * std::max(exact_cost, height_scale_)
                        : kInfinity;
    const Verdict verdict = check(vt, vs, p);
    switch (verdict) {
      case Verdict::kOk:
        collapse(vt, vs, p, error);
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
      case Verdict::kHeight:
        ++state_.stats.refused_height;
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

  // Optimal placement: the minimiser of edge (a, b)'s summed quadric (see
  // Minimiser).
  Minimiser minimiser(uint32_t a, uint32_t b) const {
    Minimiser m;
    if (options_.placement == Placement::kHalf || (is_set(a, kFixed) && is_set(b, kFixed))) {
      return m;
    }
    Vec3d p;
    if (!(quadric_[a].q + quadric_[b].q).minimizer(&p)) return m;
    m.p = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
    m.ok = std::isfinite(m.p[0]) && std::isfinite(m.p[1]) && std::isfinite(m.p[2]);
    return m;
  }

  // Where vs ends up when vt collapses into it; m is minimiser(vt, vs).
  Vec3f placement(uint32_t vt, uint32_t vs, const Minimiser& m) const {
    if (options_.placement == Placement::kHalf || is_set(vs, kFixed)) return vinfo_[vs].position;
    if (m.ok) return m.p;
    const Quadric q = quadric_[vt].q + quadric_[vs].q;
    const Vec3f& a = vinfo_[vs].position;
    const Vec3f& b = vinfo_[vt].position;
    const Vec3f mid{0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), 0.5f * (a[2] + b[2])};
    const double ea = q.evaluate(to_d(a));
    const double eb = q.evaluate(to_d(b));
    const double em = q.evaluate(to_d(mid));
    if (ea <= eb && ea <= em) return a;
    return eb <= em ? b : mid;
  }

  // The cost of collapsing vt into vs, the key the collapses are ranked by,
  // infinite when the locks forbid it; m is minimiser(vt, vs). In half
  // placement it is also the collapse's error; in optimal placement it is
  // the error times the edge's summed weight (collapse_error()).
  double cost(uint32_t vt, uint32_t vs, const Minimiser& m) const {
    if (is_set(vt, kNoRemove) || is_set(vs, kNoKeep)) return kInfinity;

    // Evaluating both quadrics at p is cheaper than summing them first.
    const Quadric& qt = quadric_[vt].q;
    const Quadric& qs = quadric_[vs].q;
    // Half placement: the error vt's quadric sees at vs, as a mean over vt's
    // own weight. Adding vs's quadric (and weight) would let a survivor with a
    // large weight (long boundary edges, many merged vertices) dilute the
    // error of a small vertex; vs does not move, so its own planes gain no
    // error from this collapse (meshoptimizer ranks collapses the same way).
    if (options_.placement == Placement::kHalf) return half_cost(vt, vinfo_[vt], vinfo_[vs]);
    // Optimal placement moves both endpoints: both quadrics count, summed
    // rather than averaged (Garland and Heckbert's cost, and CGAL's), so a
    // vertex that stands for many faces is dear to move. Averaged, cheap
    // collapses of heavy vertices went first and set the errors at 50 %
    // (docs/simplify.md, "Optimal placement"). The crack floor is a mean
    // squared distance, so it is taken on the mean.
    const Vec3d p = to_d(placement(vt, vs, m));
    const double weight = qt.weight + qs.weight;
    if (!(weight > 0)) return with_crack_floor(vinfo_[vt], p, 0);
    return weight * with_crack_floor(vinfo_[vt], p, (qt.evaluate(p) + qs.evaluate(p)) / weight);
  }

  // The error of collapsing vt into vs at cost c (a squared length: what
  // max_error bounds and the records keep): the cost itself in half
  // placement, its mean over the edge's weight in optimal placement.
  double collapse_error(uint32_t vt, uint32_t vs, double c) const {
    if (options_.placement == Placement::kHalf) return c;
    const double weight = quadric_[vt].q.weight + quadric_[vs].q.weight;
    return weight > 0 ? c / weight : c;
  }

  // Error e of moving tv to p, raised for a crack's vertex (kCoincident):
  // moved away from its twin it opens the crack by the distance it moves,
  // which its quadric hardly sees, so that distance squared is the least
  // the move costs. A select, not a branch (the half-placement listing).
  static double with_crack_floor(const VertexInfo& tv, const Vec3d& p, double e) {
    const Vec3d d = sub(to_d(tv.position), p);
    return (tv.flags & kCoincident) != 0 ? std::max(e, dot(d, d)) : e;
  }

  // Half placement: the error vt's quadric sees at vs (records tv and sv),
  // without the locks. Computed without branches on values (the listing's
  // evaluations overlap only then).
  double half_cost(uint32_t vt, const VertexInfo& tv, const VertexInfo& sv) const {
    const AlignedQuadric& q = quadric_[vt];
    const Vec3d ps = to_d(sv.position);
    return with_crack_floor(tv, ps, q.q.evaluate(ps) * q.inverse_weight);
  }

  // The half-edge a->b, listed as `half_edge` (Candidate).
  void add_candidate(size_t part, uint32_t a, uint32_t b, uint32_t half_edge, bool boundary_edge) {
    if (options_.placement == Placement::kHalf) {
      add_half_candidate(part, a, b, half_edge, boundary_edge);
      return;
    }
    // removing a, keeping b
    const Minimiser m = minimiser(a, b);
    const double ab = !boundary_edge && is_set(a, kBoundary) ? kInfinity : cost(a, b, m);
    const double ba = !boundary_edge && is_set(b, kBoundary) ? kInfinity : cost(b, a, m);
    if (!(ab < kInfinity) && !(ba < kInfinity)) return;
    const auto fab = static_cast<float>(ab);
    const auto fba = static_cast<float>(ba);
    // On equal costs remove the larger index, except in optimal placement
    // where both directions end at the same point: keep the endpoint nearer
    // to it (the smaller index on ties).
    bool remove_a = fab < fba || (fab == fba && precedes(b, a));
    if (fab == fba && options_.placement == Placement::kOptimal) {
      const Vec3d pd = to_d(placement(a, b, m));
      const Vec3d da = sub(pd, to_d(vinfo_[a].position));
      const Vec3d db = sub(pd, to_d(vinfo_[b].position));
      const double la = dot(da, da);
      const double lb = dot(db, db);
      remove_a = lb < la || (lb == la && precedes(b, a));
    }
    uint32_t bits;
    std::memcpy(&bits, remove_a ? &fab : &fba, sizeof bits);
    candidates_.push_back(part,
                          Candidate{bits | (remove_a ? 0u : Candidate::kReversed), half_edge});
  }

  // add_candidate() in half placement, with the same result, but choosing
  // the direction by selects rather than branches: the two costs compare at
  // random, and a branch on them would be mispredicted half the time. Costs
  // are never negative, so their float bits order like unsigned integers.
  void add_half_candidate(int part, uint32_t a, uint32_t b, uint32_t half_edge,
                          bool boundary_edge) {
    const VertexInfo& ia = vinfo_[a];
    const VertexInfo& ib = vinfo_[b];
    const double ab = half_cost(a, ia, ib);
    const double ba = half_cost(b, ib, ia);
    // cost()'s locks, and a boundary vertex leaves only along a boundary edge.
    const uint32_t no_remove = kNoRemove | (boundary_edge ? 0u : kBoundary);
    const bool blocked_ab = ((ia.flags & no_remove) | (ib.flags & kNoKeep)) != 0;
    const bool blocked_ba = ((ib.flags & no_remove) | (ia.flags & kNoKeep)) != 0;
    if (blocked_ab && blocked_ba) return;
    constexpr float kBlocked = std::numeric_limits<float>::infinity();
    const float fab = blocked_ab ? kBlocked : static_cast<float>(ab);
    const float fba = blocked_ba ? kBlocked : static_cast<float>(ba);
    uint32_t bits_ab;
    uint32_t bits_ba;
    std::memcpy(&bits_ab, &fab, sizeof bits_ab);
    std::memcpy(&bits_ba, &fba, sizeof bits_ba);
    // On equal costs remove the larger index.
    const uint32_t remove_a = static_cast<uint32_t>(bits_ab < bits_ba) |
                              (static_cast<uint32_t>(bits_ab == bits_ba) &
                               static_cast<uint32_t>(ib.input_id < ia.input_id));
    const uint32_t mask = 0u - remove_a;
    const uint32_t bits = (bits_ab & mask) | (bits_ba & ~mask);
    candidates_.push_back(part, Candidate{bits | (~mask & Candidate::kReversed), half_edge});
  }

  // ---- legality ----

  Verdict check(uint32_t vt, uint32_t vs, const Vec3f& p) {
    uint32_t shared = 0;
    uint32_t vl = kNoVertex;
    uint32_t vr = kNoVertex;
    // vt's neighbours, gathered while looking for the shared faces: every
    // face's next vertex, and on a boundary also the previous ones (one
    // neighbour there has no face after it). Small arrays compared pairwise
    // beat marking a vertex-sized array, whose writes miss the cache.
    ring_.clear();
    fan_.clear();
    // A one-word filter of the ring: most of vs's neighbours are not in it,
    // and one test then replaces a search of the whole ring.
    uint64_t ring_filter = 0;
    const VertexInfo& info_t = vinfo_[vt];
    const bool vt_boundary = (info_t.flags & kBoundary) != 0;
    for (uint32_t i = info_t.start, end = info_t.start + info_t.size; i < end; ++i) {
      const uint32_t next = alias_[corners_[i].next];
      const uint32_t prev = alias_[corners_[i].prev];
      if (next == prev) continue;  // the face died in this pass
      fan_.push_back({next, prev});
      ring_.push_back(next);
      ring_filter |= uint64_t{1} << (next & 63);
      if (vt_boundary) {
        ring_.push_back(prev);
        ring_filter |= uint64_t{1} << (prev & 63);
      }
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
    const VertexInfo& info_s = vinfo_[vs];
    const bool vs_boundary = (info_s.flags & kBoundary) != 0;
    if (!edge_boundary && vt_boundary && vs_boundary) return Verdict::kLink;
    if (!edge_boundary && vt_boundary) return Verdict::kOther;
    const bool vs_boundary_after = vt_boundary || vs_boundary;
    if (info_s.count + info_t.count - 2 * shared < (vs_boundary_after ? 1u : 3u)) {
      return Verdict::kOther;
    }
    for (uint32_t w : {vl, vr}) {
      if (w != kNoVertex && vinfo_[w].count - 1 < (is_set(w, kBoundary) ? 1u : 3u)) {
        return Verdict::kOther;
      }
    }
    // The moved faces before the link condition: with the height guard most
    // refusals are found here, before vs's fan is read.
    const Verdict moved = check_moved_faces(info_t.position, vs, p, fan_);
    if (moved != Verdict::kOk) return moved;
    // Link condition: the only common neighbours are the wing vertices.
    const bool optimal = options_.placement == Placement::kOptimal;
    fan_s_.clear();
    for (uint32_t i = info_s.start, end = info_s.start + info_s.size; i < end; ++i) {
      const uint32_t next = alias_[corners_[i].next];
      const uint32_t prev = alias_[corners_[i].prev];
      if (next == prev) continue;
      if (optimal) fan_s_.push_back({next, prev});
      for (uint32_t w : {next, prev}) {
        if (w == vt || w == vl || w == vr) continue;
        if ((ring_filter >> (w & 63) & 1) != 0 &&
            std::find(ring_.begin(), ring_.end(), w) != ring_.end()) {
          return Verdict::kLink;
        }
        if (!vs_boundary) break;  // inside, every neighbour is some face's next
      }
    }
    if (optimal) {
      // vs moves too (the guard is off in optimal placement: kFlip or kOk).
      const Verdict moved_s = check_moved_faces(info_s.position, vt, p, fan_s_);
      if (moved_s != Verdict::kOk) return moved_s;
    }
    vl_ = vl;
    vr_ = vr;
    shared_ = shared;
    return Verdict::kOk;
  }

  // The faces of `fan` (around a vertex at `from`) not containing `other`,
  // moved from `from` to p: kFlip when one turns by more than the threshold
  // or becomes (nearly) degenerate, kHeight when `from` lies farther from
  // its new plane than height_bound_ allows (a squared length; infinite
  // without the guard), kOk otherwise. One cross product serves both tests.
  Verdict check_moved_faces(const Vec3f& from, uint32_t other, const Vec3f& p,
                            const std::vector<Corner>& fan) const {
    const Vec3d pd = to_d(p);
    const Vec3d a = to_d(from);
    for (const Corner& corner : fan) {
      if (corner.next == other || corner.prev == other) continue;
      const Vec3d b = to_d(vinfo_[corner.next].position);
      const Vec3d c = to_d(vinfo_[corner.prev].position);
      Vec3d normal;
      if (!keeps_orientation(a, b, c, pd, cos_limit_, &normal)) return Verdict::kFlip;
      const double height = dot(normal, sub(a, pd));  // times |normal|
      if (height * height > height_bound_ * dot(normal, normal)) return Verdict::kHeight;
    }
    return Verdict::kOk;
  }

  // ---- the collapse ----

  // Merges vt into vs, as check() found it (wings vl_, vr_, shared_ faces).
  // The triangles are rewritten at the next pass (finish_pass).
  void collapse(uint32_t vt, uint32_t vs, const Vec3f& p, double error) {
    CollapseRecord rec;
    rec.vt = vt;
    rec.vs = vs;
    rec.vl = vl_;
    rec.vr = vr_;
    if (options_.placement == Placement::kOptimal) {
      state_.moved_positions.push_back(vinfo_[vt].position);
      state_.moved_positions.push_back(vinfo_[vs].position);
    }
    rec.error = static_cast<float>(std::sqrt(error));

    if (!seam_attrs_.empty() && !options_.permissive) record_seam_values(vt, vs);
    for (uint32_t w : {vl_, vr_}) {
      if (w != kNoVertex) --vinfo_[w].count;
    }
    triangle_count_ -= shared_;
    vinfo_[vs].count += vinfo_[vt].count - 2 * shared_;
    vinfo_[vt].count = 0;
    state_.vertex_alive[vt] = 0;
    alias_[vt] = vs;

    vinfo_[vs].flags |= vinfo_[vt].flags & kBoundary;
    if (options_.placement == Placement::kOptimal) move_vertex(vt, vs, p);
    state_.log.push_back(rec);
    ++state_.stats.collapses;
    const double relative = settings_.diagonal > 0 ? rec.error / settings_.diagonal : 0;
    state_.stats.max_collapse_error = std::max(state_.stats.max_collapse_error, relative);

    // Their quadrics (and vs's faces) changed: the costs listed for their
    // other edges are stale until the next pass.
    locked_[vt] = 1;
    locked_[vs] = 1;
  }

  // The attribute values the corners moving from vt to vs take at the next
  // finish_pass(): those of vs, read from any live face of vs (vs is not on
  // a seam, so its corners agree).
  void record_seam_values(uint32_t vt, uint32_t vs) {
    const VertexInfo& info = vinfo_[vs];
    for (uint32_t i = info.start, end = info.start + info.size; i < end; ++i) {
      if (alias_[corners_[i].next] == alias_[corners_[i].prev]) continue;
      const uint32_t f = faces_[i];
      const int k = corner_of(state_.triangles[f], vs);
      for (size_t a = 0; a < seam_attrs_.size(); ++a)
        seam_value_[a][vt] = seam_attrs_[a]->corners[f][k];
      return;
    }
  }

  // Optimal placement: vs moves to p and its per-vertex attributes are
  // interpolated along the edge at p's projection.
  void move_vertex(uint32_t vt, uint32_t vs, const Vec3f& p) {
    const Vec3d a = to_d(vinfo_[vs].position);
    const Vec3d e = sub(to_d(vinfo_[vt].position), a);
    const double len = dot(e, e);
    double s = len > 0 ? dot(sub(to_d(p), a), e) / len : 0.5;
    s = std::min(1.0, std::max(0.0, s));
    vinfo_[vs].position = p;
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

  const SimplifyOptions& options_;
  const EngineSettings& settings_;
  EngineState state_;
  uint64_t triangle_count_ = 0;

  std::vector<VertexInfo> vinfo_;
  // Per-vertex corner lists, rebuilt at each pass (see finish_pass);
  // faces_ holds the face of each corner, only kept for seam attributes.
  std::vector<Corner> corners_;
  std::vector<uint32_t> faces_;
  std::vector<uint32_t> alias_;  // a removed vertex's survivor; itself while alive
  std::vector<uint8_t> locked_;  // touched in this pass
  std::vector<MeshAttribute*> seam_attrs_;
  std::vector<std::vector<uint32_t>> seam_value_;  // per seam attribute, per removed vertex
  std::vector<AlignedQuadric> quadric_;
  std::vector<uint32_t> ring_;  // check()'s scratch: vt's neighbours
  std::vector<Corner> fan_;     // check()'s scratch: vt's live faces
  std::vector<Corner> fan_s_;   // likewise for vs, in optimal placement
  uint32_t vl_ = kNoVertex;     // the wings and shared face count check() found
  uint32_t vr_ = kNoVertex;
  uint32_t shared_ = 0;
  std::vector<uint32_t> live_triangles_;  // a superset, filtered at each listing
  std::vector<uint32_t> live_vertices_;   // those with faces, in order, filtered by finish_pass()
  // False until the first finish_pass(): every triangle and vertex is live,
  // and the two lists above, the identity then, are not made (6 bytes per
  // triangle of the first pass's peak).
  bool lists_made_ = false;
  const ParallelScope& threads_;
  CandidateList candidates_;
  uint32_t pass_ = 0;
  float max_cost_float_ = 0;  // the listed cost that ends a walk (see the constructor)
  uint64_t since_progress_ = 0;
  double cos_limit_ = -1;
  bool prefetch_walk_ = true;
  // The height guard (half placement only: in optimal placement vs moves too).
  bool height_guard_ = false;
  double height_scale_ = 0;          // the pass's limit, as the bound's floor (a squared length)
  double height_bound_ = kInfinity;  // the collapse being checked: its squared height limit
};

}  // namespace

EngineState run_collapse_engine(TriangleMesh mesh, MeshTopology topology,
                                const SimplifyOptions& options, const EngineSettings& settings) {
  Engine engine(std::move(mesh), std::move(topology), options, settings);
  return engine.run();
}

}  // namespace simplify_internal
}  // namespace lodbake
