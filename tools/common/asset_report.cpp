#include "tools/common/asset_report.h"

#include <iostream>

#include "formats/container/container_layout.h"
#include "formats/sections/open_container.h"
#include "lib/core/sha256.h"
#include "lib/ingest/container_mesh.h"
#include "lib/scene/scene_topology.h"
#include "tools/common/mesh_report.h"

namespace lodbake::cli {

MetaInput asset_meta_input(const std::string& path, const Bytes& bytes) {
  if (starts_with_container_magic(bytes.data(), bytes.size())) {
    Result<OpenedContainer> opened = open_container(bytes);
    if (opened.is_ok())
      if (std::optional<MetaInput> input = container_meta_input(opened.value())) return *input;
  }
  const size_t slash = path.find_last_of('/');
  return MetaInput{to_valid_utf8(slash == std::string::npos ? path : path.substr(slash + 1)),
                   sha256_hex(bytes.data(), bytes.size()), bytes.size()};
}

int print_asset_build(const Tool& tool, const char* schema, const std::string& input,
                      const std::string& output, const AssetBuild& built) {
  if (tool.json()) {
    tool.print_json({{"schema", schema},
                     {"input", input},
                     {"asset", true},
                     {"output", output},
                     {"bytes", built.file.size()},
                     {"groups", built.groups}});
    return 0;
  }
  std::cout << "input       " << input << ": an asset, " << built.groups.size()
            << " meshes with triangles, each built once in its own group\n";
  for (const nlohmann::json& g : built.groups) {
    std::cout << "group " << g["group"].get<uint64_t>() << "     mesh " << g["mesh"].get<uint64_t>()
              << ", " << g["triangles"].get<uint64_t>() << " triangles"
              << (g["repaired"].get<bool>() ? " (repaired)" : "") << ": " << g["report"].dump()
              << "\n";
  }
  std::cout << "wrote       " << output << ": " << built.file.size() << " bytes\n";
  return 0;
}

int run_asset_build(const Tool& tool, const AssetRun& run, MetaSection meta, const Bytes& bytes,
                    const MeshBuilder& build) {
  if (run.repair && run.strict)
    return tool.usage_error("--strict refuses what --repair would fix: give one of them");
  ImportReport imported;
  Result<Scene> scene = read_asset(run.input, bytes, SceneResources{}, &imported);
  if (!scene.is_ok()) return tool.fail(run.input, scene.status());
  for (const std::string& warning : imported.warnings)
    tool.warn(run.input, warning);
  print_import_notes(tool, run.input, imported);
  if (run.on_scene) run.on_scene(scene.value());
  LoadOptions load;
  load.repair = run.repair;
  load.strict = run.strict;
  meta.input = asset_meta_input(run.input, bytes);
  size_t meshes = 0, done = 0;
  for (const SceneMesh& mesh : scene.value().meshes)
    meshes += mesh_triangle_count(mesh) != 0;
  Progress progress(tool, run.progress);
  Result<AssetBuild> built =
      build_asset(scene.value(), std::move(meta), load,
                  [&](uint32_t scene_mesh, const TriangleMesh& mesh) -> Result<MeshSections> {
                    Result<MeshSections> sections = build(scene_mesh, mesh);
                    if (meshes != 0) progress.update(static_cast<double>(++done) / meshes);
                    return sections;
                  });
  if (!built.is_ok()) return tool.fail(run.input, built.status());
  Status written = write_file_atomic(run.output, built.value().file);
  if (!written.is_ok()) return tool.fail(run.output, written);
  for (const std::string& warning : built.value().warnings)
    tool.warn(run.output, warning);
  if (!run.attributes)
    tool.info(run.output, run.partial_note != nullptr ? run.partial_note : kPositionsOnly);
  return print_asset_build(tool, run.schema, run.input, run.output, built.value());
}

}  // namespace lodbake::cli
