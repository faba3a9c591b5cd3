// Shared by the mode vtrees tests (vtrees_stream_test.cpp,
// vtrees_net_test.cpp): a balanced hierarchy with its refinement data, its
// progressive mesh, vertex trees and server database built from a test
// mesh, and the tolerance-0 view that asks for every split.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/replay/vtrees_server.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "simplify_test_meshes.h"
#include "tests/unit/test_meshes.h"

namespace lodbake::vtrees_test {

struct Built {
  TriangleMesh input;
  VertexHierarchy h;
  std::vector<NodeRefinement> data;
  ProgressiveMesh pm;
  VertexTrees trees;
  std::unique_ptr<VtreesDatabase> db;
};

inline std::unique_ptr<Built> build(TriangleMesh input) {
  auto b = std::make_unique<Built>();
  b->input = std::move(input);
  b->input.normals = MeshAttribute();
  b->input.texcoords = MeshAttribute();
  Result<BalancedHierarchy> built = build_balanced_hierarchy(b->input, BalancedBuildOptions());
  EXPECT_TRUE(built.is_ok()) << built.status().message();
  if (!built.is_ok()) return b;
  b->h = std::move(built).value().hierarchy;
  Result<std::vector<NodeRefinement>> data = compute_refinement_data(b->h, b->input);
  EXPECT_TRUE(data.is_ok()) << data.status().message();
  if (data.is_ok()) b->data = std::move(data).value();
  Result<ProgressiveMesh> pm = hierarchy_to_progressive_mesh(b->h);
  EXPECT_TRUE(pm.is_ok()) << pm.status().message();
  if (!pm.is_ok()) return b;
  b->pm = std::move(pm).value();
  Result<VertexTrees> trees = build_vertex_trees(b->pm);
  EXPECT_TRUE(trees.is_ok()) << trees.status().message();
  if (!trees.is_ok()) return b;
  b->trees = std::move(trees).value();
  Result<VtreesDatabase> db = VtreesDatabase::create(b->trees, b->h, b->data);
  EXPECT_TRUE(db.is_ok()) << db.status().message();
  if (db.is_ok()) b->db = std::make_unique<VtreesDatabase>(std::move(db).value());
  return b;
}

inline std::unique_ptr<Built> build_mesh(const std::string& name) {
  if (name == "torus") return build(test_meshes::torus(24, 16));
  return build(load_clean_mesh(name));
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

}  // namespace lodbake::vtrees_test
