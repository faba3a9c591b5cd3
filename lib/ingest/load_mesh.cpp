#include "lib/ingest/load_mesh.h"

#include "lib/core/sha256.h"
#include "lib/core/unreferenced_vertices.h"
#include "lib/meshio/mesh_import.h"

namespace lodbake {

Status load_mesh(const std::string& path, const LoadOptions& options, LoadedMesh* loaded) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(path));
  return load_mesh_bytes(path, std::move(bytes), options, loaded);
}

Status load_mesh_bytes(const std::string& path, Bytes bytes, const LoadOptions& options,
                       LoadedMesh* loaded) {
  loaded->file_bytes = bytes.size();
  loaded->sha256 = sha256_hex(bytes.data(), bytes.size());
  LODBAKE_ASSIGN_OR_RETURN(loaded->mesh, import_mesh(path, bytes, &loaded->import));
  bytes = Bytes();  // the parsed mesh replaces the file's bytes; free them early

  loaded->check = check_mesh(loaded->mesh);
  const MeshCheckReport* final_check = &loaded->check;
  if (options.repair) {
    loaded->repair.emplace();
    LODBAKE_RETURN_IF_ERROR(repair_mesh(loaded->mesh, &*loaded->repair));
    loaded->check_after_repair = check_mesh(loaded->mesh);
    final_check = &*loaded->check_after_repair;
  }
  LODBAKE_RETURN_IF_ERROR(options.policy ? check_usable(*final_check, *options.policy)
                                         : Status::ok());
  if (options.drop_unreferenced && final_check->out_of_range_triangles == 0)
    loaded->dropped_unreferenced = remove_unreferenced_vertices(loaded->mesh);
  return Status::ok();
}

}  // namespace lodbake
