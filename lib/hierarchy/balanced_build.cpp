// Balanced vertex hierarchy by level-wise independent half-edge collapses:
// the hybrid of Kim, Lee and Kobbelt section 6.2 (maximally independent edge
// sets, Xia & Varshney / El-Sana & Varshney, ordered by an error that
// reflects subtree depth, Hoppe 1997). Choices where the paper is vague:
// - a level (round) lists every half-edge collapse u -> t of the current
//   mesh whose new node is no taller than the height cap, with the key
//   (height of the node it makes, valence of u, the smaller child height,
//   quadric error), sorted, and walks the list greedily: a collapse is taken
//   when neither u nor t took part in a collapse of this level and u is not
//   adjacent to a vertex removed in this level. So the stars of the removed
//   vertices (the faces a collapse changes) of one level are disjoint, a
//   vertex is split at most once per level, and the set is maximal for the
//   walk under the cap;
// - the depth-aware error taken to its limit: height comes first, so short
//   subtrees merge before tall ones grow, and the cap (the tallest tree
//   allowed so far) rises by one only when a level under it finds no legal
//   collapse, so the forest grows a level only when every vertex that can
//   still merge has reached the current height. Low valence next: a removal
//   blocks its neighbours for the level, so low-valence vertices leave the
//   largest independent sets; a short partner next (merging with a short
//   node costs the tall one nothing more). The quadric error orders the
//   rest. On the shared meshes this gives 1 to 3 fewer levels than ordering
//   by height and error alone (docs/hierarchy.md);
// - which of the tie-breaks after height wins depends on the mesh by a
//   level either way, so up to three orderings (valence then short partner;
//   valence; short partner) finish the build from a shared state at 1/16 of
//   the vertices, and the hierarchy with the fewest <tree-id, node-id> bits
//   is kept;
// - error: lib/simplify's quadrics (faces weighted by sqrt(area), boundary
//   planes by boundary_weight * length), half placement, the removed
//   vertex's weighted mean squared distance at the survivor;
// - legality at the moment of the collapse, as lib/simplify's engine: link
//   condition, a boundary vertex is removed only along a boundary edge, every
//   vertex keeps three faces (one on a boundary), no moved face turns more
//   than max_normal_change_degrees or becomes degenerate;
// - stopping: the rounds go on until no collapse is legal (the coarsest
//   base mesh, as the paper's table compares). Stopping earlier would always
//   save id bits (a round removes fewer than half of the vertices but may
//   add a level), so the bit count is not a useful stopping rule;
// - fundamental cut vertices: faces are only ever re-labelled by collapses,
//   so a current face keeps its input face's index; the fundamental cut
//   vertex of a wing face (t, u, l) is the input vertex at l's corner of
//   that input face (docs/hierarchy.md has the argument);
// - packing: roots ordered by their survivor's input index, nodes breadth
//   first over all trees, left (surviving) child before right.
// Threads (lib/core/parallel.h): a round lists its candidates in vertex
// ranges concatenated in range order (the serial list) and sorts them in
// fixed chunks, so every thread count walks the same sorted list; the walk
// itself stays serial (each collapse blocks the ones after it). The
// orderings finish one after the other on one state, rewound to the shared
// point between them (side by side, each on a copy, cost a state per
// ordering: docs/lab/hierarchy-memory.md).
#include "lib/hierarchy/balanced_build.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <new>
#include <optional>
#include <string>

#include "formats/sections/vhie.h"
#include "formats/support/bit_packing.h"
#include "lib/core/parallel.h"
#include "lib/core/parallel_sort.h"
#include "lib/simplify/face_quadrics.h"
#include "lib/simplify/mesh_topology.h"
#include "lib/simplify/quadric.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint32_t kNone = 0xffffffffu;
// Vertices per part of a round's candidate listing (fewer: one part).
constexpr size_t kMinListPart = 4096;
// Candidates per sorted chunk: a constant, so the chunks (and the order of
// tied keys, were there any) are the same for every thread count.
constexpr size_t kSortChunk = size_t{1} << 15;

struct TempNode {
  uint32_t left = kNone;   // surviving child
  uint32_t right = kNone;  // removed child
  uint32_t parent = kNone;
  uint32_t height = 0;         // 0 for leaves
  uint32_t round = 0;          // round that made it (leaves 0)
  uint32_t survivor = 0;       // input vertex of its leftmost leaf
  uint32_t cut_left = kNone;   // input vertex
  uint32_t cut_right = kNone;  // input vertex
  float error = 0;
};

