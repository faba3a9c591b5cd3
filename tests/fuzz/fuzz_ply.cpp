// Fuzz target for parse_ply. On success it checks what every reader promises
// (indices in range, finite values, attribute sizes) and that re-encoding
// the mesh as binary little-endian PLY and reading it back gives the same
// mesh. On failure the message must be one non-empty line.
#include <cstdint>
#include <cstring>
#include <string>

#include "formats/support/file_io.h"
#include "lib/meshio/mesh_readers.h"
#include "tests/fuzz/mesh_invariants.h"

namespace {

using lodbake::AttributeBinding;
using lodbake::Bytes;
using lodbake::TriangleMesh;

using lodbake::fuzz::require;

void append(Bytes* out, const void* p, size_t n) {
  const auto* b = static_cast<const uint8_t*>(p);
  out->insert(out->end(), b, b + n);
}

Bytes encode_binary_ply(const TriangleMesh& mesh) {
  const bool normals = mesh.normals.present();
  const bool texcoords = mesh.texcoords.present();
  std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                       std::to_string(mesh.positions.size()) +
                       "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  if (texcoords) header += "property float u\nproperty float v\n";
  header += "element face " + std::to_string(mesh.triangles.size()) +
            "\nproperty list uchar uint vertex_indices\nend_header\n";
  Bytes out(header.begin(), header.end());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    append(&out, mesh.positions[v].data(), 12);
    if (normals) append(&out, &mesh.normals.values[3 * v], 12);
    if (texcoords) append(&out, &mesh.texcoords.values[2 * v], 8);
  }
  for (const auto& t : mesh.triangles) {
    out.push_back(3);
    append(&out, t.data(), 12);
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::ImportReport report;
  lodbake::Result<TriangleMesh> result = lodbake::parse_ply(data, size, &report);
  if (!result.is_ok()) {
    lodbake::fuzz::check_error(result.status());
    return 0;
  }
  const TriangleMesh& mesh = result.value();
  require(report.format.rfind("ply-", 0) == 0);
  lodbake::fuzz::check_finite(mesh);
  lodbake::fuzz::check_indices(mesh);
  // PLY attributes are vertex properties.
  for (const lodbake::MeshAttribute* a : {&mesh.normals, &mesh.texcoords})
    require(!a->present() || a->binding == AttributeBinding::kPerVertex);

  Bytes again = encode_binary_ply(mesh);
  lodbake::Result<TriangleMesh> reread = lodbake::parse_ply(again.data(), again.size(), nullptr);
  require(reread.is_ok());
  require(reread.value() == mesh);
  return 0;
}
