// Fan-hierarchy construction (Livny, Sokolovsky & El-Sana 2007, "Dual
// adaptive paths for multiresolution hierarchies", sections 3.1-3.3), with
// Garland-Heckbert quadrics (lib/simplify/quadric.h). Choices where the
// paper is vague:
// - error: delta(u) is u's accumulated quadric (its input faces' planes and
//   those of every vertex merged into it) evaluated at the centre v, as a
//   weighted MEAN squared distance (Q(p) / weight, the collapse engine's
//   measure, so it is a length squared); Delta(v) is their sum over link(v).
//   Faces weigh sqrt(area) and boundary edges add perpendicular planes, as in
//   lodbake-simplify, so both tools rank the same surface alike;
// - nodes: one per fan-merge. A vertex may be a centre again later (that is
//   what makes the hierarchy deep); its previous node is then the new node's
//   first child, which the fine path never collapses;
// - fine path: the link's vertices ordered by delta(u) (ties: vertex index),
//   collapsed one by one into v. Every collapse of the path must leave a
//   valid triangulation (FanMeshState::stars_valid: edge-manifold, single
//   fans, no duplicate triangles, no vertex left without a triangle) and turn
//   no modified triangle by more than max_normal_change_degrees, neither
//   against its normal before that collapse nor before the merge; otherwise
//   the whole merge is undone and skipped. A skipped vertex is retried when
//   a neighbour's merge changes its link (its error is then recomputed and it
//   goes back into the heap);
// - heap: a binary heap of vertices updated in place, ordered by priority
//   then vertex index, so the result is deterministic. After a merge the new
//   link's keys are refreshed lazily: a vertex is re-keyed when it reaches
//   the top and goes back in if it is no longer the cheapest (keys mostly
//   grow as quadrics accumulate, so this is nearly the eager order at a
//   fraction of the cost: most of those vertices are merged into another
//   fan before they reach the top);
// - stop: heap empty, the vertex target, or (per candidate) the error limit.
// - threads: the merges are one greedy sequence; the quadric set-up and the
//   first key of every vertex run on lib/core/parallel.h. Each set-up part
//   owns a range of the vertices and walks every triangle, adding only to
//   its own vertices, so each sum is made in triangle order; each first key
//   sums its link in star order, as a later re-key does. So the hierarchy is
//   the same for any thread count.
#include "lib/fanmerge/fan_build.h"

#include <algorithm>
#include <cmath>
#include <new>

#include "lib/core/parallel.h"
#include "lib/fanmerge/fan_mesh_state.h"
#include "lib/simplify/face_quadrics.h"
#include "lib/simplify/mesh_topology.h"
#include "lib/simplify/quadric.h"
#include "lib/simplify/vec_math.h"

namespace lodbake {
namespace {

using fan_internal::FanMeshState;
using fan_internal::has_corner;

constexpr double kPi = 3.14159265358979323846;

// A binary min-heap of vertices keyed by priority (ties: vertex index), with
// each vertex's position kept so that a changed priority is updated in place:
// the heap never holds more than one entry per vertex.
class VertexHeap {
 public:
  void reset(size_t vertex_count) {
    entries_.clear();
    position_.assign(vertex_count, kAbsent);
  }
  bool empty() const { return entries_.empty(); }
  bool contains(uint32_t v) const { return position_[v] != kAbsent; }
  double top_priority() const { return entries_.front().priority; }
  uint32_t top() const { return entries_.front().vertex; }
  void set(uint32_t v, double priority) {
    if (position_[v] == kAbsent) {
      position_[v] = static_cast<uint32_t>(entries_.size());
      entries_.push_back({priority, v});
      up(position_[v]);
      return;
    }
    const uint32_t i = position_[v];
    entries_[i].priority = priority;
    up(i);
    down(position_[v]);
  }
  void pop() { erase(entries_.front().vertex); }
  /// Removes v (no-op when absent): the last entry takes its place and moves
  /// up or down.
  void erase(uint32_t v) {
    const uint32_t i = position_[v];
    if (i == kAbsent) return;
    position_[v] = kAbsent;
    const Entry last = entries_.back();
    entries_.pop_back();
    if (i == entries_.size()) return;
    place(i, last);
    up(i);
    down(position_[last.vertex]);
  }

