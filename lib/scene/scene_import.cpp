// read_scene_file(): any asset or mesh file into a Scene. Decompression and
// format detection are import_mesh()'s (prepare_mesh_content()), so a file
// reads as the same format whether a tool asks for a mesh or a scene.
// glTF goes to read_gltf_scene(); every mesh file becomes one mesh named
// after the file, used by one node of one scene (scene_from_mesh.h).
#include <new>
#include <string>

#include "lib/dracoio/draco_io.h"
#include "lib/meshio/mesh_import.h"
#include "lib/meshio/mesh_readers.h"
#include "lib/scene/obj_scene.h"
#include "lib/scene/scene_from_mesh.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_points.h"

namespace lodbake {
namespace {

// "a/b/dragon.ply" -> "dragon" (the name without its folder and extension;
// prepare_mesh_content() already took a ".gz" off).
std::string file_stem(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  if (dot != std::string::npos && dot != 0) name.resize(dot);
  return name;
}

std::string folder_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// PLY colours as COLOR_0: integers as normalized UNSIGNED_BYTE or
// UNSIGNED_SHORT (what glTF allows besides FLOAT), floats as FLOAT.
SceneAttribute colour_stream(const VertexColours& colours) {
  SceneAttribute a;
  a.semantic = "COLOR_0";
  const auto count = static_cast<uint32_t>(colours.values.size() / colours.components);
  if (colours.max_value == 1) {
    a.data = float_accessor(colours.values.data(), count, colours.components);
    return a;
  }
  a.data.type = colours.components == 4 ? ElementType::kVec4 : ElementType::kVec3;
  a.data.normalized = true;
  a.data.count = count;
  if (colours.max_value == 255) {
    a.data.component_type = ComponentType::kUnsignedByte;
    a.data.bytes.reserve(colours.values.size());
    for (float v : colours.values)
      a.data.bytes.push_back(static_cast<uint8_t>(v));
  } else {
    a.data.component_type = ComponentType::kUnsignedShort;
    a.data.bytes.reserve(colours.values.size() * 2);
    for (float v : colours.values) {
      const auto u = static_cast<uint16_t>(v);
      a.data.bytes.push_back(static_cast<uint8_t>(u & 0xff));
      a.data.bytes.push_back(static_cast<uint8_t>(u >> 8));
    }
  }
  return a;
}

Result<Scene> read_ply_scene(const uint8_t* data, size_t size, const std::string& name,
                             ImportReport* report) {
  VertexColours colours;
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, parse_ply(data, size, report, &colours));
  std::vector<SceneAttribute> streams;
  if (colours.components != 0) streams.push_back(colour_stream(colours));
  LODBAKE_ASSIGN_OR_RETURN(ScenePrimitive primitive, primitive_from_mesh(mesh, streams));
  std::vector<ScenePrimitive> primitives;
  primitives.push_back(std::move(primitive));
  return scene_of_mesh(name, std::move(primitives));
}

Result<Scene> parse_scene(const std::string& path, const Bytes& file_bytes,
                          const SceneResources& resources, ImportReport* report) {
  LODBAKE_ASSIGN_OR_RETURN(MeshContent content, prepare_mesh_content(path, file_bytes, report));
  const Bytes& bytes = content.bytes(file_bytes);
  const uint8_t* data = bytes.data();
  const size_t size = bytes.size();
  const std::string name = file_stem(content.file_name);
  switch (content.format) {
    case MeshFormat::kGltf:
    case MeshFormat::kGlb:
      return read_gltf_scene(data, size, resources, report);
    case MeshFormat::kObj:
      return read_obj_scene(data, size, name, resources, report);
    case MeshFormat::kPly:
      return read_ply_scene(data, size, name, report);
    case MeshFormat::kOff: {
      LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, parse_off(data, size, report));
      return scene_from_mesh(mesh, name);
    }
    case MeshFormat::kStl: {
      LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, parse_stl(data, size, report));
      return scene_from_mesh(mesh, name);
    }
    case MeshFormat::kDraco: {
      LODBAKE_ASSIGN_OR_RETURN(TriangleMesh mesh, parse_draco(data, size, report));
      return scene_from_mesh(mesh, name);
    }
  }
  return unsupported("unknown mesh format");
}

}  // namespace

Result<Scene> read_scene_bytes(const std::string& path, const Bytes& bytes,
                               const SceneResources& resources, ImportReport* report) {
  // References resolve from the file's own folder, whatever the caller's.
  SceneResources local = resources;
  local.folder = folder_of(path);
  try {
    Result<Scene> scene = parse_scene(path, bytes, local, report);
    if (!scene.is_ok()) return scene;
    for (SceneMesh& mesh : scene.value().meshes)
      if (mesh.point_of_vertex.size() != mesh.primitives.size()) weld_mesh_points(&mesh);
    return scene;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while reading the file");
  }
}

Result<Scene> read_scene_file(const std::string& path, const SceneResources& resources,
                              ImportReport* report) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(path));
  return read_scene_bytes(path, bytes, resources, report);
}

}  // namespace lodbake
