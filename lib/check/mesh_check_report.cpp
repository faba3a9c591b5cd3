// Human-readable problem lines of a MeshCheckReport: one line per problem,
// count first, then the first offending elements, so a user can find them
// in the file ("3 non-manifold edges (more than two faces): edges 0-1, 0-5, 2-7, ...").
#include <string>
#include <vector>

#include "lib/check/mesh_check.h"

namespace lodbake {
namespace {

std::string element_text(uint64_t value) {
  return std::to_string(value);
}
std::string element_text(const VertexPair& edge) {
  return std::to_string(edge[0]) + "-" + std::to_string(edge[1]);
}

// "<count> <noun>[s] <what>: <noun>[s] a, b, c, ..." -- the trailing "..."
// says there are more than the samples shown.
template <typename T>
std::string line(uint64_t count, const char* singular, const char* plural_form,
                 const std::string& what, const char* element_singular, const char* element_plural,
                 const std::vector<T>& samples) {
  std::string text =
      std::to_string(count) + " " + (count == 1 ? singular : plural_form) + " " + what;
  if (samples.empty()) return text;
  text += std::string(": ") + (samples.size() == 1 ? element_singular : element_plural) + " ";
  for (size_t i = 0; i < samples.size(); ++i) {
    if (i > 0) text += ", ";
    text += element_text(samples[i]);
  }
  if (count > samples.size()) text += ", ...";
  return text;
}

}  // namespace

uint64_t MeshCheckReport::count(MeshProblem problem) const {
  switch (problem) {
    case MeshProblem::kNonFiniteCoordinates:
      return non_finite_coordinates;
    case MeshProblem::kOutOfRangeIndices:
      return out_of_range_triangles;
    case MeshProblem::kNonManifoldEdges:
      return non_manifold_edges;
    case MeshProblem::kNonManifoldVertices:
      return non_manifold_vertices;
    case MeshProblem::kRepeatedIndexTriangles:
      return repeated_index_triangles;
    case MeshProblem::kZeroAreaTriangles:
      return zero_area_triangles;
    case MeshProblem::kDuplicateTriangles:
      return duplicate_triangles;
    case MeshProblem::kUnreferencedVertices:
      return unreferenced_vertices;
    case MeshProblem::kInconsistentOrientation:
      return inconsistent_orientation_edges;
  }
  return 0;
}

bool MeshCheckReport::has_problems() const {
  for (MeshProblem problem : kAllMeshProblems) {
    if (count(problem) != 0) return true;
  }
  return false;
}

std::string MeshCheckReport::describe(MeshProblem problem) const {
  const uint64_t n = count(problem);
  if (n == 0) return "";
  const MeshCheckSamples& s = samples;
  switch (problem) {
    case MeshProblem::kNonFiniteCoordinates:
      return line(n, "vertex", "vertices", "with a non-finite coordinate (NaN or infinity)",
                  "vertex", "vertices", s.non_finite_vertices);
    case MeshProblem::kOutOfRangeIndices:
      return line(n, "triangle", "triangles",
                  "with a vertex index out of range (" + std::to_string(vertices) + " vertices)",
                  "triangle", "triangles", s.out_of_range_triangles);
    case MeshProblem::kNonManifoldEdges:
      return line(n, "non-manifold edge", "non-manifold edges", "(more than two faces)", "edge",
                  "edges", s.non_manifold_edges);
    case MeshProblem::kNonManifoldVertices:
      return line(n, "non-manifold vertex", "non-manifold vertices",
                  n == 1 ? "(faces around it form separate fans)"
                         : "(faces around each form separate fans)",
                  "vertex", "vertices", s.non_manifold_vertices);
    case MeshProblem::kRepeatedIndexTriangles:
      return line(n, "degenerate triangle", "degenerate triangles", "with a repeated vertex index",
                  "triangle", "triangles", s.repeated_index_triangles);
    case MeshProblem::kZeroAreaTriangles:
      return line(n, "degenerate triangle", "degenerate triangles",
                  "with zero area (collinear corners)", "triangle", "triangles",
                  s.zero_area_triangles);
    case MeshProblem::kDuplicateTriangles:
      return line(n, "duplicate triangle", "duplicate triangles",
                  "(same vertices as an earlier triangle)", "triangle", "triangles",
                  s.duplicate_triangles);
    case MeshProblem::kUnreferencedVertices:
      return line(n, "unreferenced vertex", "unreferenced vertices", "(used by no triangle)",
                  "vertex", "vertices", s.unreferenced_vertices);
    case MeshProblem::kInconsistentOrientation:
      return line(n, "edge", "edges",
                  "with inconsistent orientation (both faces walk it the same way)", "edge",
                  "edges", s.inconsistent_orientation_edges);
  }
  return "";
}

std::vector<std::string> MeshCheckReport::problems() const {
  std::vector<std::string> lines;
  for (MeshProblem problem : kAllMeshProblems) {
    if (count(problem) != 0) lines.push_back(describe(problem));
  }
  return lines;
}

}  // namespace lodbake
