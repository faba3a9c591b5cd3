// Binary little-endian PLY writer (Turk's PLY format as read by Blender,
// MeshLab, CGAL and parse_ply()).
//
// Choices: vertices carry float x y z, then nx ny nz and s t when the mesh
// has normals or texture coordinates; per-corner attributes are first made
// per-vertex by split_corner_attributes() (vertices duplicated where their
// corners disagree). Faces are "list uchar uint vertex_indices" triangles.
// The header has a fixed comment and no timestamps, so output is
// deterministic.
#include <string>

#include "formats/support/byte_reader.h"
#include "lib/meshio/corner_split.h"
#include "lib/meshio/mesh_writers.h"
#include "lib/meshio/writer_support.h"

namespace lodbake {

Result<Bytes> write_ply(const TriangleMesh& input) {
  LODBAKE_RETURN_IF_ERROR(check_writable(input));
  const TriangleMesh mesh = split_corner_attributes(input);
  if (mesh.positions.size() >= uint64_t{0xffffffff})
    return invalid_input("mesh has more vertices than 32-bit PLY indices can address");
  const bool normals = mesh.normals.present();
  const bool st = mesh.texcoords.present();

  Bytes bytes;
  TextOut header(&bytes);
  header.text("ply\nformat binary_little_endian 1.0\ncomment written by lodbake\nelement vertex ");
  header.integer(mesh.positions.size());
  header.text("\nproperty float x\nproperty float y\nproperty float z\n");
  if (normals) header.text("property float nx\nproperty float ny\nproperty float nz\n");
  if (st) header.text("property float s\nproperty float t\n");
  header.text("element face ");
  header.integer(mesh.triangles.size());
  header.text("\nproperty list uchar uint vertex_indices\nend_header\n");

  const size_t floats_per_vertex = 3 + (normals ? 3 : 0) + (st ? 2 : 0);
  bytes.reserve(bytes.size() + mesh.positions.size() * floats_per_vertex * 4 +
                mesh.triangles.size() * 13);
  ByteWriter out(&bytes);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (float c : mesh.positions[i])
      out.write(c);
    for (size_t k = 0; normals && k < 3; ++k)
      out.write(mesh.normals.values[i * 3 + k]);
    for (size_t k = 0; st && k < 2; ++k)
      out.write(mesh.texcoords.values[i * 2 + k]);
  }
  for (const Triangle& t : mesh.triangles) {
    out.write(uint8_t{3});
    for (uint32_t i : t)
      out.write(i);
  }
  return bytes;
}

}  // namespace lodbake
