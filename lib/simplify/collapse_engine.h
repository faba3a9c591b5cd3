// The half-edge collapse loop behind simplify(): quadrics, passes over the
// edges sorted by cost, the legality checks and the collapse itself, over
// flat arrays. Internal to lib/simplify; simplify.cpp
// validates the input and turns the result into meshes and a PM.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "lib/core/parallel.h"
#include "lib/simplify/mesh_topology.h"
#include "lib/simplify/simplify.h"

namespace lodbake {
namespace simplify_internal {

/// One applied collapse, in input vertex ids: vt was merged into vs. The
/// positions before the collapse are in EngineState (moved_positions, or the
/// vertices' own in half placement): 20 bytes a record instead of 44.
struct CollapseRecord {
  uint32_t vt = 0;
  uint32_t vs = 0;
  uint32_t vl = kNoVertex;  // third vertex of the removed face (vs, vt, vl)
  uint32_t vr = kNoVertex;  // third vertex of the removed face (vt, vs, vr)
  float error = 0;          // sqrt of the mean quadric error: a distance
};

struct EngineSettings {
  uint64_t target_triangles = 0;  // stop at or below
  double max_cost = 0;            // stop before a collapse costing more (mean squared distance)
  double diagonal = 0;            // of the bounding box, for the statistics
  // The input id of each vertex, when the mesh was renumbered
  // (vertex_order.h): ties between vertices are broken by it, so that the
  // collapse sequence does not depend on the numbering. Null: identity.
  // The engine empties it while it runs (its vertex records hold the ids)
  // and fills it again before it returns.
  std::vector<uint32_t>* input_ids = nullptr;
  // The threads of the parallel steps (never null).
  const ParallelScope* threads = nullptr;
};

struct EngineState {
  std::vector<Vec3f> positions;  // current positions (moved ones in optimal mode)
  std::vector<Triangle> triangles;
  std::vector<uint8_t> triangle_alive;
  std::vector<uint8_t> vertex_alive;
  MeshAttribute normals;    // current values; per-corner corners follow the triangles
  MeshAttribute texcoords;  // likewise
  std::vector<CollapseRecord> log;
  // Optimal placement only (vertices move): vt's then vs's position before
  // log[i], at 2i and 2i + 1. In half placement no vertex moves, so they are
  // `positions[vt]` and `positions[vs]`, and this stays empty.
  std::vector<Vec3f> moved_positions;
  SimplifyStats stats;

  Vec3f vt_position(size_t i) const {
    return moved_positions.empty() ? positions[log[i].vt] : moved_positions[2 * i];
  }
  Vec3f vs_position(size_t i) const {
    return moved_positions.empty() ? positions[log[i].vs] : moved_positions[2 * i + 1];
  }
};

/// Runs the collapses on `mesh` (whose adjacency is `topology`; its arrays
/// become the state's).
/// \pre build_topology(mesh, &topology, with_faces) succeeded, with_faces
/// true when `mesh` has a per-corner attribute.
EngineState run_collapse_engine(TriangleMesh mesh, MeshTopology topology,
                                const SimplifyOptions& options, const EngineSettings& settings);

}  // namespace simplify_internal
}  // namespace lodbake
