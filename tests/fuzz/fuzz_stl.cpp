// Fuzz target for parse_stl. On success: indices in range, finite and
// pairwise distinct positions (welding is exact), one triangle per facet,
// and writing the mesh back as binary STL and reading it again gives the
// same mesh (same first-appearance vertex order). On failure the message
// must be one non-empty line.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "lib/meshio/mesh_readers.h"
#include "tests/fuzz/mesh_invariants.h"

namespace {

using lodbake::Bytes;
using lodbake::TriangleMesh;
using lodbake::Vec3f;

using lodbake::fuzz::require;

Bytes encode_binary_stl(const TriangleMesh& mesh) {
  Bytes out(80, 'x');
  auto append = [&out](const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    out.insert(out.end(), b, b + n);
  };
  const auto count = static_cast<uint32_t>(mesh.triangles.size());
  append(&count, 4);
  const float normal[3] = {0, 0, 0};
  const uint16_t attribute = 0;
  for (const auto& t : mesh.triangles) {
    append(normal, 12);
    for (uint32_t v : t)
      append(mesh.positions[v].data(), 12);
    append(&attribute, 2);
  }
  return out;
}

// Positions as welding compares them: -0.0 equals +0.0.
std::vector<Vec3f> canonical(const std::vector<Vec3f>& positions) {
  std::vector<Vec3f> out = positions;
  for (auto& p : out) {
    for (float& c : p)
      c = c == 0.0f ? 0.0f : c;
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::ImportReport report;
  lodbake::Result<TriangleMesh> result = lodbake::parse_stl(data, size, &report);
  if (!result.is_ok()) {
    lodbake::fuzz::check_error(result.status());
    return 0;
  }
  const TriangleMesh& mesh = result.value();
  require(report.file_faces == mesh.triangles.size());
  require(report.welded_vertices + mesh.positions.size() == 3 * mesh.triangles.size());
  lodbake::fuzz::check_indices(mesh);
  lodbake::fuzz::check_finite(mesh);
  std::vector<Vec3f> sorted = canonical(mesh.positions);
  std::sort(sorted.begin(), sorted.end());
  require(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());

  Bytes again = encode_binary_stl(mesh);
  lodbake::Result<TriangleMesh> reread = lodbake::parse_stl(again.data(), again.size(), nullptr);
  require(reread.is_ok());
  require(reread.value() == mesh);
  return 0;
}
