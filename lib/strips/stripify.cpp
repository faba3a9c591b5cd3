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
std::vector<uint32_t> edge_neighbours(const TriangleMesh& mesh, const std::vector<uint8_t>& live) {
  struct Half {
    uint32_t lo, hi, corner;  // corner = 3 * face + edge
    bool forward;             // lo -> hi is the face's direction
  };
  std::vector<Half> halves;
  halves.reserve(mesh.triangles.size() * 3);
  for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
    if (!live[f]) continue;
    const Triangle& t = mesh.triangles[f];
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = t[e], b = t[(e + 1) % 3];
      halves.push_back({std::min(a, b), std::max(a, b), 3 * f + e, a < b});
    }
  }
  std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.corner < y.corner;
  });
  std::vector<uint32_t> neighbour(mesh.triangles.size() * 3, kNone);
  for (size_t i = 0; i < halves.size();) {
    size_t j = i;
    while (j < halves.size() && halves[j].lo == halves[i].lo && halves[j].hi == halves[i].hi)
      ++j;
    if (j - i == 2 && halves[i].forward != halves[i + 1].forward) {
      neighbour[halves[i].corner] = halves[i + 1].corner / 3;
      neighbour[halves[i + 1].corner] = halves[i].corner / 3;
    }
    i = j;
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
      queue_.push({degree_[f], f});
    }
    while (!queue_.empty()) {
      const auto [degree, f] = queue_.top();
      queue_.pop();
      if (visited_[f] || degree != degree_[f]) continue;  // stale entry
      strip_from(f);
    }
    stats_->strips = out_->strip_count();
    stats_->indices = out_->indices.size();
  }

 private:
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
        queue_.push({degree_[g], g});
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

  using Entry = std::pair<uint32_t, uint32_t>;  // (unvisited neighbours, face)
  const TriangleMesh& mesh_;
  TriangleStrips* out_;
  StripifyStats* stats_;
  std::vector<uint32_t> neighbour_;
  std::vector<uint8_t> visited_;
  std::vector<uint32_t> degree_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue_;
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
