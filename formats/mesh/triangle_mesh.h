// The one indexed triangle mesh every lodbake module exchanges: what the
// mesh readers produce, what the BASE section stores, what the algorithms
// consume. Plain data, no behaviour beyond small helpers, so that formats/
// (which must not depend on lib/) can read and write it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lodbake {

using Vec3f = std::array<float, 3>;
using Vec2f = std::array<float, 2>;
using Triangle = std::array<uint32_t, 3>;

// How an attribute's values map onto the mesh.
enum class AttributeBinding : uint8_t {
  kNone = 0,       // the mesh does not carry this attribute
  kPerVertex = 1,  // values.size() == positions.size(); corner c uses values[triangles[c]]
  kPerCorner = 2,  // corners.size() == triangles.size(); corner k of triangle t uses
                   // values[corners[t][k]] (OBJ-style separate index streams)
};

// A carried per-vertex or per-corner attribute (normals: 3 components,
// texture coordinates: 2 components), stored flat as `components` floats per value.
struct MeshAttribute {
  AttributeBinding binding = AttributeBinding::kNone;
  uint32_t components = 0;
  std::vector<float> values;      // components * value_count floats
  std::vector<Triangle> corners;  // only for kPerCorner

  bool present() const { return binding != AttributeBinding::kNone; }
  size_t value_count() const { return components == 0 ? 0 : values.size() / components; }
  bool operator==(const MeshAttribute& o) const {
    return binding == o.binding && components == o.components && values == o.values &&
           corners == o.corners;
  }
};

struct TriangleMesh {
  std::vector<Vec3f> positions;
  std::vector<Triangle> triangles;  // counter-clockwise seen from outside
  MeshAttribute normals;            // 3 components when present
  MeshAttribute texcoords;          // 2 components when present

  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return triangles.size(); }
  bool operator==(const TriangleMesh& o) const {
    return positions == o.positions && triangles == o.triangles && normals == o.normals &&
           texcoords == o.texcoords;
  }
};

}  // namespace lodbake
