// Shared by the mode stream tests (stream_test.cpp, stream_net_test.cpp): a
// balanced hierarchy with its refinement data built from a test mesh, the
// tolerance-0 view that asks for every split, and the check that a client
// holds exactly the input mesh.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "formats/sections/vhie.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/vhier_replay.h"
#include "simplify_test_meshes.h"
#include "tests/unit/test_meshes.h"

namespace lodbake::stream_test {

struct Built {
  TriangleMesh input;
  VertexHierarchy h;
  std::vector<NodeRefinement> data;
};

inline Built build(TriangleMesh input) {
  Built b;
  b.input = std::move(input);
  b.input.normals = MeshAttribute();
  b.input.texcoords = MeshAttribute();
  Result<BalancedHierarchy> built = build_balanced_hierarchy(b.input, BalancedBuildOptions());
  EXPECT_TRUE(built.is_ok()) << built.status().message();
  if (!built.is_ok()) return b;
  b.h = std::move(built).value().hierarchy;
  Result<std::vector<NodeRefinement>> data = compute_refinement_data(b.h, b.input);
  EXPECT_TRUE(data.is_ok()) << data.status().message();
  if (data.is_ok()) b.data = std::move(data).value();
  return b;
}

inline Built build_mesh(const std::string& name) {
  if (name == "torus") return build(test_meshes::torus(24, 16));
  return build(load_clean_mesh(name));
}

inline Triangle canonical(const Triangle& t) {
  const int k = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
  return {t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
}

inline std::vector<Triangle> sorted_canonical(std::vector<Triangle> tris) {
  for (Triangle& t : tris)
    t = canonical(t);
  std::sort(tris.begin(), tris.end());
  return tris;
}

// node index of every id of the complete hierarchy
inline std::map<HierarchyNodeId, uint32_t> id_map(const StreamHierarchy& db) {
  std::map<HierarchyNodeId, uint32_t> m;
  for (uint32_t i = 0; i < db.ids.size(); ++i)
    m[db.ids[i]] = i;
  return m;
}

inline ViewRequest refine_everything(const Built& b) {
  const BoundingSphere sphere = bounding_sphere(b.h.position);
  CameraFrame f;
  f.eye = {sphere.center[0], sphere.center[1], sphere.center[2] + 3 * sphere.radius};
  f.target = sphere.center;
  ViewRequest r = view_request_for(f, Viewport(), 0.01f * sphere.radius, 0);
  EXPECT_EQ(r.tolerance, 0.0f);
  return r;
}

/// Empty when the client's mesh, in input vertex ids, is the input mesh
/// (same oriented triangles, same positions) and a valid one; else what
/// differs. Callable from any thread.
inline std::string input_mesh_problem(const StreamClient& c, const StreamHierarchy& db,
                                      const Built& b) {
  const std::map<HierarchyNodeId, uint32_t> ids = id_map(db);
  if (c.refiner().front_size() != b.input.positions.size()) {
    return "front of " + std::to_string(c.refiner().front_size()) + " vertices, the input has " +
           std::to_string(b.input.positions.size());
  }
  std::vector<Triangle> tris;
  for (const Triangle& t : c.refiner().triangles()) {
    Triangle u;
    for (int k = 0; k < 3; ++k) {
      auto it = ids.find(c.id_of(t[k]));
      if (it == ids.end() || !b.h.is_leaf(it->second)) return "a front vertex is not a leaf";
      u[k] = b.h.input_vertex[it->second];
      if (!(c.partial().position[t[k]] == b.input.positions[u[k]])) return "a position differs";
    }
    tris.push_back(u);
  }
  if (sorted_canonical(tris) != sorted_canonical(b.input.triangles)) return "triangles differ";
  const std::vector<std::string> problems = check_vhier_mesh(c.refiner());
  return problems.empty() ? std::string() : problems.front();
}

/// Empty when every split of the complete hierarchy was received exactly
/// once by the client; else the first node that was not.
inline std::string every_split_once(const StreamClient& c, const StreamHierarchy& db) {
  const std::map<HierarchyNodeId, uint32_t> ids = id_map(db);
  std::vector<int> count(db.h->node_count(), 0);
  for (const HierarchyNodeId& id : c.received()) {
    auto it = ids.find(id);
    if (it == ids.end()) return "received a split of no node";
    ++count[it->second];
  }
  for (uint32_t i = 0; i < db.h->node_count(); ++i) {
    if (count[i] != (db.h->is_leaf(i) ? 0 : 1)) {
      return "node " + std::to_string(i) + " received " + std::to_string(count[i]) + " times";
    }
  }
  return std::string();
}

}  // namespace lodbake::stream_test
