// check_usable(): turns a mesh check into the accept/refuse decision of a
// tool run without --repair. Out-of-range indices and empty meshes are not
// repairable (the readers reject the former before anything else runs); the
// other blocking problems are, so their message points at --repair.
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

Status check_usable(const MeshCheckReport& report, const UsePolicy& policy) {
  if (report.out_of_range_triangles != 0) {
    return invalid_input(report.describe(MeshProblem::kOutOfRangeIndices));
  }
  if (report.triangles == 0) return invalid_input("the mesh has no triangles");
  for (MeshProblem problem : kAllMeshProblems) {
    if (report.count(problem) != 0 && refused(problem, policy)) {
      return invalid_input(report.describe(problem) + " (use --repair to fix)");
    }
  }
  return Status::ok();
}

}  // namespace lodbake
