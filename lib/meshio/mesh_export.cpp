// write_mesh_for_path(): the writer chosen by the output file's extension.
#include "lib/dracoio/draco_io.h"
#include "lib/meshio/file_name.h"
#include "lib/meshio/mesh_writers.h"

namespace lodbake {

Result<Bytes> write_mesh_for_path(const std::string& path, const TriangleMesh& mesh) {
  std::string ext = lower_extension(path);
  if (ext == "obj") return write_obj(mesh);
  if (ext == "off") return write_off(mesh);
  if (ext == "ply") return write_ply(mesh);
  if (ext == "glb") return write_glb(mesh);
  if (ext.empty())
    return unsupported(
        "the output name has no extension to choose the format by (supported: "
        ".obj .off .ply .glb)");
  return unsupported("cannot write a mesh as '." + ext +
                     "' (supported output formats: .obj .off .ply .glb)");
}

}  // namespace lodbake