 private:
  static constexpr uint32_t kAbsent = 0xffffffffu;
  struct Entry {
    double priority;
    uint32_t vertex;
    bool operator<(const Entry& o) const {
      return priority < o.priority || (priority == o.priority && vertex < o.vertex);
    }
  };
  void place(uint32_t i, const Entry& e) {
    entries_[i] = e;
    position_[e.vertex] = i;
  }
  void up(uint32_t i) {
    const Entry e = entries_[i];
    while (i > 0) {
      const uint32_t parent = (i - 1) / 2;
      if (!(e < entries_[parent])) break;
      place(i, entries_[parent]);
      i = parent;
    }
    place(i, e);
  }
  void down(uint32_t i) {
    const Entry e = entries_[i];
    const uint32_t n = static_cast<uint32_t>(entries_.size());
    for (;;) {
      uint32_t child = 2 * i + 1;
      if (child >= n) break;
      if (child + 1 < n && entries_[child + 1] < entries_[child]) ++child;
      if (!(entries_[child] < e)) break;
      place(i, entries_[child]);
      i = child;
    }
    place(i, e);
  }
  std::vector<Entry> entries_;
  std::vector<uint32_t> position_;
};

// Below this many vertices per part, starting a thread costs more than its
// share of the set-up or the first keys saves.
constexpr size_t kMinVerticesPerPart = 8192;

class FanBuilder {
 public:
  FanBuilder(const TriangleMesh& input, const FanBuildOptions& options)
      : input_(input), options_(options), scope_(options.threads) {}

  Status run(const simplify_internal::MeshTopology& topology, FanBuildResult* result) {
    const size_t n = input_.positions.size();
    state_.init(input_);
    setup_quadrics(topology);
    node_of_.resize(n);
    for (uint32_t v = 0; v < n; ++v)
      node_of_[v] = v;
    heap_.reset(n);
    mark_.assign(n, 0);
    dirty_.assign(n, 0);
    h_.vertex_count = static_cast<uint32_t>(n);
    h_.triangle_count = static_cast<uint32_t>(input_.triangles.size());
    cos_limit_ = std::cos(options_.max_normal_change_degrees * kPi / 180.0);
    set_limits();

    push_all();
    const uint64_t start_vertices = state_.present_count();
    const uint64_t goal = start_vertices > target_ ? start_vertices - target_ : 1;
    uint64_t next_report = 0;
    while (!heap_.empty()) {
      if (state_.present_count() <= target_) break;
      const uint32_t v = heap_.top();
      if (dirty_[v]) {
        // Its link changed since its key was computed: re-key it and let
        // the heap decide again.
        dirty_[v] = 0;
        heap_.set(v, priority(v));
        continue;
      }
      heap_.pop();
      if (!state_.present(v)) continue;
      if (error_limit_ && delta_of(v) > *error_limit_) {
        ++stats_.skipped_error;
        continue;
      }
      if (try_merge(v)) update_after_merge(v);
      if (options_.progress && stats_.merges >= next_report) {
        next_report = stats_.merges + 1024;
        const double done = static_cast<double>(start_vertices - state_.present_count());
        options_.progress(std::min(1.0, done / static_cast<double>(goal)));
      }
    }
    stats_.merges = h_.internal_count();
    stats_.output_vertices = state_.present_count();
    stats_.output_triangles = state_.alive_count();
    result->coarsest.positions = input_.positions;
    result->coarsest.triangles = state_.alive_triangles();
    result->hierarchy = std::move(h_);
    result->stats = stats_;
    return Status::ok();
  }