struct Candidate {
  uint32_t height;
  uint32_t secondary;
  float cost;
  uint32_t u;  // removed
  uint32_t t;  // survivor
  bool operator<(const Candidate& o) const {
    if (height != o.height) return height < o.height;
    if (secondary != o.secondary) return secondary < o.secondary;
    if (cost != o.cost) return cost < o.cost;
    if (u != o.u) return u < o.u;
    return t < o.t;
  }
};

class Builder {
 public:
  Builder(const TriangleMesh& mesh, const BalancedBuildOptions& options, int ordering,
          const ParallelScope& threads)
      : mesh_(mesh), options_(options), ordering_(ordering), threads_(&threads) {}

  Status setup() {
    const size_t n = mesh_.positions.size();
    {
      // Freed before the quadrics and nodes are made (it was held through
      // setup: the 3.49M-triangle mesh's peak, 133 MB of it).
      simplify_internal::MeshTopology topology;
      LODBAKE_RETURN_IF_ERROR(simplify_internal::build_topology(mesh_, &topology));
      std::vector<simplify_internal::FanCorner>().swap(topology.corners);
      vertex_faces_.resize(n);
      for (size_t v = 0; v < n; ++v) {
        vertex_faces_[v].assign(topology.faces.begin() + topology.face_start[v],
                                topology.faces.begin() + topology.face_start[v + 1]);
      }
      boundary_ = std::move(topology.boundary);
    }
    tris_ = mesh_.triangles;
    face_alive_.assign(tris_.size(), 1);
    cos_limit_ = std::cos(options_.max_normal_change_degrees * kPi / 180.0);
    setup_quadrics();
    // A node per vertex and at most one per collapse, reserved whole: the
    // pages are touched only as nodes are made, and growing by doubling in
    // round 1 held the old and the new array at once (the build's peak).
    nodes_.reserve(2 * n);
    nodes_.resize(n);
    node_of_.resize(n);
    for (uint32_t v = 0; v < n; ++v) {
      node_of_[v] = v;
      nodes_[v].survivor = v;
    }
    stamp_.assign(n, RoundStamp());
    ring_mark_.assign(n, 0);
    removed_.assign(n, 0);
    for (uint32_t v = 0; v < n; ++v) {
      if (!vertex_faces_[v].empty()) live_.push_back(v);
    }

    // Round 0 is the input itself.
    level_vertices_.push_back(n);
    cap_ = 1;
    round_ = 1;
    return Status::ok();
  }

  void set_ordering(int ordering) { ordering_ = ordering; }

  // The shape pack() would give (hierarchy_shape()), from the nodes: every
  // node is kept, a tree's levels are its root's height + 1.
  Result<HierarchyShape> shape() const {
    HierarchyShape s;
    s.nodes = nodes_.size();
    for (const TempNode& nd : nodes_) {
      if (nd.parent != kNone) continue;
      ++s.roots;
      s.depth = std::max(s.depth, nd.height + 1);
    }
    // pack() refuses a tree deeper than 64 levels.
    if (s.depth > 64) return runtime_error("a tree of the hierarchy is deeper than 64 levels");
    s.splits = (s.nodes - s.roots) / 2;
    s.leaves = s.roots + s.splits;
    s.tree_bits = bits_for_count(s.roots);
    s.id_bits = s.tree_bits + static_cast<int>(s.depth);
    s.id_bytes = s.id_bits <= 32 ? 4 : 8;
    return s;
  }

  // What an ordering made after the checkpoint: all pack() reads of it.
  struct Ending {
    std::vector<TempNode> tail;
    std::vector<uint64_t> level_vertices;
  };
  Ending ending() const {
    Ending e;
    e.tail.assign(nodes_.begin() + static_cast<std::ptrdiff_t>(checkpoint_.node_count),
                  nodes_.end());
    e.level_vertices = level_vertices_;
    return e;
  }
  // The nodes and levels as `e`'s ordering left them (the rest of the state
  // is not rewound: only pack() follows).
  void adopt(const Ending& e) {
    for (uint32_t node : checkpoint_.node_of)
      nodes_[node].parent = kNone;
    nodes_.resize(checkpoint_.node_count);
    nodes_.insert(nodes_.end(), e.tail.begin(), e.tail.end());
    for (size_t i = checkpoint_.node_count; i < nodes_.size(); ++i) {
      nodes_[nodes_[i].left].parent = static_cast<uint32_t>(i);
      nodes_[nodes_[i].right].parent = static_cast<uint32_t>(i);
    }
    level_vertices_ = e.level_vertices;
  }

