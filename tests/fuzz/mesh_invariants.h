// Shared by the mesh-reader fuzz targets: structural invariants every
// successfully imported TriangleMesh must satisfy, the finiteness the text,
// PLY and STL readers promise, and the error-message contract of a failed
// import. A violation traps, so the fuzzer (or the corpus replay under the
// sanitizers) reports it.
#pragma once

#include <cmath>
#include <cstring>
#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {
namespace fuzz {

inline void require(bool condition) {
  if (!condition) __builtin_trap();
}

// Sizes and indices of one attribute agree with its binding.
inline void check_attribute(const TriangleMesh& mesh, const MeshAttribute& a, uint32_t components) {
  if (!a.present()) return;
  require(a.components == components);
  require(a.values.size() % components == 0);
  if (a.binding == AttributeBinding::kPerVertex) {
    require(a.value_count() == mesh.positions.size());
    require(a.corners.empty());
    return;
  }
  require(a.binding == AttributeBinding::kPerCorner);
  require(a.corners.size() == mesh.triangles.size());
  for (const Triangle& t : a.corners) {
    for (uint32_t i : t)
      require(i < a.value_count());
  }
}

// Every index (of the triangles and of the attributes) is in range.
inline void check_indices(const TriangleMesh& mesh) {
  for (const Triangle& t : mesh.triangles) {
    for (uint32_t i : t)
      require(i < mesh.positions.size());
  }
  check_attribute(mesh, mesh.normals, 3);
  check_attribute(mesh, mesh.texcoords, 2);
}

// check_indices() on a mesh that has triangles (readers refuse empty ones).
inline void check_mesh(const TriangleMesh& mesh) {
  require(!mesh.triangles.empty());
  check_indices(mesh);
}

// Positions and attribute values are all finite.
inline void check_finite(const TriangleMesh& mesh) {
  for (const Vec3f& p : mesh.positions) {
    for (float c : p)
      require(std::isfinite(c));
  }
  for (const MeshAttribute* a : {&mesh.normals, &mesh.texcoords}) {
    for (float f : a->values)
      require(std::isfinite(f));
  }
}

// One non-empty line.
inline void check_error(const Status& status) {
  const std::string& m = status.message();
  require(!status.is_ok());
  require(!m.empty());
  require(m.find('\n') == std::string::npos);
}

inline bool all_finite(const TriangleMesh& mesh) {
  for (const Vec3f& p : mesh.positions) {
    for (float c : p) {
      if (!(c - c == 0.0f)) return false;
    }
  }
  return true;
}

// Position equality that treats +0 and -0 as equal (welding does) and
// compares anything else bit for bit.
inline bool same_position(const Vec3f& a, const Vec3f& b) {
  for (int i = 0; i < 3; ++i) {
    if (a[i] == 0.0f && b[i] == 0.0f) continue;
    if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0) return false;
  }
  return true;
}

}  // namespace fuzz
}  // namespace lodbake
