// TEMPORARY, to be deleted when main has lib/dracoio's read_resource() and
// read_gltf_scene() (branch issue27-reader): stand-ins so that lib/scene
// links and its OBJ + MTL tests run before those land. Remove this file and
// its line in lib/scene/CMakeLists.txt at merge.
#include <string>

#include "lib/scene/scene_io.h"

namespace lodbake {

Result<Bytes> read_resource(const SceneResources& resources, const std::string& uri,
                            std::string* resolved_path) {
  if (resources.folder.empty()) return unsupported("no folder to read '" + uri + "' from");
  if (uri.empty() || uri[0] == '/' || uri.find("..") != std::string::npos)
    return unsupported("'" + uri + "' leaves the asset's folder");
  const std::string path = resources.folder + "/" + uri;
  if (resolved_path != nullptr) *resolved_path = path;
  return read_file(path);
}

Result<Scene> read_gltf_scene(const uint8_t*, size_t, const SceneResources&, ImportReport*) {
  return unsupported("glTF scenes are not read yet");
}

}  // namespace lodbake
