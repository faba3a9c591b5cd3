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

std::vector<std::string> corner_wedge_problems(
    const std::vector<std::array<uint32_t, 3>>& corners, const PmWedges& wedges) {
  size_t missing = 0, mixed = 0, first_missing = 0, first_mixed = 0;
  for (size_t f = 0; f < corners.size(); ++f) {
    const std::array<uint32_t, 3>& c = corners[f];
    if (c[0] >= wedges.wedge_count() || c[1] >= wedges.wedge_count() ||
        c[2] >= wedges.wedge_count()) {
      if (missing++ == 0) first_missing = f;
      continue;
    }
    const uint32_t p = wedges.wedge_primitive[c[0]];
    if (p == wedges.wedge_primitive[c[1]] && p == wedges.wedge_primitive[c[2]]) continue;
    if (mixed++ == 0) first_mixed = f;
  }
  std::vector<std::string> problems;
  if (missing != 0)
    problems.push_back(std::to_string(missing) + " faces have a corner without a wedge, first face " +
                       std::to_string(first_missing));
  if (mixed != 0)
    problems.push_back(std::to_string(mixed) + " faces have corners of two primitives, first face " +
                       std::to_string(first_mixed));
  return problems;
}

}  // namespace lodbake