  // The hierarchy, packed once the build's state but the nodes is freed
  // (packing beside it was the build's peak).
  Result<BalancedHierarchy> result() {
    tris_ = std::vector<Triangle>();
    face_alive_ = std::vector<uint8_t>();
    vertex_faces_ = std::vector<std::vector<uint32_t>>();
    boundary_ = std::vector<uint8_t>();
    quadric_ = std::vector<Quadric>();
    node_of_ = std::vector<uint32_t>();
    removed_ = std::vector<uint8_t>();
    stamp_ = std::vector<RoundStamp>();
    ring_mark_ = std::vector<uint32_t>();
    live_ = std::vector<uint32_t>();
    checkpoint_ = Checkpoint();
    return pack();
  }

  // What the rounds after this point change, so that restore() can rewind
  // the build to it: the orderings finish one after the other on one state
  // instead of each on a copy (a copy holds every per-vertex array; this
  // holds the live vertices' and faces' entries only).
  void checkpoint() {
    // Only the roots' parents change later: a removed vertex's node has one.
    drop_removed();
    Checkpoint& c = checkpoint_;
    c = Checkpoint();
    c.live = live_;
    c.quadric.reserve(live_.size());
    c.faces.reserve(live_.size());
    c.node_of.reserve(live_.size());
    for (uint32_t v : live_) {
      c.quadric.push_back(quadric_[v]);
      c.faces.push_back(vertex_faces_[v]);
      c.node_of.push_back(node_of_[v]);
    }
    for (uint32_t f = 0; f < tris_.size(); ++f) {
      if (!face_alive_[f]) continue;
      c.live_faces.push_back(f);
      c.tris.push_back(tris_[f]);
    }
    c.node_count = nodes_.size();
    c.round = round_;
    c.cap = cap_;
    c.level_vertices = level_vertices_;
  }

  void restore() {
    const Checkpoint& c = checkpoint_;
    // Stamps of the rewound rounds would match the rounds run again.
    for (RoundStamp& r : stamp_) {
      if (r.used >= c.round) r.used = 0;
      if (r.near >= c.round) r.near = 0;
    }
    // Only a live vertex's faces, quadric and node change after the
    // checkpoint; vertices removed since are live there.
    for (size_t i = 0; i < c.live.size(); ++i) {
      const uint32_t v = c.live[i];
      quadric_[v] = c.quadric[i];
      vertex_faces_[v] = c.faces[i];
      node_of_[v] = c.node_of[i];
      nodes_[c.node_of[i]].parent = kNone;
      removed_[v] = 0;
    }
    for (size_t i = 0; i < c.live_faces.size(); ++i) {
      tris_[c.live_faces[i]] = c.tris[i];
      face_alive_[c.live_faces[i]] = 1;
    }
    nodes_.resize(c.node_count);
    live_ = c.live;
    round_ = c.round;
    cap_ = c.cap;
    level_vertices_ = c.level_vertices;
  }

  // Levels until at most `vertices` remain or no collapse is legal.
  void build_until(uint64_t vertices) {
    while (level_vertices_.back() > vertices) {
      capped_ = false;
      const uint64_t made = run_round(round_);
      if (made == 0) {
        if (!capped_) return;
        ++cap_;
        continue;
      }
      level_vertices_.push_back(level_vertices_.back() - made);
      ++round_;
    }
  }

