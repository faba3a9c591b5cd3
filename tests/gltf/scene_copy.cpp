// scene_copy ASSET OUTDIR: reads an asset (.gltf, .glb, or any mesh file
// lodbake reads, with read_scene_file), writes it as OUTDIR/<stem>.glb and as
// OUTDIR/<stem>/<stem>.gltf with its .bin and images, then reads both outputs
// back and checks that each gives the input's scene (first_scene_difference).
// Across formats an image's storage (uri, mimeType) is the writer's choice
// and is not compared; its bytes are. Exit codes: 0 equal, 1 usage, 2 I/O,
// 3 and 5 as the reader or writer fails, 7 a round trip that differs.
#include <cstdio>
#include <filesystem>
#include <string>

#include "formats/support/file_io.h"
#include "lib/scene/scene_compare.h"
#include "lib/scene/scene_io.h"

namespace {

namespace fs = std::filesystem;
using lodbake::Bytes;
using lodbake::Result;
using lodbake::Scene;

int fail(const std::string& what, const lodbake::Status& status) {
  std::fprintf(stderr, "Error: %s: %s\n", what.c_str(), status.message().c_str());
  return static_cast<int>(status.kind());
}

Result<Scene> read_scene(const fs::path& path) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, lodbake::read_file(path.string()));
  lodbake::SceneResources resources;
  resources.folder = path.parent_path().string();
  lodbake::ImportReport report;
  return lodbake::read_gltf_scene(bytes.data(), bytes.size(), resources, &report);
}

lodbake::Status write(const fs::path& path, const Bytes& bytes) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  return lodbake::write_file_atomic(path.string(), bytes);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: scene_copy ASSET OUTDIR\n");
    return 1;
  }
  const fs::path input = argv[1];
  const fs::path out = argv[2];
  const bool input_glb = input.extension() == ".glb";
  const bool input_gltf = input.extension() == ".gltf";
  lodbake::ImportReport imported;
  Result<Scene> scene = lodbake::read_scene_file(input.string(), {}, &imported);
  if (!scene.is_ok()) return fail(input.string(), scene.status());

  lodbake::SceneWriteReport report;
  const std::string stem = input.stem().string();
  Result<Bytes> glb = lodbake::write_scene_glb(scene.value(), &report);
  if (!glb.is_ok()) return fail("writing GLB", glb.status());
  const fs::path glb_path = out / (stem + ".glb");
  lodbake::Status status = write(glb_path, glb.value());
  if (!status.is_ok()) return fail(glb_path.string(), status);

  auto files = lodbake::write_scene_gltf(scene.value(), stem + ".gltf", &report);
  if (!files.is_ok()) return fail("writing glTF", files.status());
  for (const lodbake::SceneOutputFile& file : files.value()) {
    status = write(out / stem / file.name, file.bytes);
    if (!status.is_ok()) return fail((out / stem / file.name).string(), status);
  }
  for (const std::string& warning : report.warnings)
    std::fprintf(stderr, "Warning: %s\n", warning.c_str());

  const std::pair<fs::path, bool> outputs[] = {{glb_path, input_glb},
                                               {out / stem / (stem + ".gltf"), input_gltf}};
  int result = 0;
  for (const auto& [path, same_format] : outputs) {
    Result<Scene> back = read_scene(path);
    if (!back.is_ok()) return fail(path.string(), back.status());
    lodbake::SceneCompareOptions options;
    options.image_storage = same_format;
    const std::string difference =
        lodbake::first_scene_difference(scene.value(), back.value(), options);
    if (!difference.empty()) {
      std::fprintf(stderr, "Error: %s reads back differently: %s\n", path.c_str(),
                   difference.c_str());
      result = 7;
    }
  }
  return result;
}
