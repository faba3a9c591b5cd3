// Checks shared by the OBJ and OFF fuzz targets: what every reader promises
// on success (indices in range, finite values, attribute sizes), a failure
// message that is one non-empty line, and an exact round trip through a
// writer and the same reader.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {
namespace fuzz {

inline void require(bool condition) {
  if (!condition) std::abort();
}

inline void check_message(const Status& status) {
  require(!status.is_ok());
  require(!status.message().empty());
  require(status.message().find('\n') == std::string::npos);
}

inline void check_attribute(const MeshAttribute& a, const TriangleMesh& mesh, uint32_t components) {
  if (!a.present()) return;
  require(a.components == components);
  require(a.values.size() % components == 0);
  for (float f : a.values)
    require(std::isfinite(f));
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

inline void check_mesh(const TriangleMesh& mesh) {
  require(!mesh.triangles.empty());
  for (const Vec3f& p : mesh.positions) {
    for (float c : p)
      require(std::isfinite(c));
  }
  for (const Triangle& t : mesh.triangles) {
    for (uint32_t i : t)
      require(i < mesh.positions.size());
  }
  check_attribute(mesh.normals, mesh, 3);
  check_attribute(mesh.texcoords, mesh, 2);
}

// Parses, checks, writes, parses again and requires the identical mesh.
template <typename Parse, typename Write>
void check_round_trip(const uint8_t* data, size_t size, Parse parse, Write write) {
  Result<TriangleMesh> mesh = parse(data, size);
  if (!mesh.is_ok()) {
    check_message(mesh.status());
    return;
  }
  check_mesh(mesh.value());
  Result<Bytes> bytes = write(mesh.value());
  require(bytes.is_ok());
  Result<TriangleMesh> again = parse(bytes.value().data(), bytes.value().size());
  require(again.is_ok());
  require(again.value() == mesh.value());
}

}  // namespace fuzz
}  // namespace lodbake
