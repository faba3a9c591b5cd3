// Orientation-keeping stripifier, in the spirit of STRIPE (Evans, Skiena,
// Varshney, "Optimizing triangle strips for fast rendering", 1996), which
// the SETS paper uses because it keeps swaps rare.
//
// Choices:
// - Greedy strips grown forward from the unvisited triangle with the fewest
//   unvisited neighbours (SGI's heuristic; ties: lowest triangle index), so
//   strips start at the border of what is left and rarely strand triangles.
//   The first triangle is rotated so that its exit edge leads to the
//   neighbour with the fewest unvisited neighbours.
// - Each step enters the neighbour across the strip's open edge (u, v) and
//   then picks the next open edge: (v, d) without cost, or (u, d) with a
//   swap (u repeated: "u v u d", one extra index). The swap is taken only
//   when the free edge leads nowhere and the swapped one does: swaps only
//   where needed.
// - Neighbours are taken across edges shared by exactly two triangles with
//   opposite directions (consistent orientation); the window parity then
//   gives each triangle its own orientation with no further check.
#include "lib/strips/stripify.h"

#include <algorithm>
#include <array>
#include <functional>
#include <new>
#include <queue>
#include <string>
#include <vector>

namespace lodbake {
namespace {

constexpr uint32_t kNone = 0xFFFFFFFFu;

// neighbour[3 * f + e]: the triangle across edge e = (t[e], t[e+1]) of f.
// Half-edges are bucketed by their lower vertex (a counting sort, which
// keeps corner order), then each short bucket is sorted by the other end.
std::vector<uint32_t> edge_neighbours(const TriangleMesh& mesh, const std::vector<uint8_t>& live) {
  struct Half {
    uint32_t hi, corner;  // corner = 3 * face + edge
    bool forward;         // lo -> hi is the face's direction
  };
  const size_t faces = mesh.triangles.size();
  std::vector<uint32_t> start(mesh.vertex_count() + 1, 0);
  for (uint32_t f = 0; f < faces; ++f) {
    if (!live[f]) continue;
    const Triangle& t = mesh.triangles[f];
    for (uint32_t e = 0; e < 3; ++e)
      ++start[std::min(t[e], t[(e + 1) % 3]) + 1];
  }
  for (size_t v = 0; v + 1 < start.size(); ++v)
    start[v + 1] += start[v];
  std::vector<Half> halves(start.back());
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (uint32_t f = 0; f < faces; ++f) {
    if (!live[f]) continue;
    const Triangle& t = mesh.triangles[f];
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = t[e], b = t[(e + 1) % 3];
      halves[fill[std::min(a, b)]++] = {std::max(a, b), 3 * f + e, a < b};
    }
  }
  std::vector<uint32_t> neighbour(faces * 3, kNone);
  for (size_t v = 0; v + 1 < start.size(); ++v) {
    Half* const begin = halves.data() + start[v];
    Half* const end = halves.data() + start[v + 1];
    std::sort(begin, end, [](const Half& x, const Half& y) {
      return x.hi != y.hi ? x.hi < y.hi : x.corner < y.corner;
    });
    for (Half* i = begin; i < end;) {
      Half* j = i;
      while (j < end && j->hi == i->hi)
        ++j;
      if (j - i == 2 && i[0].forward != i[1].forward) {
        neighbour[i[0].corner] = i[1].corner / 3;
        neighbour[i[1].corner] = i[0].corner / 3;
      }
      i = j;
    }
  }
  return neighbour;
}

class Stripifier {
 public:
  Stripifier(const TriangleMesh& mesh, TriangleStrips* out, StripifyStats* stats)
      : mesh_(mesh), out_(out), stats_(stats) {}

  void run() {
    const size_t faces = mesh_.triangles.size();
    std::vector<uint8_t> live(faces, 0);
    for (size_t f = 0; f < faces; ++f) {
      const Triangle& t = mesh_.triangles[f];
      live[f] = is_real_triangle(t[0], t[1], t[2]);
      if (live[f]) {
        ++stats_->triangles;
      } else {
        ++stats_->skipped_degenerate;
      }
    }
    neighbour_ = edge_neighbours(mesh_, live);
    visited_.assign(faces, 0);
    degree_.assign(faces, 0);
    for (uint32_t f = 0; f < faces; ++f) {
      if (!live[f]) {
        visited_[f] = 1;
        continue;
      }
      for (int e = 0; e < 3; ++e)
        degree_[f] += neighbour_[3 * f + e] != kNone;
    }
    for (uint32_t f = next_start(); f != kNone; f = next_start())
      strip_from(f);
    stats_->strips = out_->strip_count();
    stats_->indices = out_->indices.size();
  }

