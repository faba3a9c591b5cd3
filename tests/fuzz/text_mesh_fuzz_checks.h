// The round trip shared by the OBJ and OFF fuzz targets: what every reader
// promises on success (mesh_invariants.h, plus finite values), a failure
// message that is one non-empty line, and an exact round trip through a
// writer and the same reader.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "tests/fuzz/mesh_invariants.h"

namespace lodbake {
namespace fuzz {

// Parses, checks, writes, parses again and requires the identical mesh.
template <typename Parse, typename Write>
void check_round_trip(const uint8_t* data, size_t size, Parse parse, Write write) {
  Result<TriangleMesh> mesh = parse(data, size);
  if (!mesh.is_ok()) {
    check_error(mesh.status());
    return;
  }
  check_mesh(mesh.value());
  check_finite(mesh.value());
  Result<Bytes> bytes = write(mesh.value());
  require(bytes.is_ok());
  Result<TriangleMesh> again = parse(bytes.value().data(), bytes.value().size());
  require(again.is_ok());
  require(again.value() == mesh.value());
}

}  // namespace fuzz
}  // namespace lodbake
