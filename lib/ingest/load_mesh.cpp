#include "lib/ingest/load_mesh.h"

#include "formats/container/container_layout.h"
#include "formats/sections/open_container.h"
#include "lib/core/parallel.h"
#include "lib/core/sha256.h"
#include "lib/core/unreferenced_vertices.h"
#include "lib/ingest/container_mesh.h"
#include "lib/meshio/corner_split.h"
#include "lib/meshio/file_name.h"
#include "lib/meshio/mesh_import.h"
#include "lib/meshio/writer_support.h"

namespace lodbake {

Status load_mesh(const std::string& path, const LoadOptions& options, LoadedMesh* loaded) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(path));
  return load_mesh_bytes(path, std::move(bytes), options, loaded);
}

Status load_mesh_bytes(const std::string& path, Bytes bytes, const LoadOptions& options,
                       LoadedMesh* loaded) {
  LODBAKE_RETURN_IF_ERROR(parse_mesh_bytes(path, std::move(bytes), loaded));
  return prepare_mesh(options, loaded);
}

bool has_per_corner_attributes(const TriangleMesh& mesh) {
  return mesh.normals.binding == AttributeBinding::kPerCorner ||
         mesh.texcoords.binding == AttributeBinding::kPerCorner;
}

Status parse_mesh_bytes(const std::string& path, Bytes bytes, LoadedMesh* loaded) {
  loaded->file_bytes = bytes.size();
  loaded->sha256 = sha256_hex(bytes.data(), bytes.size());
  // Another tool's output (its magic, or a .lbk name so that a broken
  // header gets the container reader's error): the mesh it stands for,
  // checked like any mesh.
  if (starts_with_container_magic(bytes.data(), bytes.size()) || lower_extension(path) == "lbk") {
    LODBAKE_ASSIGN_OR_RETURN(OpenedContainer file, open_container(std::move(bytes)));
    LODBAKE_ASSIGN_OR_RETURN(ContainerMesh mesh, container_input_mesh(file));
    loaded->mesh = std::move(mesh.mesh);
    loaded->original_input = mesh.input;
    loaded->container_source = mesh.source;
    loaded->import.format = "lodbake container (" + mesh.source + ")";
    if (mesh.asset_meshes > 1)
      loaded->import.warnings.push_back(
          "the container holds an asset of " + std::to_string(mesh.asset_meshes) +
          " meshes; this tool builds on one mesh, group " + std::to_string(mesh.group) +
          "'s (every mesh: the builders and simplify --pm on the container, simplify -o "
          "ASSET.glb on the glTF file)");
  } else {
    LODBAKE_ASSIGN_OR_RETURN(loaded->mesh, import_mesh(path, bytes, &loaded->import));
  }
  return Status::ok();  // the parsed mesh replaces the file's bytes, freed here
}

Status prepare_mesh(const LoadOptions& options, LoadedMesh* loaded) {
  if (options.per_vertex_attributes && has_per_corner_attributes(loaded->mesh)) {
    LODBAKE_RETURN_IF_ERROR(check_writable(loaded->mesh));
    const size_t before = loaded->mesh.positions.size();
    loaded->mesh = split_corner_attributes(loaded->mesh);
    loaded->seam_vertices = loaded->mesh.positions.size() - before;
  }

  const ParallelScope scope(options.threads);
  const PartRunner run_parts = [&scope](size_t parts, const std::function<void(size_t)>& part) {
    scope.for_each_part(parts, part);
  };
  loaded->check = check_mesh(loaded->mesh, run_parts);
  const MeshCheckReport* final_check = &loaded->check;
  bool repair = options.repair;
  if (!repair && options.policy && loaded->check.triangles != 0) {
    // Problems come in kAllMeshProblems order with out-of-range indices and
    // non-finite coordinates first, so when the first refused problem is one
    // the default repair fixes, it fixes all of them.
    std::optional<MeshProblem> problem = first_refused_problem(loaded->check, *options.policy);
    if (problem && fixed_by_default_repair(*problem)) {
      if (options.strict) return invalid_input("--strict: " + loaded->check.describe(*problem));
      repair = true;
    }
  }
  if (repair) {
    RepairReport report;
    MeshCheckReport after;
    LODBAKE_RETURN_IF_ERROR(repair_mesh(loaded->mesh, &report, &after, run_parts));
    loaded->repair = report;
    loaded->repaired_by_default = !options.repair;
    loaded->check_after_repair = std::move(after);
    final_check = &*loaded->check_after_repair;
  }
  LODBAKE_RETURN_IF_ERROR(options.policy ? check_usable(*final_check, *options.policy)
                                         : Status::ok());
  if (options.drop_unreferenced && final_check->out_of_range_triangles == 0)
    loaded->dropped_unreferenced = remove_unreferenced_vertices(loaded->mesh);
  return Status::ok();
}

}  // namespace lodbake
