// check_usable(): turns a mesh check into the accept/refuse decision of a
// tool. Out-of-range indices and empty meshes are not repairable (the
// readers reject the former before anything else runs); the other blocking
// problems are, so their message points at --repair.
#include "lib/check/mesh_policy.h"

namespace lodbake {
namespace {

bool refused(MeshProblem problem, const UsePolicy& policy) {
  switch (problem) {
    case MeshProblem::kOutOfRangeIndices:
    case MeshProblem::kNonFiniteCoordinates:
    case MeshProblem::kNonManifoldEdges:
      return true;
    case MeshProblem::kNonManifoldVertices:
      return policy.refuse_non_manifold_vertices;
    case MeshProblem::kRepeatedIndexTriangles:
    case MeshProblem::kZeroAreaTriangles:
      return policy.refuse_degenerate_triangles;
    case MeshProblem::kDuplicateTriangles:
      return policy.refuse_duplicate_triangles;
    case MeshProblem::kUnreferencedVertices:
      return policy.refuse_unreferenced_vertices;
    case MeshProblem::kInconsistentOrientation:
      return policy.refuse_inconsistent_orientation;
  }
  return true;
}

}  // namespace

UsePolicy UsePolicy::two_manifold() {
  UsePolicy policy;
  policy.refuse_non_manifold_vertices = true;
  policy.refuse_inconsistent_orientation = true;
  policy.refuse_degenerate_triangles = true;
  policy.refuse_duplicate_triangles = true;
  return policy;
}

std::optional<MeshProblem> first_refused_problem(const MeshCheckReport& report,
                                                 const UsePolicy& policy) {
  // Out-of-range indices come first whatever kAllMeshProblems' order: the
  // other counts leave those triangles out.
  if (report.out_of_range_triangles != 0) return MeshProblem::kOutOfRangeIndices;
  for (MeshProblem problem : kAllMeshProblems) {
    if (report.count(problem) != 0 && refused(problem, policy)) return problem;
  }
  return std::nullopt;
}

bool fixed_by_default_repair(MeshProblem problem) {
  switch (problem) {
    case MeshProblem::kNonManifoldEdges:
    case MeshProblem::kNonManifoldVertices:
    case MeshProblem::kRepeatedIndexTriangles:
    case MeshProblem::kZeroAreaTriangles:
    case MeshProblem::kDuplicateTriangles:
    case MeshProblem::kInconsistentOrientation:
      return true;
    case MeshProblem::kOutOfRangeIndices:
    case MeshProblem::kNonFiniteCoordinates:
    case MeshProblem::kUnreferencedVertices:
      return false;
  }
  return false;
}

Status check_usable(const MeshCheckReport& report, const UsePolicy& policy) {
  if (report.out_of_range_triangles != 0) {
    return invalid_input(report.describe(MeshProblem::kOutOfRangeIndices));
  }
  if (report.triangles == 0) return invalid_input("the mesh has no triangles");
  std::optional<MeshProblem> problem = first_refused_problem(report, policy);
  if (problem) return invalid_input(report.describe(*problem) + " (use --repair to fix)");
  return Status::ok();
}

}  // namespace lodbake
