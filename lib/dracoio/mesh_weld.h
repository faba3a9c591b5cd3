// Internal to lib/dracoio: the mesh as glTF and Draco primitives store it
// (every attribute per vertex, seams stored as duplicated vertices) and the
// welding that turns it into a TriangleMesh.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"

namespace lodbake {
namespace dracoio {

// One vertex per glTF vertex (Draco point); normals and texcoords, when not
// empty, hold 3 and 2 floats per vertex.
struct RawMesh {
  std::vector<Vec3f> positions;
  std::vector<float> normals;
  std::vector<float> texcoords;
  std::vector<Triangle> triangles;
};

// Merges vertices whose positions are exactly equal (+0 and -0 count as equal;
// a NaN only matches the same bit pattern). Welded vertices keep the index
// order of their first occurrence, so a mesh without coincident positions
// comes out with the same vertex order and triangles. An attribute stays per
// vertex when every set of merged vertices carries bit-identical values;
// otherwise it becomes per corner with one value per raw vertex. Sets
// `*welded` to the number of vertices merged away.
TriangleMesh weld_exact_positions(RawMesh raw, uint64_t* welded);

}  // namespace dracoio
}  // namespace lodbake
