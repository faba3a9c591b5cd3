// The mesh as glTF primitives store it (every attribute per vertex, seams
// stored as duplicated vertices) and the welding that turns it into a
// TriangleMesh: what flatten_scene() (scene_flatten.h) merges a scene into.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {

// One vertex per glTF vertex; normals and texcoords, when not
// empty, hold 3 and 2 floats per vertex.
struct RawMesh {
  std::vector<Vec3f> positions;
  std::vector<float> normals;
  std::vector<float> texcoords;
  std::vector<Triangle> triangles;
};

// How glTF vertices with equal positions become one vertex.
enum class WeldMode {
  // Every exactly equal position is one vertex: glTF stores a vertex once per
  // side of a normal or texture seam, and only the positions tell the
  // topology. The default for every file lodbake did not write.
  kExactPositions,
  // Equal positions are one vertex only where their triangles share an edge
  // (in positions) that exactly two triangles use, in opposite directions:
  // seams are closed, but vertices that a repair split apart (two fans
  // touching at a point, the pages of a non-manifold edge) stay apart. For
  // lodbake's GLB of a mesh with per-corner attributes.
  kManifoldEdges,
  // Every glTF vertex is a vertex: lodbake's GLB of a mesh whose attributes
  // are all per vertex, where the index buffer already is the topology.
  kNone,
};

// Merges vertices as `mode` says (+0 and -0 count as equal; a NaN only
// matches the same bit pattern). Merged vertices are numbered by their first
// raw vertex, so a mesh without coincident positions comes out with the same
// vertex order and triangles. Under kManifoldEdges a vertex used by no
// triangle joins the first vertex at its position. An attribute stays per
// vertex when every set of merged vertices carries bit-identical values;
// otherwise it becomes per corner with one value per raw vertex. Sets
// `*welded` to the number of vertices merged away.
TriangleMesh weld_vertices(RawMesh raw, WeldMode mode, uint64_t* welded);

}  // namespace lodbake
