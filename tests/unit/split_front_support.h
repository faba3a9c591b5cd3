// Shared by the DAG and vertex-tree tests: recording a PM (greedy, or the
// balanced hierarchy's), an independent
// replay of any subset of a PM's splits (in split order, with the walk
// progressive_mesh.h documents), triangle-set comparison and the invariants
// every selectively refined mesh must keep.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "formats/mesh/progressive_mesh.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/simplify/simplify.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace front_test {

inline ProgressiveMesh record_half_pm(const std::string& file) {
  TriangleMesh input = load_clean_mesh(file);
  input.normals = MeshAttribute();
  input.texcoords = MeshAttribute();
  SimplifyOptions options;
  options.record_pm = true;
  options.placement = Placement::kHalf;
  Result<SimplifyResult> result = simplify(input, options);
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  if (!result.is_ok()) return ProgressiveMesh();
  return *std::move(result).value().pm;
}

/// The progressive mesh of `file`'s balanced vertex hierarchy
/// (hierarchy_to_progressive_mesh); the hierarchy and each split's node in
/// *h and *node_of_split when not null.
inline ProgressiveMesh balanced_pm(const std::string& file, VertexHierarchy* h = nullptr,
                                   std::vector<uint32_t>* node_of_split = nullptr) {
  TriangleMesh input = load_clean_mesh(file);
  input.normals = MeshAttribute();
  input.texcoords = MeshAttribute();
  Result<BalancedHierarchy> built = build_balanced_hierarchy(input, BalancedBuildOptions());
  EXPECT_TRUE(built.is_ok()) << built.status().message();
  if (!built.is_ok()) return ProgressiveMesh();
  Result<ProgressiveMesh> pm =
      hierarchy_to_progressive_mesh(built.value().hierarchy, node_of_split);
  EXPECT_TRUE(pm.is_ok()) << pm.status().message();
  if (!pm.is_ok()) return ProgressiveMesh();
  if (h != nullptr) *h = std::move(built).value().hierarchy;
  return std::move(pm).value();
}

/// Test parameters name a shared mesh; "balanced:" in front asks for the
/// balanced hierarchy's PM instead of the greedy one lodbake-simplify records.
inline constexpr char kBalanced[] = "balanced:";
inline std::string mesh_file(const std::string& param) {
  return param.rfind(kBalanced, 0) == 0 ? param.substr(sizeof(kBalanced) - 1) : param;
}
inline ProgressiveMesh test_pm(const std::string& param) {
  return param.rfind(kBalanced, 0) == 0 ? balanced_pm(mesh_file(param)) : record_half_pm(param);
}

/// The triangle rotated so its smallest index comes first (orientation kept).
inline Triangle canonical(Triangle t) {
  while (t[0] > t[1] || t[0] > t[2])
    t = {t[1], t[2], t[0]};
  return t;
}

inline std::vector<Triangle> sorted_canonical(const std::vector<Triangle>& tris) {
  std::vector<Triangle> out;
  out.reserve(tris.size());
  for (const Triangle& t : tris)
    out.push_back(canonical(t));
  std::sort(out.begin(), out.end());
  return out;
}

/// Empty when `tris` is edge-manifold and consistently oriented (no directed
/// edge twice), has no degenerate and no duplicate triangle (any
/// orientation); else what is wrong first.
inline std::string mesh_problem(const std::vector<Triangle>& tris) {
  std::set<std::pair<uint32_t, uint32_t>> half_edges;
  std::set<Triangle> unordered;
  for (const Triangle& t : tris) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return "degenerate triangle";
    Triangle s = t;
    std::sort(s.begin(), s.end());
    if (!unordered.insert(s).second) return "duplicate triangle";
    for (int c = 0; c < 3; ++c) {
      if (!half_edges.insert({t[c], t[(c + 1) % 3]}).second) {
        return "directed edge " + std::to_string(t[c]) + "->" + std::to_string(t[(c + 1) % 3]) +
               " twice (non-manifold or inconsistent orientation)";
      }
    }
  }
  return "";
}

