#include "lib/fanmerge/fan_wedges.h"

#include <new>
#include <string>
#include <utility>

#include "formats/mesh/progressive_mesh.h"
#include "formats/sections/fanh.h"
#include "formats/sections/wedg.h"

namespace lodbake {
namespace {

std::string str(uint64_t x) {
  return std::to_string(x);
}

int corner_at(const Triangle& t, uint32_t v) {
  return t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : -1;
}

struct Move {
  uint32_t corner, vertex, wedge;
};

}  // namespace

Result<FanWedges> FanWedges::create(const TriangleMesh& input, const FanHierarchy& h,
                                    const PmWedges& wedges) {
  if (std::vector<std::string> f = validate_fanh_structure(h); !f.empty())
    return invalid_input("fan hierarchy: " + f.front());
  if (input.vertex_count() != h.vertex_count || input.triangle_count() != h.triangle_count)
    return invalid_input("fan hierarchy over " + str(h.vertex_count) + " vertices and " +
                         str(h.triangle_count) + " triangles, mesh with " +
                         str(input.vertex_count()) + " and " + str(input.triangle_count()));
  if (std::vector<std::string> f = validate_wedg_corners(wedges, input); !f.empty())
    return invalid_input(f.front());
  try {
    const size_t triangles = input.triangles.size();
    std::vector<Triangle> at = input.triangles;
    std::vector<std::array<uint32_t, 3>> wedge = wedges.base;
    std::vector<uint8_t> alive(triangles, 1);
    std::vector<uint32_t> vertex(h.node_count());
    for (uint32_t v = 0; v < h.vertex_count; ++v)
      vertex[v] = v;
    std::vector<Move> moves;
    std::vector<std::pair<uint32_t, uint32_t>> partner;  // (wedge at u, wedge at v)
    for (size_t i = 0; i < h.internal_count(); ++i) {
      const uint32_t b = h.child_start[i], e = h.child_start[i + 1];
      const uint32_t v = vertex[h.children[b]];
      vertex[h.vertex_count + i] = v;
      for (uint32_t j = b + 1; j < e; ++j) {
        const uint32_t u = vertex[h.children[j]];
        auto refuse = [&](uint32_t t) {
          return invalid_input("fan hierarchy: node " + str(h.vertex_count + i) + " child " +
                               str(j - b) + " does not replay over the mesh at triangle " + str(t));
        };
        partner.clear();
        for (uint32_t r = h.removed_start[j]; r < h.removed_start[j + 1]; ++r) {
          const uint32_t t = h.removed[r];
          const int ku = corner_at(at[t], u), kv = corner_at(at[t], v);
          if (!alive[t] || ku < 0 || kv < 0) return refuse(t);
          alive[t] = 0;
          partner.emplace_back(wedge[t][ku], wedge[t][kv]);
        }
        for (uint32_t m = h.modified_start[j]; m < h.modified_start[j + 1]; ++m) {
          const uint32_t t = h.modified[m];
          const int ku = corner_at(at[t], u);
          if (!alive[t] || ku < 0 || corner_at(at[t], v) >= 0) return refuse(t);
          uint32_t& w = wedge[t][ku];
          for (const auto& [at_u, at_v] : partner) {
            if (at_u == w) {
              w = at_v;
              break;
            }
          }
          at[t][ku] = v;
          moves.push_back({static_cast<uint32_t>(3 * t + ku), v, w});
        }
      }
    }
    FanWedges out;
    out.triangle_count_ = static_cast<uint32_t>(triangles);
    out.start_.assign(3 * triangles + 1, 0);
    for (size_t c = 0; c < 3 * triangles; ++c)
      out.start_[c + 1] = 1;
    for (const Move& m : moves)
      ++out.start_[m.corner + 1];
    for (size_t c = 0; c < 3 * triangles; ++c)
      out.start_[c + 1] += out.start_[c];
    out.chain_.resize(out.start_.back());
    std::vector<uint32_t> fill(out.start_.begin(), out.start_.end() - 1);
    for (size_t t = 0; t < triangles; ++t)
      for (int k = 0; k < 3; ++k)
        out.chain_[fill[3 * t + k]++] = {input.triangles[t][k], wedges.base[t][k]};
    for (const Move& m : moves)
      out.chain_[fill[m.corner]++] = {m.vertex, m.wedge};
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory following the fan hierarchy's wedges");
  }
}

uint32_t FanWedges::wedge(uint32_t t, int k, uint32_t vertex) const {
  if (t >= triangle_count_ || k < 0 || k > 2) return kNoVertex;
  const size_t c = 3 * size_t{t} + k;
  for (uint32_t i = start_[c]; i < start_[c + 1]; ++i)
    if (chain_[i][0] == vertex) return chain_[i][1];
  return kNoVertex;
}

Result<std::vector<std::array<uint32_t, 3>>> FanWedges::corners(const FanRuntime& runtime) const {
  if (runtime.input_triangle_count() != triangle_count_)
    return invalid_input("the fan runtime has " + str(runtime.input_triangle_count()) +
                         " input triangles, the wedges " + str(triangle_count_));
  try {
    std::vector<std::array<uint32_t, 3>> out;
    out.reserve(runtime.triangle_count());
    for (uint32_t t = 0; t < triangle_count_; ++t) {
      if (!runtime.alive(t)) continue;
      const Triangle& c = runtime.corners(t);
      std::array<uint32_t, 3> w;
      for (int k = 0; k < 3; ++k) {
        w[k] = wedge(t, k, c[k]);
        if (w[k] == kNoVertex)
          return invalid_input("triangle " + str(t) + "'s corner at vertex " + str(c[k]) +
                               " has no wedge there");
      }
      out.push_back(w);
    }
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory listing the fan front's wedges");
  }
}

}  // namespace lodbake
