// The mesh check that runs on every import: counts and problems of an
// indexed triangle mesh, computed exactly on its index structure (no
// geometry kernel needed, so it is fast and CGAL-free). Definitions follow
// ../shared/data/meshes/MANIFEST.md so that its counts can be compared; the
// precise definitions are at the top of mesh_check.cpp and in
// docs/mesh-check.md.
#pragma once

#include <functional>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

using VertexPair = std::array<uint32_t, 2>;

/// Up to kMaxSamples offending elements per problem, the smallest indices
/// first, so that a message can point at where the problem is.
struct MeshCheckSamples {
  static constexpr size_t kMaxSamples = 3;
  std::vector<uint64_t> non_finite_vertices;
  std::vector<uint64_t> out_of_range_triangles;
  std::vector<VertexPair> non_manifold_edges;  // (smaller, larger) vertex index
  std::vector<uint64_t> non_manifold_vertices;
  std::vector<uint64_t> repeated_index_triangles;
  std::vector<uint64_t> zero_area_triangles;
  std::vector<uint64_t> duplicate_triangles;  // the later copy
  std::vector<uint64_t> unreferenced_vertices;
  std::vector<VertexPair> inconsistent_orientation_edges;
};

/// The problems a check can find, in the order problems() lists them.
enum class MeshProblem {
  kNonFiniteCoordinates,
  kOutOfRangeIndices,
  kNonManifoldEdges,
  kNonManifoldVertices,
  kRepeatedIndexTriangles,
  kZeroAreaTriangles,
  kDuplicateTriangles,
  kUnreferencedVertices,
  kInconsistentOrientation,
};
constexpr MeshProblem kAllMeshProblems[] = {
    MeshProblem::kNonFiniteCoordinates,    MeshProblem::kOutOfRangeIndices,
    MeshProblem::kNonManifoldEdges,        MeshProblem::kNonManifoldVertices,
    MeshProblem::kRepeatedIndexTriangles,  MeshProblem::kZeroAreaTriangles,
    MeshProblem::kDuplicateTriangles,      MeshProblem::kUnreferencedVertices,
    MeshProblem::kInconsistentOrientation,
};

struct MeshCheckReport {
  uint64_t vertices = 0;
  uint64_t triangles = 0;
  // Over referenced, finite vertices only (unreferenced vertices must not
  // change results); both zero when there are none.
  Vec3f bbox_min{0, 0, 0};
  Vec3f bbox_max{0, 0, 0};
  // Topology counts use the "topology triangles": in-range indices, three
  // distinct vertices (zero-area and duplicate triangles are included).
  uint64_t components = 0;                // topology triangles connected through shared vertices
  uint64_t edges = 0;                     // distinct undirected edges
  uint64_t boundary_edges = 0;            // edges with exactly one face
  uint64_t boundary_loops = 0;            // connected components of the boundary edges
  uint64_t non_manifold_edges = 0;        // edges with more than two faces
  uint64_t non_manifold_vertices = 0;     // faces around the vertex form more than one fan
  uint64_t degenerate_triangles = 0;      // repeated_index_triangles + zero_area_triangles
  uint64_t repeated_index_triangles = 0;  // in range, some index twice
  uint64_t zero_area_triangles = 0;       // distinct finite corners, exactly collinear
  uint64_t duplicate_triangles = 0;       // same vertex set as an earlier triangle
  uint64_t unreferenced_vertices = 0;     // used by no triangle with in-range indices
  uint64_t inconsistent_orientation_edges = 0;  // 2-face edges walked twice the same way
  uint64_t non_finite_coordinates = 0;          // vertices with a NaN or infinite coordinate
  uint64_t out_of_range_triangles = 0;          // an index >= vertices (readers reject these)
  // Euler genus when the mesh is closed, manifold, consistently oriented and
  // one component; -1 otherwise.
  int64_t genus = -1;
  MeshCheckSamples samples;

  bool closed() const { return boundary_edges == 0; }
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0; }
  /// How many elements have `problem` (vertices, triangles or edges).
  uint64_t count(MeshProblem problem) const;
  /// True when any problem count is non-zero (open boundaries and several
  /// components are not problems).
  bool has_problems() const;
  /// One line describing `problem` with its first offending elements, e.g.
  /// "3 non-manifold edges (more than two faces): edges 0-1, 0-5, 2-7, ...";
  /// empty when the mesh does not have it.
  std::string describe(MeshProblem problem) const;
  /// describe() of every problem the mesh has, in kAllMeshProblems order.
  std::vector<std::string> problems() const;
};

/// Checks `mesh`. Linear time apart from small per-vertex sorts; never fails
/// (out-of-range indices are counted, not followed). Its independent parts
/// are handed to `run_parts` when given (ParallelScope::for_each_part: the
/// check stays free of a thread library, as the replay runtime links it);
/// the report is the same however they run.
using PartRunner = std::function<void(size_t parts, const std::function<void(size_t)>& part)>;
MeshCheckReport check_mesh(const TriangleMesh& mesh, const PartRunner& run_parts = nullptr);

/// The index-structure part of check_mesh() that says whether `mesh` is a
/// triangulation: out-of-range and repeated indices, edges (boundary,
/// non-manifold, inconsistent orientation) and duplicates, with their
/// samples, equal to check_mesh()'s. Coordinates, zero areas, non-manifold
/// vertices, components and genus are left at zero: the replay modes run
/// this at every step, where those cost more than the rest together.
MeshCheckReport check_triangulation(const TriangleMesh& mesh);

}  // namespace lodbake