/// Empty when every vertex of `tris` exists on the front `applied` (a base
/// vertex, or the vertex B + i of an applied split i); else the first one
/// that does not.
inline std::string missing_vertex(const std::vector<Triangle>& tris,
                                  const std::vector<uint8_t>& applied, uint32_t base_vertices) {
  for (const Triangle& t : tris) {
    for (uint32_t v : t) {
      if (v >= base_vertices &&
          (v - base_vertices >= applied.size() || !applied[v - base_vertices])) {
        return "vertex " + std::to_string(v) + " is used but its split is not applied";
      }
    }
  }
  return "";
}

/// Applies the splits i with `applied[i]` to the base mesh in split order;
/// split i creates vertex B + i. Same walk as PmRefiner; a failed walk
/// (wing not adjacent, fan not found) is a test failure.
inline std::vector<Triangle> replay_subset(const ProgressiveMesh& pm,
                                           const std::vector<uint8_t>& applied) {
  std::vector<Triangle> faces = pm.base.triangles;
  const uint32_t n0 = static_cast<uint32_t>(pm.base.vertex_count());
  std::vector<std::vector<uint32_t>> of(pm.full_vertex_count());
  for (uint32_t f = 0; f < faces.size(); ++f)
    for (uint32_t v : faces[f])
      of[v].push_back(f);
  auto corner = [](const Triangle& t, uint32_t v) { return t[0] == v ? 0 : (t[1] == v ? 1 : 2); };
  auto with_next = [&](uint32_t v, uint32_t next) {
    for (uint32_t f : of[v])
      if (faces[f][(corner(faces[f], v) + 1) % 3] == next) return f;
    return kNoVertex;
  };
  auto with_prev = [&](uint32_t v, uint32_t prev) {
    for (uint32_t f : of[v])
      if (faces[f][(corner(faces[f], v) + 2) % 3] == prev) return f;
    return kNoVertex;
  };
  for (uint32_t i = 0; i < pm.splits.size(); ++i) {
    if (!applied[i]) continue;
    const VertexSplit& s = pm.splits[i];
    const uint32_t vt = n0 + i;
    // The split needs vs and its wings to exist and the wings to be
    // adjacent to vs (PmRefiner's checks).
    for (uint32_t v : {s.vs, s.vl, s.vr}) {
      if (v != kNoVertex && v >= n0 && !applied[v - n0]) {
        ADD_FAILURE() << "split " << i << " needs vertex " << v << ", whose split is not applied";
        return {};
      }
    }
    for (uint32_t w : {s.vl, s.vr}) {
      if (w != kNoVertex && with_next(s.vs, w) == kNoVertex && with_prev(s.vs, w) == kNoVertex) {
        ADD_FAILURE() << "split " << i << ": wing " << w << " is not adjacent to " << s.vs;
        return {};
      }
    }
    std::vector<uint32_t> moved;
    bool reached = false;
    if (s.vr != kNoVertex) {
      uint32_t next = s.vr;
      for (uint32_t f; (f = with_next(s.vs, next)) != kNoVertex;) {
        if (moved.size() > of[s.vs].size()) {
          ADD_FAILURE() << "split " << i << ": fan does not end";
          return {};
        }
        moved.push_back(f);
        next = faces[f][(corner(faces[f], s.vs) + 2) % 3];
        if (next == s.vl) {
          reached = true;
          break;
        }
      }
    }
    if (s.vl != kNoVertex && !reached) {
      uint32_t prev = s.vl;
      for (uint32_t f; (f = with_prev(s.vs, prev)) != kNoVertex;) {
        if (moved.size() > of[s.vs].size()) {
          ADD_FAILURE() << "split " << i << ": fan does not end";
          return {};
        }
        moved.push_back(f);
        prev = faces[f][(corner(faces[f], s.vs) + 1) % 3];
      }
    }
    for (uint32_t f : moved) {
      faces[f][corner(faces[f], s.vs)] = vt;
      of[s.vs].erase(std::find(of[s.vs].begin(), of[s.vs].end(), f));
      of[vt].push_back(f);
    }
    auto add = [&](const Triangle& t) {
      for (uint32_t v : t)
        of[v].push_back(static_cast<uint32_t>(faces.size()));
      faces.push_back(t);
    };
    if (s.vl != kNoVertex) add({s.vs, vt, s.vl});
    if (s.vr != kNoVertex) add({vt, s.vs, s.vr});
  }
  return faces;
}

}  // namespace front_test
}  // namespace lodbake
