// Loading the shared meshes the simplifier tests run on: imported through
// the tools' ingest path with the engine's policy (no non-manifold vertex,
// consistent orientation, no degenerate or duplicate triangle) and the
// unreferenced vertices dropped.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <utility>

#include "formats/mesh/triangle_mesh.h"
#include "lib/ingest/load_mesh.h"

namespace lodbake {

inline std::string shared_mesh_path(const std::string& file) {
  const char* root = std::getenv("LODBAKE_SHARED_DATA");
  // CTest sets LODBAKE_SHARED_DATA; without it the load fails naming the path.
  return std::string(root ? root : "LODBAKE_SHARED_DATA-not-set") + "/meshes/" + file;
}

inline LoadOptions clean_mesh_options() {
  LoadOptions options;
  options.drop_unreferenced = true;
  options.policy = UsePolicy::two_manifold();
  options.strict = true;  // a mesh the tools would repair fails the test instead
  return options;
}

/// Loads a clean shared mesh; fails the test when it cannot.
inline TriangleMesh load_clean_mesh(const std::string& file) {
  LoadedMesh loaded;
  const Status status = load_mesh(shared_mesh_path(file), clean_mesh_options(), &loaded);
  EXPECT_TRUE(status.is_ok()) << file << ": " << status.message();
  return loaded.mesh;
}

// The value of `result`, or T{} after failing the test.
template <typename T>
T take(Result<T> result, const char* what) {
  EXPECT_TRUE(result.is_ok()) << what << ": " << result.status().message();
  return result.is_ok() ? std::move(result).value() : T{};
}

// cgal_elephant.off without its normals and texture coordinates: the
// small shared mesh (2775 vertices) the section tests bake containers from.
inline const TriangleMesh& bare_elephant() {
  static const TriangleMesh mesh = [] {
    TriangleMesh m = load_clean_mesh("cgal_elephant.off");
    m.normals = MeshAttribute();
    m.texcoords = MeshAttribute();
    return m;
  }();
  return mesh;
}

}  // namespace lodbake
