// Adjacency and manifold check for the collapse engine. The check is local:
// around vertex v every face contributes its outgoing edge v->next and its
// incoming edge prev->v; a manifold, consistently oriented fan has each
// outgoing and each incoming neighbour at most once, and linking face i to
// the face whose outgoing neighbour is i's incoming one yields one chain
// (boundary vertex) or one cycle (interior vertex). Non-manifold vertices are
// refused rather than split: the engine's link condition assumes single fans,
// and --repair splits them.
#include "lib/simplify/mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace lodbake {
namespace simplify_internal {
namespace {

using FanFace = FanCorner;

// Fans up to this size take the quadratic fast path: almost every vertex of
// a real mesh, and far cheaper than the sorting path for them.
constexpr size_t kSmallFan = 16;
constexpr uint32_t kNone = 0xffffffffu;
// Below this many triangles the fan checks run on one thread.
constexpr size_t kParallelFanCheck = 8192;

// Four vertex ids in one SSE2 register (GCC/Clang vector extensions, which
// fall back to scalar code elsewhere); comparisons give -1 in equal lanes.
using Ids = uint32_t __attribute__((vector_size(16)));
constexpr size_t kLanes = 4;
// Padding of the lanes past the fan: never a vertex id (ids are below 2^31,
// build_topology()), and `next` padding never equals `prev` padding.
constexpr uint32_t kPadNext = 0xffffffffu;
constexpr uint32_t kPadPrev = 0xfffffffeu;

// For each face i of a fan of k <= 4 * R faces: how many faces share its
// next, plus how many share its prev (repeats[i]); the last face whose next
// is i's prev (successor[i], kNone if none); and how many faces have i's
// next as their prev (preds[i]). Face i sits in lane i % 4 of register
// i / 4 and each face j is compared with all of them at once, without
// branches; R is fixed so that the registers stay registers.
template <size_t R>
void compare_fan(const FanFace* fan, size_t k, uint32_t* repeats, uint32_t* successor,
                 uint32_t* preds) {
  // Built in registers: scalar stores read back as one vector would wait
  // for the stores to retire (a failed store forwarding).
  auto next_of = [fan, k](size_t i) { return i < k ? fan[i].next : kPadNext; };
  auto prev_of = [fan, k](size_t i) { return i < k ? fan[i].prev : kPadPrev; };
  Ids nexts[R];
  Ids prevs[R];
  Ids repeat_count[R];
  Ids successor_of[R];
  Ids pred_count[R];
  for (size_t r = 0; r < R; ++r) {
    const size_t i = r * kLanes;
    nexts[r] = Ids{next_of(i), next_of(i + 1), next_of(i + 2), next_of(i + 3)};
    prevs[r] = Ids{prev_of(i), prev_of(i + 1), prev_of(i + 2), prev_of(i + 3)};
    repeat_count[r] = Ids{};
    successor_of[r] = Ids{} + kNone;
    pred_count[r] = Ids{};
  }
  for (size_t j = 0; j < k; ++j) {
    const Ids next = Ids{} + fan[j].next;
    const Ids prev = Ids{} + fan[j].prev;
    const Ids index = Ids{} + static_cast<uint32_t>(j);
    for (size_t r = 0; r < R; ++r) {
      repeat_count[r] -= static_cast<Ids>(nexts[r] == next) + static_cast<Ids>(prevs[r] == prev);
      const Ids is_successor = static_cast<Ids>(prevs[r] == next);
      successor_of[r] = (successor_of[r] & ~is_successor) | (index & is_successor);
      pred_count[r] -= static_cast<Ids>(nexts[r] == prev);
    }
  }
  std::memcpy(repeats, repeat_count, sizeof repeat_count);
  std::memcpy(successor, successor_of, sizeof successor_of);
  std::memcpy(preds, pred_count, sizeof pred_count);
}

// The quadratic check of a small fan: true when no neighbour repeats as
// `next` or as `prev` and the faces form one chain or one cycle, with *open
// set for a chain. False sends the fan to the sorting path, which finds and
// names the problem.
bool small_fan_is_simple(const FanFace* fan, size_t k, bool* open) {
  uint32_t counts[kSmallFan];
  uint32_t successor[kSmallFan];
  uint32_t preds[kSmallFan];
  if (k <= 2 * kLanes) {
    compare_fan<2>(fan, k, counts, successor, preds);
  } else {
    compare_fan<kSmallFan / kLanes>(fan, k, counts, successor, preds);
  }
  uint32_t repeats = 0;
  for (size_t i = 0; i < k; ++i)
    repeats += counts[i];
  // Each face matches itself twice.
  if (repeats != 2 * k) return false;
  uint32_t start = 0;
  size_t chain_starts = 0;
  for (size_t i = 0; i < k; ++i) {
    if (preds[i] == 0) {
      ++chain_starts;
      start = static_cast<uint32_t>(i);
    }
  }
  if (chain_starts > 1) return false;
  size_t walked = 1;
  for (uint32_t j = successor[start]; j != kNone && j != start; j = successor[j]) {
    if (++walked > k) return false;
  }
  *open = chain_starts == 1;
  return walked == k;
}

// The fans of vertices [begin, end): each must be one chain or one cycle.
// Sets topology->boundary of those vertices; fails at the first bad one.
Status check_fans(MeshTopology* topology, size_t begin, size_t end) {
  const std::vector<uint32_t>& start = topology->face_start;
  std::vector<uint32_t> by_next;
  std::vector<uint8_t> visited;
  std::vector<uint32_t> prevs;
  std::vector<uint8_t> has_pred;
  for (size_t v = begin; v < end; ++v) {
    const FanFace* fan = &topology->corners[start[v]];
    const size_t k = start[v + 1] - start[v];
    if (k == 0) continue;
    bool simple_open = false;
    if (k <= kSmallFan && small_fan_is_simple(fan, k, &simple_open)) {
      topology->boundary[v] = simple_open ? 1 : 0;
      continue;
    }
    by_next.resize(k);
    for (size_t i = 0; i < k; ++i)
      by_next[i] = static_cast<uint32_t>(i);
    std::sort(by_next.begin(), by_next.end(),
              [&](uint32_t a, uint32_t b) { return fan[a].next < fan[b].next; });
    prevs.resize(k);
    for (size_t i = 0; i < k; ++i)
      prevs[i] = fan[i].prev;
    std::sort(prevs.begin(), prevs.end());
    for (size_t i = 1; i < k; ++i) {
      const uint32_t a = fan[by_next[i - 1]].next;
      const uint32_t b = fan[by_next[i]].next;
      if (a == b || prevs[i - 1] == prevs[i]) {
        const uint32_t w = a == b ? a : prevs[i];
        // Three or more faces on v-w, or two faces walking it the same way.
        const size_t uses = std::count_if(
            fan, fan + k, [&](const FanFace& f) { return f.next == w || f.prev == w; });
        if (uses > 2) {
          return invalid_input("edge " + std::to_string(std::min<size_t>(v, w)) + "-" +
                               std::to_string(std::max<size_t>(v, w)) + " has " +
                               std::to_string(uses) + " faces (non-manifold edge)");
        }
        return invalid_input("edge " + std::to_string(std::min<size_t>(v, w)) + "-" +
                             std::to_string(std::max<size_t>(v, w)) +
                             " is walked the same way by two faces (inconsistent orientation "
                             "or duplicate triangle; use --repair to fix)");
      }
    }
    // Face i continues into the face whose `next` is i's `prev` (rotating
    // around v). Count chains and cycles.
    auto successor = [&](size_t i) -> int64_t {
      const uint32_t want = fan[i].prev;
      auto it = std::lower_bound(by_next.begin(), by_next.end(), want,
                                 [&](uint32_t a, uint32_t value) { return fan[a].next < value; });
      if (it == by_next.end() || fan[*it].next != want) return -1;
      return *it;
    };
    has_pred.assign(k, 0);
    for (size_t i = 0; i < k; ++i) {
      const int64_t s = successor(i);
      if (s >= 0) has_pred[static_cast<size_t>(s)] = 1;
    }
    visited.assign(k, 0);
    size_t fans = 0;
    bool open = false;
    for (int pass = 0; pass < 2; ++pass) {
      for (size_t i = 0; i < k; ++i) {
        if (visited[i] || (pass == 0 && has_pred[i])) continue;
        if (pass == 0) open = true;
        ++fans;
        for (int64_t j = static_cast<int64_t>(i); j >= 0 && !visited[static_cast<size_t>(j)];
             j = successor(static_cast<size_t>(j))) {
          visited[static_cast<size_t>(j)] = 1;
        }
      }
    }
    if (fans > 1) {
      return invalid_input("vertex " + std::to_string(v) + ": its faces form " +
                           std::to_string(fans) +
                           " separate fans (non-manifold vertex; use --repair to fix)");
    }
    topology->boundary[v] = open ? 1 : 0;
  }
  return Status::ok();
}

}  // namespace

Status build_topology(const TriangleMesh& mesh, MeshTopology* topology, bool with_faces,
                      const ParallelScope* threads) {
  const size_t n = mesh.positions.size();
  const size_t m = mesh.triangles.size();
  if (n >= (size_t{1} << 31) || m >= (size_t{1} << 30)) {
    return unsupported("mesh too large for the collapse engine (" + std::to_string(n) +
                       " vertices, " + std::to_string(m) + " triangles)");
  }
  for (size_t v = 0; v < n; ++v) {
    const Vec3f& p = mesh.positions[v];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return invalid_input("vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  }
  std::vector<uint32_t>& start = topology->face_start;
  start.assign(n + 1, 0);
  for (size_t t = 0; t < m; ++t) {
    const Triangle& tri = mesh.triangles[t];
    for (uint32_t v : tri) {
      if (v >= n) {
        return invalid_input("triangle " + std::to_string(t) + ": vertex index " +
                             std::to_string(v) + " out of range (" + std::to_string(n) +
                             " vertices)");
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      return invalid_input("triangle " + std::to_string(t) +
                           " repeats a vertex (use --repair to fix)");
    }
    for (uint32_t v : tri)
      ++start[v + 1];
  }
  for (size_t v = 0; v < n; ++v)
    start[v + 1] += start[v];
  topology->faces.resize(with_faces ? 3 * m : 0);
  topology->corners.resize(3 * m);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t < m; ++t) {
      const Triangle& tri = mesh.triangles[t];
      for (int k = 0; k < 3; ++k) {
        const uint32_t slot = fill[tri[k]]++;
        if (with_faces) topology->faces[slot] = static_cast<uint32_t>(t);
        topology->corners[slot] = {tri[(k + 1) % 3], tri[(k + 2) % 3]};
      }
    }
  }
  topology->boundary.assign(n, 0);

  // The fan checks are independent per vertex: in parts, ranges of the
  // vertices; the first failed part's error is the first in vertex order.
  const size_t parts = threads ? threads->parts(m, kParallelFanCheck / 2) : 1;
  std::vector<Status> part_status(parts);
  auto check_part = [&](size_t part) {
    const IndexRange range = part_range(n, parts, part);
    part_status[part] = check_fans(topology, range.begin, range.end);
  };
  if (threads) {
    threads->for_each_part(parts, check_part);
  } else {
    check_part(0);
  }
  for (const Status& status : part_status) {
    if (!status.is_ok()) return status;
  }
  return Status::ok();
}

}  // namespace simplify_internal
}  // namespace lodbake