 private:
  void setup_quadrics() {
    const size_t n = mesh_.positions.size();
    quadric_.assign(n, Quadric());
    for (const Triangle& t : tris_) {
      const Vec3d p0 = to_d(mesh_.positions[t[0]]);
      const Vec3d p1 = to_d(mesh_.positions[t[1]]);
      const Vec3d p2 = to_d(mesh_.positions[t[2]]);
      const Quadric q = sqrt_area_triangle_quadric(p0, p1, p2);
      for (uint32_t v : t)
        quadric_[v] += q;
      if (!(options_.boundary_weight > 0)) continue;
      const Vec3d normal = cross(sub(p1, p0), sub(p2, p0));
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = t[k];
        const uint32_t b = t[(k + 1) % 3];
        if (!boundary_[a] || !boundary_[b] || has_half_edge(b, a)) continue;
        Quadric bq;
        if (!boundary_edge_quadric(to_d(mesh_.positions[a]), to_d(mesh_.positions[b]), normal,
                                   options_.boundary_weight, BoundaryWeighting::kTimesLength, &bq))
          continue;
        quadric_[a] += bq;
        quadric_[b] += bq;
      }
    }
  }

  // True when a live face has the half-edge a -> b.
  bool has_half_edge(uint32_t a, uint32_t b) const {
    for (uint32_t f : vertex_faces_[a]) {
      const Triangle& t = tris_[f];
      if (t[(corner_of(t, a) + 1) % 3] == b) return true;
    }
    return false;
  }

  void neighbours(uint32_t v, std::vector<uint32_t>* out) const {
    out->clear();
    for (uint32_t f : vertex_faces_[v]) {
      const Triangle& t = tris_[f];
      const int k = corner_of(t, v);
      out->push_back(t[(k + 1) % 3]);
      out->push_back(t[(k + 2) % 3]);
    }
    std::sort(out->begin(), out->end());
    out->erase(std::unique(out->begin(), out->end()), out->end());
  }

  float cost(uint32_t u, uint32_t t) const {
    const Quadric& q = quadric_[u];
    const double e = q.weight > 0 ? q.evaluate(to_d(mesh_.positions[t])) / q.weight : 0;
    return static_cast<float>(e);
  }

  // The candidate u -> t (u's ring has `valence` vertices); false when the
  // height cap holds it back.
  bool make_candidate(uint32_t u, uint32_t hu, uint32_t t, uint32_t valence, Candidate* c) const {
    const uint32_t ht = nodes_[node_of_[t]].height;
    const uint32_t h = std::max(hu, ht) + 1;
    if (h > cap_) return false;
    // Low-valence vertices first: each removal blocks its neighbours for
    // the level, so they leave the largest independent set.
    const uint32_t shorter = std::min(hu, ht);
    const uint32_t sec = ordering_ == 0   ? valence * 64 + shorter
                         : ordering_ == 1 ? valence
                                          : shorter;
    *c = {h, sec, cost(u, t), u, t};
    return true;
  }

  // The candidates of live vertices [begin, end) in vertex order, or with
  // `best_only` each vertex's least one; sets *capped when the height cap
  // held one back and *nan when a cost is NaN.
  void list_candidates(size_t begin, size_t end, bool best_only, std::vector<Candidate>* out,
                       bool* capped, bool* nan) const {
    // A manifold vertex has at most one neighbour more than faces: the list
    // is reserved once instead of doubling.
    size_t bound = 0;
    for (size_t i = begin; i < end; ++i)
      bound += best_only ? 1 : vertex_faces_[live_[i]].size() + 1;
    out->reserve(out->size() + bound);
    std::vector<uint32_t> ring;
    for (size_t i = begin; i < end; ++i) {
      const uint32_t u = live_[i];
      if (vertex_faces_[u].empty()) continue;
      const uint32_t hu = nodes_[node_of_[u]].height;
      if (hu + 1 > cap_) {
        *capped = true;
        continue;
      }
      neighbours(u, &ring);
      const auto valence = static_cast<uint32_t>(ring.size());
      Candidate best{};
      bool found = false;
      for (uint32_t t : ring) {
        Candidate c;
        if (!make_candidate(u, hu, t, valence, &c)) {
          *capped = true;
          continue;
        }
        if (std::isnan(c.cost)) *nan = true;
        if (!best_only) {
          out->push_back(c);
        } else if (!found || c < best) {
          best = c;
          found = true;
        }
      }
      if (found) out->push_back(best);
    }
  }

  // u's least candidate after `after` (u = after.u), in the state of the
  // walk. Valid for the walk because u is neither used nor near: its
  // faces, ring, quadric and height are as listed, and so is the key of
  // every t not used yet (a used t's key may differ, but its candidate is
  // refused wherever it falls).
  bool next_candidate(const Candidate& after, Candidate* next) {
    const uint32_t u = after.u;
    const uint32_t hu = nodes_[node_of_[u]].height;
    neighbours(u, &ring_);
    const auto valence = static_cast<uint32_t>(ring_.size());
    bool found = false;
    for (uint32_t t : ring_) {
      Candidate c;
      if (!make_candidate(u, hu, t, valence, &c) || !(after < c)) continue;
      if (!found || c < *next) {
        *next = c;
        found = true;
      }
    }
    return found;
  }

  void drop_removed() {
    live_.erase(std::remove_if(live_.begin(), live_.end(),
                               [&](uint32_t v) { return vertex_faces_[v].empty(); }),
                live_.end());
  }

  // The listing of one round (in parts when there are threads): each live
  // vertex's candidates in vertex order, or its least one.
  std::vector<Candidate> list_round(bool best_only, bool* nan) {
    const size_t n = live_.size();
    const size_t parts = threads_->parts(n, kMinListPart);
    std::vector<Candidate> candidates;
    if (parts == 1) {
      bool held_back = false;
      list_candidates(0, n, best_only, &candidates, &held_back, nan);
      capped_ = capped_ || held_back;
      return candidates;
    }
    std::vector<std::vector<Candidate>> listed(parts);
    std::vector<uint8_t> capped(parts, 0);
    std::vector<uint8_t> nans(parts, 0);
    threads_->for_each_part(listed.size(), [&](size_t p) {
      const IndexRange range = part_range(n, parts, p);
      bool part_capped = false;
      bool part_nan = false;
      list_candidates(range.begin, range.end, best_only, &listed[p], &part_capped, &part_nan);
      capped[p] = part_capped ? 1 : 0;
      nans[p] = part_nan ? 1 : 0;
    });
    size_t total = 0;
    for (const std::vector<Candidate>& part : listed)
      total += part.size();
    candidates.reserve(total);
    for (size_t p = 0; p < listed.size(); ++p) {
      candidates.insert(candidates.end(), listed[p].begin(), listed[p].end());
      std::vector<Candidate>().swap(listed[p]);
      if (capped[p]) capped_ = true;
      if (nans[p]) *nan = true;
    }
    return candidates;
  }

  enum class Taken { kYes, kUBlocked, kRefused };

  Taken take(const Candidate& c, uint32_t round) {
    const RoundStamp& su = stamp_[c.u];
    if (su.used == round || su.near == round) return Taken::kUBlocked;
    if (stamp_[c.t].used == round) return Taken::kRefused;
    uint32_t vl = kNone;
    uint32_t vr = kNone;
    if (!legal(c.u, c.t, &vl, &vr)) return Taken::kRefused;
    // u's ring, before the collapse moves its faces.
    for (uint32_t f : vertex_faces_[c.u]) {
      const Triangle& tri = tris_[f];
      for (uint32_t w : tri)
        if (w != c.u) stamp_[w].near = round;
    }
    stamp_[c.u].used = stamp_[c.t].used = round;
    collapse(c.u, c.t, vl, round, c.cost);
    return Taken::kYes;
  }

  // The walk's time goes to cache misses on the stamps of vertices far
  // apart: a candidate's are fetched well before the walk reaches it.
  void prefetch(const Candidate& c) const {
    __builtin_prefetch(&stamp_[c.u]);
    __builtin_prefetch(&stamp_[c.t]);
  }

  uint64_t run_round(uint32_t round) {
    // The live vertices, in vertex order: the same list as all vertices
    // with the removed ones skipped, without visiting them every round.
    drop_removed();
    uint64_t made = 0;
    bool nan = false;
    // Without a NaN cost the key is a strict total order ((u, t) is listed
    // once), so the walk's order is the one there is, and a vertex's next
    // candidate can wait until its last one is refused: the round lists
    // each vertex's least candidate only (a sixth of the list) and a heap
    // holds the next ones. A NaN cost keeps the whole list and
    // sort_in_chunks' merge, whose order the comparisons fix.
    std::vector<Candidate> candidates = list_round(true, &nan);
    if (nan) {
      candidates = std::vector<Candidate>();
      candidates = list_round(false, &nan);
      sort_in_chunks(*threads_, &candidates, kSortChunk, std::less<Candidate>());
      for (const Candidate& c : candidates)
        if (take(c, round) == Taken::kYes) ++made;
      return made;
    }
    auto greater = [](const Candidate& a, const Candidate& b) { return b < a; };
    std::vector<Candidate> later;  // min-heap of refused vertices' next candidates
    auto visit = [&](const Candidate& c) {
      const Taken taken = take(c, round);
      if (taken == Taken::kYes) ++made;
      if (taken != Taken::kRefused) return;
      Candidate next;
      if (!next_candidate(c, &next)) return;
      prefetch(next);
      later.push_back(next);
      std::push_heap(later.begin(), later.end(), greater);
    };
    // Visits the waiting candidates that come before *c (all without c).
    auto walk_to = [&](const Candidate* c) {
      while (!later.empty() && (c == nullptr || later.front() < *c)) {
        std::pop_heap(later.begin(), later.end(), greater);
        const Candidate next = later.back();
        later.pop_back();
        visit(next);
      }
    };
    if (candidates.size() <= kSortChunk) {
      std::sort(candidates.begin(), candidates.end());
      constexpr size_t kAhead = 16;
      for (size_t i = 0; i < candidates.size(); ++i) {
        if (i + kAhead < candidates.size()) prefetch(candidates[i + kAhead]);
        walk_to(&candidates[i]);
        visit(candidates[i]);
      }
      walk_to(nullptr);
      return made;
    }
    threads_->for_each_chunk(candidates.size(), kSortChunk, [&](size_t, IndexRange range) {
      std::sort(candidates.begin() + static_cast<std::ptrdiff_t>(range.begin),
                candidates.begin() + static_cast<std::ptrdiff_t>(range.end));
    });
    // A min-heap of each chunk's next candidate: the chunks merged on the
    // fly as the walk reads them, without a merged copy of the list.
    struct Head {
      Candidate c;
      size_t next;
      size_t end;
    };
    auto later_head = [](const Head& a, const Head& b) { return b.c < a.c; };
    std::vector<Head> heads;
    for (size_t begin = 0; begin < candidates.size(); begin += kSortChunk) {
      const size_t end = std::min(candidates.size(), begin + kSortChunk);
      heads.push_back({candidates[begin], begin + 1, end});
    }
    std::make_heap(heads.begin(), heads.end(), later_head);
    while (!heads.empty()) {
      std::pop_heap(heads.begin(), heads.end(), later_head);
      Head& h = heads.back();
      const Candidate c = h.c;
      if (h.next == h.end) {
        heads.pop_back();
      } else {
        h.c = candidates[h.next++];
        // Walked after about one candidate of every other chunk.
        prefetch(h.c);
        std::push_heap(heads.begin(), heads.end(), later_head);
      }
      walk_to(&c);
      visit(c);
    }
    walk_to(nullptr);
    return made;
  }

  bool legal(uint32_t u, uint32_t t, uint32_t* vl, uint32_t* vr) {
    uint32_t shared = 0;
    for (uint32_t f : vertex_faces_[u]) {
      const Triangle& tri = tris_[f];
      const int k = corner_of(tri, u);
      if (tri[(k + 1) % 3] == t) {
        *vr = tri[(k + 2) % 3];  // the face (u, t, vr)
        ++shared;
      } else if (tri[(k + 2) % 3] == t) {
        *vl = tri[(k + 1) % 3];  // the face (t, u, vl)
        ++shared;
      }
    }
    if (shared == 0) return false;
    const bool boundary_edge = shared == 1;
    if (boundary_[u] && !boundary_edge) return false;
    const bool boundary_after = boundary_[u] || boundary_[t];
    if (vertex_faces_[u].size() + vertex_faces_[t].size() - 2 * shared <
        (boundary_after ? 1u : 3u)) {
      return false;
    }
    for (uint32_t w : {*vl, *vr}) {
      if (w != kNone && vertex_faces_[w].size() - 1 < (boundary_[w] ? 1u : 3u)) return false;
    }
    // Link condition: u and t share no neighbour but the wings. t's ring
    // is marked with a fresh stamp (sorting both rings cost more).
    if (++ring_stamp_ == 0) {
      std::fill(ring_mark_.begin(), ring_mark_.end(), 0);
      ring_stamp_ = 1;
    }
    for (uint32_t f : vertex_faces_[t]) {
      for (uint32_t w : tris_[f])
        ring_mark_[w] = ring_stamp_;
    }
    for (uint32_t f : vertex_faces_[u]) {
      for (uint32_t w : tris_[f]) {
        if (w == u || w == t || w == *vl || w == *vr) continue;
        if (ring_mark_[w] == ring_stamp_) return false;
      }
    }
    // Faces of u not containing t move to t's position.
    const Vec3d p = to_d(mesh_.positions[t]);
    for (uint32_t f : vertex_faces_[u]) {
      const Triangle& tri = tris_[f];
      if (tri[0] == t || tri[1] == t || tri[2] == t) continue;
      const int k = corner_of(tri, u);
      const Vec3d a = to_d(mesh_.positions[u]);
      const Vec3d b = to_d(mesh_.positions[tri[(k + 1) % 3]]);
      const Vec3d c = to_d(mesh_.positions[tri[(k + 2) % 3]]);
      if (!keeps_orientation(a, b, c, p, cos_limit_)) return false;
    }
    return true;
  }

  void remove_face_of(uint32_t v, uint32_t f) {
    std::vector<uint32_t>& faces = vertex_faces_[v];
    faces.erase(std::find(faces.begin(), faces.end(), f));
  }

  void collapse(uint32_t u, uint32_t t, uint32_t vl, uint32_t round, float cost) {
    TempNode node;
    node.left = node_of_[t];
    node.right = node_of_[u];
    node.height = std::max(nodes_[node.left].height, nodes_[node.right].height) + 1;
    node.round = round;
    node.survivor = t;
    node.error = std::sqrt(cost);
    std::vector<uint32_t> moved;
    for (uint32_t f : vertex_faces_[u]) {
      Triangle& tri = tris_[f];
      const int k = corner_of(tri, u);
      const bool shared = tri[(k + 1) % 3] == t || tri[(k + 2) % 3] == t;
      if (!shared) {
        tri[k] = t;
        moved.push_back(f);
        continue;
      }
      // The fundamental cut vertex: the input vertex at the wing's corner.
      const uint32_t wing = tri[(k + 1) % 3] == t ? tri[(k + 2) % 3] : tri[(k + 1) % 3];
      const uint32_t fine = mesh_.triangles[f][corner_of(tri, wing)];
      if (wing == vl) {
        node.cut_left = fine;
      } else {
        node.cut_right = fine;
      }
      face_alive_[f] = 0;
      remove_face_of(wing, f);
      remove_face_of(t, f);
    }
    vertex_faces_[u].clear();
    std::vector<uint32_t>& tf = vertex_faces_[t];
    tf.insert(tf.end(), moved.begin(), moved.end());
    quadric_[t] += quadric_[u];
    const auto id = static_cast<uint32_t>(nodes_.size());
    nodes_[node.left].parent = id;
    nodes_[node.right].parent = id;
    nodes_.push_back(node);
    node_of_[t] = id;
    removed_[u] = 1;
  }

  // The hierarchy, packed breadth first.
  Result<BalancedHierarchy> pack() const {
    BalancedHierarchy out;
    const size_t rounds = level_vertices_.size() - 1;
    out.stats.levels_built = static_cast<uint32_t>(rounds);
    out.stats.vertices_after_level = level_vertices_;
    const auto kept = static_cast<uint32_t>(rounds);
    // Roots: kept nodes whose parent is not kept.
    std::vector<uint32_t> roots;
    for (uint32_t i = 0; i < nodes_.size(); ++i) {
      const TempNode& nd = nodes_[i];
      if (nd.round > kept) continue;
      if (nd.parent == kNone || nodes_[nd.parent].round > kept) roots.push_back(i);
    }
    std::sort(roots.begin(), roots.end(),
              [this](uint32_t a, uint32_t b) { return nodes_[a].survivor < nodes_[b].survivor; });
    VertexHierarchy& h = out.hierarchy;
    std::vector<uint32_t> order(roots.begin(), roots.end());
    std::vector<uint32_t> final_of(nodes_.size(), kNone);
    std::vector<uint8_t> depth;
    for (size_t i = 0; i < order.size(); ++i)
      depth.push_back(1);
    for (size_t i = 0; i < order.size(); ++i) {
      const TempNode& nd = nodes_[order[i]];
      final_of[order[i]] = static_cast<uint32_t>(i);
      h.parent.push_back(kNone);
      h.first_child.push_back(kNone);
      if (nd.left == kNone) continue;
      if (depth[i] >= 64) {
        return runtime_error("a tree of the hierarchy is deeper than 64 levels");
      }
      h.first_child[i] = static_cast<uint32_t>(order.size());
      order.push_back(nd.left);
      order.push_back(nd.right);
      depth.push_back(depth[i] + 1);
      depth.push_back(depth[i] + 1);
    }
    const size_t count = order.size();
    h.parent.assign(count, kNone);
    h.position.resize(count);
    h.cut_left.assign(count, kNoNode);
    h.cut_right.assign(count, kNoNode);
    h.input_vertex.assign(count, kNoVertex);
    h.error.assign(count, 0.0f);
    for (uint32_t i = 0; i < count; ++i) {
      const TempNode& nd = nodes_[order[i]];
      h.position[i] = mesh_.positions[nd.survivor];
      h.error[i] = nd.error;
      if (h.first_child[i] == kNoNode) {
        h.input_vertex[i] = order[i];  // leaves are temp nodes 0 .. leaves-1
      } else {
        h.parent[h.first_child[i]] = i;
        h.parent[h.first_child[i] + 1] = i;
      }
    }
    for (uint32_t i = 0; i < count; ++i) {
      const TempNode& nd = nodes_[order[i]];
      if (h.first_child[i] == kNoNode) continue;
      h.cut_left[i] = nd.cut_left == kNone ? kNoNode : final_of[nd.cut_left];
      h.cut_right[i] = nd.cut_right == kNone ? kNoNode : final_of[nd.cut_right];
    }
    // The base mesh: the input faces whose corners lie in three trees.
    std::vector<uint32_t> tree(count);
    for (uint32_t i = 0; i < count; ++i)
      tree[i] = h.parent[i] == kNoNode ? i : tree[h.parent[i]];
    h.base.positions.resize(roots.size());
    for (size_t r = 0; r < roots.size(); ++r)
      h.base.positions[r] = h.position[r];
    for (const Triangle& t : mesh_.triangles) {
      const Triangle b{tree[final_of[t[0]]], tree[final_of[t[1]]], tree[final_of[t[2]]]};
      if (b[0] != b[1] && b[1] != b[2] && b[0] != b[2]) h.base.triangles.push_back(b);
    }
    return out;
  }

  const TriangleMesh& mesh_;
  const BalancedBuildOptions& options_;
  int ordering_;
  const ParallelScope* threads_;  // never null
  uint32_t round_ = 1;
  std::vector<Triangle> tris_;
  std::vector<uint8_t> face_alive_;
  std::vector<std::vector<uint32_t>> vertex_faces_;
  std::vector<uint8_t> boundary_;
  std::vector<Quadric> quadric_;
  double cos_limit_ = -1;
  uint32_t cap_ = 0;
  bool capped_ = false;
  std::vector<TempNode> nodes_;
  std::vector<uint32_t> node_of_;
  std::vector<uint8_t> removed_;
  // Per vertex, the last round in which it took part in a collapse (used)
  // and in which a neighbour was removed (near): side by side, as the walk
  // reads both of u.
  struct RoundStamp {
    uint32_t used = 0;
    uint32_t near = 0;
  };
  std::vector<RoundStamp> stamp_;
  std::vector<uint32_t> ring_mark_;  // == ring_stamp_: in t's ring (legal())
  uint32_t ring_stamp_ = 0;
  std::vector<uint32_t> live_;  // vertices with faces, ascending, and some removed
  struct Checkpoint {
    std::vector<uint32_t> live;
    std::vector<Quadric> quadric;
    std::vector<std::vector<uint32_t>> faces;
    std::vector<uint32_t> node_of;
    std::vector<uint32_t> live_faces;
    std::vector<Triangle> tris;
    size_t node_count = 0;
    uint32_t round = 0;
    uint32_t cap = 0;
    std::vector<uint64_t> level_vertices;
  } checkpoint_;
  std::vector<uint32_t> ring_;  // next_candidate()'s
  std::vector<uint64_t> level_vertices_;
};

}  // namespace