 private:
  // The unvisited triangle with the fewest unvisited neighbours, ties to the
  // lowest index (kNone when none is left). Degrees only fall, so for each
  // degree a cursor walking up the indices finds the triangles that had it
  // from the start (or got it before the cursor passed), and a heap holds
  // those lowered to it behind the cursor; stale entries are skipped.
  uint32_t next_start() {
    const uint32_t faces = static_cast<uint32_t>(degree_.size());
    for (uint32_t d = 0; d < 4; ++d) {
      uint32_t& c = cursor_[d];
      while (c < faces && (visited_[c] || degree_[c] != d))
        ++c;
      auto& heap = lowered_[d];
      while (!heap.empty() && (visited_[heap.top()] || degree_[heap.top()] != d))
        heap.pop();
      const uint32_t lowered = heap.empty() ? kNone : heap.top();
      const uint32_t first = c < faces ? c : kNone;
      if (first != kNone || lowered != kNone) return std::min(first, lowered);
    }
    return kNone;
  }

  uint32_t across(uint32_t f, uint32_t a, uint32_t b) const {
    const Triangle& t = mesh_.triangles[f];
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t x = t[e], y = t[(e + 1) % 3];
      if ((x == a && y == b) || (x == b && y == a)) return neighbour_[3 * f + e];
    }
    return kNone;
  }
  bool open(uint32_t f) const { return f != kNone && !visited_[f]; }

  void visit(uint32_t f) {
    visited_[f] = 1;
    for (int e = 0; e < 3; ++e) {
      const uint32_t g = neighbour_[3 * f + e];
      if (g != kNone && !visited_[g]) {
        --degree_[g];
        lowered_[degree_[g]].push(g);
      }
    }
  }

  void emit(uint32_t v) { out_->indices.push_back(v); }

  void strip_from(uint32_t f) {
    const Triangle& t = mesh_.triangles[f];
    // Rotation r starts the strip (t[r], t[r+1], t[r+2]); its exit edge is
    // edge (r + 1) % 3 of the triangle.
    int best = 0;
    uint32_t best_degree = 4;
    for (int r = 0; r < 3; ++r) {
      const uint32_t g = neighbour_[3 * f + (r + 1) % 3];
      if (open(g) && degree_[g] < best_degree) {
        best_degree = degree_[g];
        best = r;
      }
    }
    visit(f);
    uint32_t u = t[(best + 1) % 3], v = t[(best + 2) % 3];
    emit(t[best]);
    emit(u);
    emit(v);
    uint32_t current = f;
    for (;;) {
      const uint32_t next = across(current, u, v);
      if (!open(next)) break;
      visit(next);
      const Triangle& n = mesh_.triangles[next];
      uint32_t d = n[0];
      for (uint32_t x : n)
        if (x != u && x != v) d = x;
      if (!open(across(next, v, d)) && open(across(next, u, d))) {
        emit(u);  // swap: the open edge becomes (u, d)
        emit(d);
        ++stats_->swaps;
        v = d;
      } else {
        emit(d);
        u = v;
        v = d;
      }
      current = next;
    }
    out_->first.push_back(static_cast<uint32_t>(out_->indices.size()));
  }

  const TriangleMesh& mesh_;
  TriangleStrips* out_;
  StripifyStats* stats_;
  std::vector<uint32_t> neighbour_;
  std::vector<uint8_t> visited_;
  std::vector<uint32_t> degree_;
  std::array<uint32_t, 4> cursor_{};  // per degree (unvisited neighbours)
  std::array<std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<uint32_t>>, 4>
      lowered_;
};

}  // namespace

Result<TriangleStrips> stripify(const TriangleMesh& mesh, StripifyStats* stats) {
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (uint32_t v : mesh.triangles[f])
      if (v >= mesh.vertex_count())
        return invalid_input("triangle " + std::to_string(f) + " has vertex " + std::to_string(v) +
                             ", out of range (" + std::to_string(mesh.vertex_count()) +
                             " vertices)");
  if (mesh.vertex_count() > UINT32_MAX || mesh.triangles.size() * 5 > UINT32_MAX)
    return invalid_input("mesh too large for 32-bit strip indices");
  try {
    StripifyStats local;
    TriangleStrips strips;
    strips.vertex_count = static_cast<uint32_t>(mesh.vertex_count());
    strips.indices.reserve(mesh.triangles.size() * 2);
    Stripifier(mesh, &strips, &local).run();
    if (stats != nullptr) *stats = local;
    return strips;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory building triangle strips");
  }
}

}  // namespace lodbake
