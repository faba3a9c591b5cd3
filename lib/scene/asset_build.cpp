#include "lib/scene/asset_build.h"

#include <algorithm>
#include <filesystem>
#include <set>
#include <utility>

#include "formats/container/container_layout.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/open_container.h"
#include "lib/meshio/mesh_import.h"
#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/ply_header.h"
#include "lib/meshio/ply_plan.h"
#include "lib/scene/scene_container.h"
#include "lib/scene/scene_pack.h"

namespace lodbake {
namespace {

// What the tools' choice between mesh and asset looks at in a mesh file.
struct FileTraits {
  bool gltf = false;
  bool materials = false;  // an OBJ's, as is_asset() counts them
  bool texcoords = false;  // an OBJ's, on some face
  bool colours = false;    // a PLY's vertex colours
};

// True when one of the OBJ's material libraries names a file that can be
// read, wherever it is: a library outside the folder still makes the file
// an asset, so that reading it fails (exit 5) instead of the materials
// being dropped without a word.
bool resolves(const std::string& obj_path, const std::vector<std::string>& libraries) {
  SceneResources anywhere;
  anywhere.folder = std::filesystem::path(obj_path).parent_path().string();
  if (anywhere.folder.empty()) anywhere.folder = ".";
  anywhere.allow_outside = true;
  return std::any_of(libraries.begin(), libraries.end(), [&](const std::string& library) {
    return read_resource(anywhere, library).is_ok();
  });
}

bool mentions(const Bytes& bytes, const std::string& word) {
  return std::search(bytes.begin(), bytes.end(), word.begin(), word.end()) != bytes.end();
}

bool utf16(const Bytes& bytes) {
  return bytes.size() >= 2 &&
         ((bytes[0] == 0xff && bytes[1] == 0xfe) || (bytes[0] == 0xfe && bytes[1] == 0xff));
}

FileTraits obj_traits(const std::string& path, const Bytes& bytes, bool want_texcoords) {
  FileTraits traits;
  // Most OBJ files have neither: spare them a second parse. (UTF-16 text
  // hides its keywords from a byte search.)
  const bool may_have_materials = utf16(bytes) || mentions(bytes, "usemtl");
  if (!may_have_materials && !(want_texcoords && mentions(bytes, "vt"))) return traits;
  ImportReport ignored;
  ObjMaterialGroups groups;
  Result<TriangleMesh> mesh = parse_obj(bytes.data(), bytes.size(), &ignored, &groups);
  if (!mesh.is_ok()) return traits;  // the tool's own read says what is wrong
  traits.texcoords = mesh.value().texcoords.present() || groups.partial_texcoords.present();
  std::set<int32_t> used(groups.triangle_material.begin(), groups.triangle_material.end());
  const bool uses_material = !used.empty() && *used.rbegin() >= 0;
  traits.materials = used.size() > 1 || (uses_material && resolves(path, groups.libraries));
  return traits;
}

bool ply_has_colours(const Bytes& bytes) {
  Result<PlyHeader> header = parse_ply_header(bytes.data(), bytes.size());
  if (!header.is_ok()) return false;
  ImportReport ignored;
  Result<PlyPlan> plan = plan_ply(header.value(), bytes.size() - header.value().body_offset,
                                  &ignored, /*want_colours=*/true);
  return plan.is_ok() && plan.value().colour_components != 0;
}

FileTraits mesh_file_traits(const std::string& path, const Bytes& file_bytes, bool want_texcoords) {
  ImportReport ignored;
  Result<MeshContent> content = prepare_mesh_content(path, file_bytes, &ignored);
  if (!content.is_ok()) return {};
  const Bytes& bytes = content.value().bytes(file_bytes);
  FileTraits traits;
  switch (content.value().format) {
    case MeshFormat::kGltf:
    case MeshFormat::kGlb:
      traits.gltf = true;
      break;
    case MeshFormat::kObj:
      traits = obj_traits(path, bytes, want_texcoords);
      break;
    case MeshFormat::kPly:
      traits.colours = ply_has_colours(bytes);
      break;
    default:
      break;
  }
  return traits;
}

}  // namespace

bool is_asset(const std::string& path, const Bytes& bytes) {
  if (starts_with_container_magic(bytes.data(), bytes.size())) {
    // The section table says it; no section needs decoding to know.
    Result<Container> container = read_container(bytes.data(), bytes.size());
    return container.is_ok() && has_scene(container.value());
  }
  const FileTraits traits = mesh_file_traits(path, bytes, false);
  return traits.gltf || traits.materials || traits.colours;
}

bool is_scene_source(const std::string& path, const Bytes& bytes) {
  if (starts_with_container_magic(bytes.data(), bytes.size())) return false;
  const FileTraits traits = mesh_file_traits(path, bytes, true);
  return traits.gltf || traits.materials || traits.colours || traits.texcoords;
}

Result<Scene> read_asset(const std::string& path, const Bytes& bytes,
                         const SceneResources& resources, ImportReport* report) {
  if (starts_with_container_magic(bytes.data(), bytes.size())) {
    LODBAKE_ASSIGN_OR_RETURN(OpenedContainer opened, open_container(bytes));
    report->format = "lodbake container (asset)";
    return scene_of_container(opened.decoded(), nullptr, report);
  }
  return read_scene_bytes(path, bytes, resources, report);
}

Result<AssetBuild> build_asset(const Scene& scene, MetaSection meta, const LoadOptions& load,
                               const MeshBuilder& build) {
  LODBAKE_ASSIGN_OR_RETURN(SceneContainerContents contents, scene_container_contents(scene));
  if (contents.topologies.empty())
    return invalid_input("the asset has no triangles (no mesh with a triangle primitive)");
  AssetBuild result;
  result.warnings = contents.warnings;
  std::vector<MeshSections> built;
  for (size_t g = 0; g < contents.topologies.size(); ++g) {
    const uint32_t mesh = contents.section.meshes[g].mesh;
    const std::string where = "mesh " + std::to_string(mesh);
    LoadedMesh loaded;
    loaded.mesh = contents.topologies[g].mesh;
    LoadOptions options = load;
    options.drop_unreferenced = true;
    options.per_vertex_attributes = false;
    Status prepared = prepare_mesh(options, &loaded);
    if (!prepared.is_ok()) return Status(prepared.kind(), where + ": " + prepared.message());
    Result<MeshSections> sections = build(mesh, loaded.mesh);
    if (!sections.is_ok())
      return Status(sections.status().kind(), where + ": " + sections.status().message());
    result.groups.push_back({{"group", g},
                             {"mesh", mesh},
                             {"triangles", contents.topologies[g].mesh.triangle_count()},
                             {"repaired", loaded.repair.has_value()},
                             {"report", sections.value().report}});
    built.push_back(std::move(sections).value());
  }
  meta.counts = built.front().counts;
  meta.extra["scene"] = scene_counts(scene);
  LODBAKE_ASSIGN_OR_RETURN(Bytes meta_bytes, encode_meta(meta));
  LODBAKE_ASSIGN_OR_RETURN(Bytes scne, encode_scne(contents.section));
  ContainerWriter writer;
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kMetaTag, std::move(meta_bytes)));
  LODBAKE_RETURN_IF_ERROR(writer.add_known_section(kScneTag, std::move(scne)));
  for (uint32_t g = 0; g < built.size(); ++g)
    for (auto& [tag, bytes] : built[g].sections)
      LODBAKE_RETURN_IF_ERROR(writer.add_known_section(tag, std::move(bytes), g));
  LODBAKE_ASSIGN_OR_RETURN(result.file, writer.finish());
  return result;
}

}  // namespace lodbake