Result<BalancedHierarchy> build_balanced_hierarchy(const TriangleMesh& mesh,
                                                   const BalancedBuildOptions& options) {
  if (mesh.positions.size() >= kNoVertex / 2) {
    return invalid_input("mesh has " + std::to_string(mesh.positions.size()) +
                         " vertices, a hierarchy holds fewer than 2^31");
  }
  try {
    const ParallelScope threads(options.threads);
    const int orderings = std::max(1, std::min(3, options.orderings));
    Builder shared(mesh, options, 0, threads);
    LODBAKE_RETURN_IF_ERROR(shared.setup());
    // The orderings share the levels down to 1/16 of the vertices: the
    // tie-breaks matter in the last levels, where few vertices remain and
    // the trees' heights are decided; sharing the rest makes three
    // orderings cost little more than one.
    shared.build_until(orderings > 1 ? mesh.positions.size() / 16 : 0);
    // One after the other on the one state, rewound between them; the best
    // so far is kept (fewest id bits, then shallower, then fewer roots, then
    // the first). The listing and sorting of each round stay parallel.
    if (orderings > 1) shared.checkpoint();
    // Each ordering's shape is read from its nodes; only the best's nodes
    // after the shared point are kept, and the hierarchy is packed once.
    std::optional<Builder::Ending> best;
    int best_ordering = -1;
    HierarchyShape best_shape;
    for (int ordering = 0; ordering < orderings; ++ordering) {
      if (ordering > 0) shared.restore();
      shared.set_ordering(ordering);
      shared.build_until(0);
      LODBAKE_ASSIGN_OR_RETURN(const HierarchyShape shape, shared.shape());
      if (best_ordering < 0 || shape.id_bits < best_shape.id_bits ||
          (shape.id_bits == best_shape.id_bits &&
           (shape.depth < best_shape.depth ||
            (shape.depth == best_shape.depth && shape.roots < best_shape.roots)))) {
        best_ordering = ordering;
        best_shape = shape;
        // The last ordering's ending is the state itself.
        best.reset();
        if (ordering + 1 < orderings) best = shared.ending();
      }
    }
    if (best) shared.adopt(*best);
    best.reset();
    return shared.result();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory building the balanced hierarchy");
  }
}

}  // namespace lodbake
