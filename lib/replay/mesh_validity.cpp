#include "lib/replay/mesh_validity.h"

#include <cstdint>

#include "lib/check/mesh_check.h"

namespace lodbake {

std::vector<std::string> triangulation_problems(const TriangleMesh& mesh) {
  std::vector<std::string> problems;
  const MeshCheckReport r = check_mesh(mesh);
  auto add = [&](uint64_t count, const char* what) {
    if (count != 0) problems.push_back(std::to_string(count) + " " + what);
  };
  add(r.out_of_range_triangles, "triangles with an out-of-range index");
  add(r.repeated_index_triangles, "triangles with a repeated index");
  add(r.duplicate_triangles, "duplicate triangles");
  add(r.non_manifold_edges, "edges with more than two faces");
  add(r.inconsistent_orientation_edges,
      "edges walked twice the same way (inconsistent orientation)");
  return problems;
}

}  // namespace lodbake
