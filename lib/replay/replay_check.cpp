#include "lib/replay/replay_check.h"

#include "formats/mesh/canonical_triangles.h"

namespace lodbake {

std::vector<std::string> triangulation_problems(const MeshCheckReport& r) {
  std::vector<std::string> problems;
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

std::vector<std::string> triangulation_problems(const TriangleMesh& mesh) {
  return triangulation_problems(check_triangulation(mesh));
}

std::vector<Triangle> sorted_canonical(std::vector<Triangle> triangles) {
  sort_canonical_triangles(&triangles);
  return triangles;
}

}  // namespace lodbake
