// write_scene_file(): a scene to a .glb, or to a .gltf with the files it
// refers to, all or none.
#include <filesystem>
#include <string>

#include "lib/meshio/file_name.h"
#include "lib/scene/scene_io.h"

namespace lodbake {

bool is_scene_output(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == "glb" || ext == "gltf";
}

Status stage_scene_file(StagedOutputs* staged, const std::string& path, const Scene& scene,
                        SceneWriteReport* report) {
  const std::string ext = lower_extension(path);
  if (ext == "glb") {
    LODBAKE_ASSIGN_OR_RETURN(Bytes glb, write_scene_glb(scene, report));
    return staged->stage(path, glb);
  }
  if (ext != "gltf")
    return Status(ErrorKind::kUsage, "a scene is written as .glb or .gltf, not '." + ext + "'");
  const size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  LODBAKE_ASSIGN_OR_RETURN(std::vector<SceneOutputFile> files,
                           write_scene_gltf(scene, name, report));
  for (const SceneOutputFile& file : files) {
    // An image keeps its input's subfolder ("tex/a.png", as an OBJ's
    // library names it): the folder must exist before the file is staged in
    // it. A run that fails later leaves it behind, empty.
    const size_t sub = file.name.find_last_of('/');
    if (sub != std::string::npos) {
      std::error_code error;
      std::filesystem::create_directories(folder + file.name.substr(0, sub), error);
      if (error)
        return io_error("cannot create the folder '" + folder + file.name.substr(0, sub) +
                        "': " + error.message());
    }
    LODBAKE_RETURN_IF_ERROR(staged->stage(folder + file.name, file.bytes));
  }
  return Status::ok();
}

Status write_scene_file(const std::string& path, const Scene& scene, SceneWriteReport* report) {
  StagedOutputs staged;
  LODBAKE_RETURN_IF_ERROR(stage_scene_file(&staged, path, scene, report));
  std::string failed;
  return staged.commit(&failed);
}

}  // namespace lodbake
