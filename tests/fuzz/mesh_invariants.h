// Shared by the mesh-reader fuzz targets: structural invariants every
// successfully imported TriangleMesh must satisfy, and the error-message
// contract of a failed import. A violation traps, so the fuzzer (or the
// corpus replay under the sanitizers) reports it.
#pragma once

#include <cstring>
#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {
namespace fuzz {

inline void require(bool condition) {
  if (!condition) __builtin_trap();
}

inline void check_attribute(const TriangleMesh& mesh, const MeshAttribute& a, uint32_t components) {
  if (!a.present()) return;
  require(a.components == components);
  require(a.values.size() % components == 0);
  if (a.binding == AttributeBinding::kPerVertex) {
    require(a.value_count() == mesh.positions.size());
  } else {
    require(a.corners.size() == mesh.triangles.size());
    for (const Triangle& t : a.corners) {
      for (uint32_t i : t)
        require(i < a.value_count());
    }
  }
}

inline void check_mesh(const TriangleMesh& mesh) {
  require(!mesh.triangles.empty());
  for (const Triangle& t : mesh.triangles) {
    for (uint32_t i : t)
      require(i < mesh.positions.size());
  }
  check_attribute(mesh, mesh.normals, 3);
  check_attribute(mesh, mesh.texcoords, 2);
}

// One non-empty line, lower-case start.
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