 private:
  void set_limits() {
    const uint64_t n = state_.present_count();
    target_ = 0;
    if (options_.target_vertices) target_ = std::max(target_, *options_.target_vertices);
    if (options_.target_ratio)
      target_ = std::max(target_, static_cast<uint64_t>(
                                      std::ceil(*options_.target_ratio * static_cast<double>(n))));
    if (options_.max_error) {
      Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
      for (const Vec3f& p : input_.positions)
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], static_cast<double>(p[k]));
          hi[k] = std::max(hi[k], static_cast<double>(p[k]));
        }
      const Vec3d d = sub(hi, lo);
      const double diagonal = input_.positions.empty() ? 0 : std::sqrt(dot(d, d));
      const double limit = *options_.max_error * diagonal;
      error_limit_ = limit * limit;
    }
  }

  bool is_boundary_half_edge(const simplify_internal::MeshTopology& topology, uint32_t a,
                             uint32_t b) const {
    for (uint32_t i = topology.face_start[b]; i < topology.face_start[b + 1]; ++i) {
      const Triangle& t = input_.triangles[topology.faces[i]];
      for (int k = 0; k < 3; ++k)
        if (t[k] == b && t[(k + 1) % 3] == a) return false;
    }
    return true;
  }

  void setup_quadrics(const simplify_internal::MeshTopology& topology) {
    const size_t n = input_.positions.size();
    quadric_.assign(n, Quadric());
    const size_t parts = scope_.parts(n, kMinVerticesPerPart);
    scope_.for_each_part(parts, [&](size_t p) {
      const IndexRange own = part_range(n, parts, p);
      add_quadrics(topology, own.begin, own.end);
    });
  }

  // Adds every triangle's quadrics to its vertices in [lo, hi).
  void add_quadrics(const simplify_internal::MeshTopology& topology, size_t lo, size_t hi) {
    auto owned = [lo, hi](uint32_t v) { return v >= lo && v < hi; };
    const double bw = options_.boundary_weight;
    for (const Triangle& t : input_.triangles) {
      if (!owned(t[0]) && !owned(t[1]) && !owned(t[2])) continue;
      const Vec3d p0 = to_d(input_.positions[t[0]]);
      const Vec3d p1 = to_d(input_.positions[t[1]]);
      const Vec3d p2 = to_d(input_.positions[t[2]]);
      const Quadric q = sqrt_area_triangle_quadric(p0, p1, p2);
      for (uint32_t v : t)
        if (owned(v)) quadric_[v] += q;
      if (!(bw > 0) ||
          (!topology.boundary[t[0]] && !topology.boundary[t[1]] && !topology.boundary[t[2]]))
        continue;
      const Vec3d normal = cross(sub(p1, p0), sub(p2, p0));
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = t[k];
        const uint32_t b = t[(k + 1) % 3];
        if ((!owned(a) && !owned(b)) || !topology.boundary[a] || !topology.boundary[b] ||
            !is_boundary_half_edge(topology, a, b))
          continue;
        Quadric bq;
        if (!boundary_edge_quadric(to_d(input_.positions[a]), to_d(input_.positions[b]), normal, bw,
                                   BoundaryWeighting::kTimesLength, &bq))
          continue;
        if (owned(a)) quadric_[a] += bq;
        if (owned(b)) quadric_[b] += bq;
      }
    }
  }

  double delta(uint32_t u, uint32_t v) const {
    const Quadric& q = quadric_[u];
    return q.weight > 0 ? q.evaluate(to_d(input_.positions[v])) / q.weight : 0.0;
  }

  uint32_t next_stamp() {
    if (++stamp_ == 0) {
      std::fill(mark_.begin(), mark_.end(), 0);
      stamp_ = 1;
    }
    return stamp_;
  }

  // The distinct vertices of v's star other than v, in star order (a stamp
  // filters repeats; the order is deterministic).
  void link(uint32_t v, std::vector<uint32_t>* out) {
    out->clear();
    const uint32_t stamp = next_stamp();
    mark_[v] = stamp;
    for (uint32_t t : state_.triangles_of(v))
      for (uint32_t x : state_.corners(t))
        if (mark_[x] != stamp) {
          mark_[x] = stamp;
          out->push_back(x);
          // Every caller evaluates the link's quadrics next (88 bytes,
          // usually two cache lines, far apart in error order): start
          // loading them now.
          const char* q = reinterpret_cast<const char*>(&quadric_[x]);
          __builtin_prefetch(q);
          __builtin_prefetch(q + 80);
        }
  }

  double delta_of(uint32_t v) {
    link(v, &link_);
    double sum = 0;
    for (uint32_t u : link_)
      sum += delta(u, v);
    return sum;
  }

  double priority(uint32_t v) {
    link(v, &link_);
    return priority_of_link(v, link_);
  }

  double priority_of_link(uint32_t v, const std::vector<uint32_t>& link) const {
    double sum = 0;
    for (uint32_t u : link)
      sum += delta(u, v);
    if (options_.degree_weight != 0 && !link.empty())
      sum *= std::pow(static_cast<double>(link.size()) / 6.0, options_.degree_weight);
    return sum;
  }

  void push(uint32_t v) { heap_.set(v, priority(v)); }

  // Every present vertex into the heap in index order, as push() would put
  // them, with keys computed side by side: link() shares its marks, so each
  // part lists a link in star order by scanning what it has listed.
  void push_all() {
    const size_t n = input_.positions.size();
    std::vector<double> key(n, 0);
    const size_t parts = scope_.parts(n, kMinVerticesPerPart);
    scope_.for_each_part(parts, [&](size_t p) {
      const IndexRange own = part_range(n, parts, p);
      std::vector<uint32_t> around;
      for (size_t v = own.begin; v < own.end; ++v) {
        if (!state_.present(static_cast<uint32_t>(v))) continue;
        around.clear();
        for (uint32_t t : state_.triangles_of(static_cast<uint32_t>(v)))
          for (uint32_t x : state_.corners(t))
            if (x != v && std::find(around.begin(), around.end(), x) == around.end())
              around.push_back(x);
        key[v] = priority_of_link(static_cast<uint32_t>(v), around);
      }
    });
    for (uint32_t v = 0; v < n; ++v)
      if (state_.present(v)) heap_.set(v, key[v]);
  }

  Vec3d normal(const Triangle& t) const {
    const Vec3d p0 = to_d(input_.positions[t[0]]);
    return cross(sub(to_d(input_.positions[t[1]]), p0), sub(to_d(input_.positions[t[2]]), p0));
  }

  // False when `after` is degenerate or turned too far from `before`.
  bool turn_ok(const Vec3d& before, const Vec3d& after) const {
    const double lb = dot(before, before), la = dot(after, after);
    if (!(lb > 0)) return true;  // a degenerate input triangle has no direction to keep
    if (!(la > 0)) return false;
    return dot(before, after) >= cos_limit_ * std::sqrt(lb * la);
  }

  struct Step {
    uint32_t vertex;
    uint32_t removed_begin, removed_end;
    uint32_t modified_begin, modified_end;
  };

  void undo(uint32_t v) {
    for (size_t i = steps_.size(); i-- > 0;) {
      const Step& s = steps_[i];
      state_.split(s.vertex, v, removed_.data() + s.removed_begin, s.removed_end - s.removed_begin,
                   modified_.data() + s.modified_begin, s.modified_end - s.modified_begin);
    }
    steps_.clear();
  }

  // The fold-over test of the whole merge, without editing the mesh: a
  // triangle with exactly one corner in the closed fan is the one modified
  // by the merge (two or more: removed). Most refused merges fail here, far
  // cheaper than applying and undoing their fine path.
  bool final_turns_ok(uint32_t v) {
    const uint32_t stamp = next_stamp();
    mark_[v] = stamp;
    for (uint32_t u : children_) {
      mark_[u] = stamp;
      state_.prefetch_star(u);  // memory-bound: issue the children's misses together
    }
    for (uint32_t u : children_) {
      for (uint32_t t : state_.triangles_of(u))
        state_.prefetch_corners(t);
      for (uint32_t t : state_.triangles_of(u)) {
        const Triangle& tri = state_.corners(t);
        if ((mark_[tri[0]] == stamp) + (mark_[tri[1]] == stamp) + (mark_[tri[2]] == stamp) != 1)
          continue;
        Triangle moved = tri;
        for (uint32_t& x : moved)
          if (x == u) x = v;
        if (!turn_ok(normal(tri), normal(moved))) return false;
      }
    }
    return true;
  }

  bool try_merge(uint32_t v) {
    link(v, &children_);
    if (children_.empty()) return false;
    if (!final_turns_ok(v)) {
      ++stats_.refused_flip;
      return false;
    }
    order_.clear();
    for (uint32_t u : children_)
      order_.push_back({delta(u, v), u});
    std::sort(order_.begin(), order_.end());
    steps_.clear();
    removed_.clear();
    modified_.clear();
    first_normal_.clear();
    for (const auto& [d, u] : order_) {
      (void)d;
      state_.star(u, &star_);
      Step s{u, static_cast<uint32_t>(removed_.size()), 0, 0, 0};
      for (uint32_t t : star_)
        if (has_corner(state_.corners(t), v)) removed_.push_back(t);
      s.removed_end = static_cast<uint32_t>(removed_.size());
      s.modified_begin = static_cast<uint32_t>(modified_.size());
      step_normals_.clear();
      for (uint32_t t : star_)
        if (!has_corner(state_.corners(t), v)) {
          modified_.push_back(t);
          const Vec3d n = normal(state_.corners(t));
          step_normals_.push_back(n);
          bool seen = false;
          for (const auto& fn : first_normal_)
            seen = seen || fn.first == t;
          if (!seen) first_normal_.push_back({t, n});
        }
      s.modified_end = static_cast<uint32_t>(modified_.size());
      touched_.clear();
      state_.collect_changed(u, v, removed_.data() + s.removed_begin,
                             s.removed_end - s.removed_begin, modified_.data() + s.modified_begin,
                             s.modified_end - s.modified_begin, &touched_);
      state_.collapse(u, v, removed_.data() + s.removed_begin, s.removed_end - s.removed_begin,
                      modified_.data() + s.modified_begin, s.modified_end - s.modified_begin);
      steps_.push_back(s);
      std::sort(touched_.begin(), touched_.end());
      touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
      if (!state_.stars_valid(touched_)) {
        ++stats_.refused_topology;
        undo(v);
        return false;
      }
      for (uint32_t i = s.modified_begin; i < s.modified_end; ++i) {
        const uint32_t t = modified_[i];
        const Vec3d after = normal(state_.corners(t));
        bool ok = turn_ok(step_normals_[i - s.modified_begin], after);
        for (const auto& fn : first_normal_)
          if (fn.first == t) ok = ok && turn_ok(fn.second, after);
        if (!ok) {
          ++stats_.refused_flip;
          undo(v);
          return false;
        }
      }
    }
    record_node(v);
    return true;
  }

  void record_node(uint32_t v) {
    const uint32_t id = static_cast<uint32_t>(h_.node_count());
    h_.children.push_back(node_of_[v]);
    h_.removed_start.push_back(h_.removed_start.back());
    h_.modified_start.push_back(h_.modified_start.back());
    double sum = 0;
    for (const Step& s : steps_) {
      h_.children.push_back(node_of_[s.vertex]);
      h_.removed.insert(h_.removed.end(), removed_.begin() + s.removed_begin,
                        removed_.begin() + s.removed_end);
      h_.modified.insert(h_.modified.end(), modified_.begin() + s.modified_begin,
                         modified_.begin() + s.modified_end);
      h_.removed_start.push_back(static_cast<uint32_t>(h_.removed.size()));
      h_.modified_start.push_back(static_cast<uint32_t>(h_.modified.size()));
      sum += delta(s.vertex, v);
      quadric_[v] += quadric_[s.vertex];
      // Gone from the mesh: dropping it now spares the heap the stale entry
      // (popping and, when dirty, re-keying it). The heap's order is total
      // (priority, index), so which present vertex comes out next does not
      // depend on the entries removed.
      heap_.erase(s.vertex);
      dirty_[s.vertex] = 0;
    }
    h_.child_start.push_back(static_cast<uint32_t>(h_.children.size()));
    h_.error.push_back(static_cast<float>(sum));
    node_of_[v] = id;
    steps_.clear();
  }

  // The new link's errors changed. A vertex still in the heap is re-keyed
  // lazily, when it reaches the top (most are merged into a neighbour's fan
  // before that); one that left the heap (refused or over the error limit)
  // goes back in with its new key, to be tried again.
  void update_after_merge(uint32_t v) {
    link(v, &around_);
    push(v);
    for (uint32_t w : around_) {
      if (heap_.contains(w)) {
        dirty_[w] = 1;
      } else {
        push(w);
      }
    }
  }

  const TriangleMesh& input_;
  const FanBuildOptions& options_;
  const ParallelScope scope_;
  FanMeshState state_;
  FanHierarchy h_;
  FanBuildStats stats_;
  std::vector<Quadric> quadric_;
  std::vector<uint32_t> node_of_;
  // Per-vertex marks for link() and final_turns_ok() (one array for both,
  // so fewer cache lines): a vertex is marked when it holds the current stamp.
  std::vector<uint32_t> mark_;
  uint32_t stamp_ = 0;
  std::vector<uint8_t> dirty_;  // in the heap with a key from an older link
  VertexHeap heap_;
  uint64_t target_ = 0;
  std::optional<double> error_limit_;
  double cos_limit_ = 0;
  // Scratch, kept to avoid allocations per merge.
  std::vector<uint32_t> star_, link_, children_, around_, removed_, modified_, touched_;
  std::vector<std::pair<double, uint32_t>> order_;
  std::vector<Step> steps_;
  std::vector<Vec3d> step_normals_;
  std::vector<std::pair<uint32_t, Vec3d>> first_normal_;
};

}  // namespace

Result<FanBuildResult> build_fan_hierarchy(const TriangleMesh& input,
                                           const FanBuildOptions& options) {
  if (options.target_ratio && !(*options.target_ratio > 0 && *options.target_ratio <= 1))
    return invalid_input("target ratio must be in (0, 1]");
  if (options.max_error && !(*options.max_error >= 0))
    return invalid_input("error limit must be >= 0");
  if (!std::isfinite(options.degree_weight) || !std::isfinite(options.boundary_weight) ||
      !(options.max_normal_change_degrees >= 0 && options.max_normal_change_degrees <= 180))
    return invalid_input(
        "degree and boundary weights must be finite and the normal change in [0, 180] degrees");
  try {
    simplify_internal::MeshTopology topology;
    LODBAKE_RETURN_IF_ERROR(simplify_internal::build_topology(input, &topology));
    // build_topology() bounds the vertices below 2^31; each merge removes at
    // least one vertex, so node ids (leaves + merges) fit in 32 bits.
    FanBuildResult result;
    FanBuilder builder(input, options);
    LODBAKE_RETURN_IF_ERROR(builder.run(topology, &result));
    return result;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while building the fan hierarchy");
  }
}

}  // namespace lodbake
