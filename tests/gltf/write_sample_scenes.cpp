// write_sample_scenes OUTDIR: writes each hand-built sample scene
// (sample_scenes.h) as OUTDIR/NAME.glb and as OUTDIR/NAME/NAME.gltf with its
// .bin and images, for Khronos's validator (tests/npm/validate.mjs).
#include <cstdio>
#include <filesystem>
#include <string>

#include "lib/scene/scene_io.h"
#include "tests/gltf/sample_scenes.h"

namespace {

bool write(const std::filesystem::path& path, const lodbake::Bytes& bytes) {
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  const lodbake::Status status = lodbake::write_file_atomic(path.string(), bytes);
  if (!status.is_ok())
    std::fprintf(stderr, "Error: %s: %s\n", path.c_str(), status.message().c_str());
  return status.is_ok();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_sample_scenes OUTDIR\n");
    return 1;
  }
  const std::filesystem::path out = argv[1];
  for (const lodbake::sample_scenes::NamedScene& sample : lodbake::sample_scenes::all()) {
    lodbake::SceneWriteReport report;
    lodbake::Result<lodbake::Bytes> glb = lodbake::write_scene_glb(sample.scene, &report);
    if (!glb.is_ok()) {
      std::fprintf(stderr, "Error: %s.glb: %s\n", sample.name.c_str(),
                   glb.status().message().c_str());
      return 3;
    }
    if (!write(out / (sample.name + ".glb"), glb.value())) return 2;
    auto files = lodbake::write_scene_gltf(sample.scene, sample.name + ".gltf", &report);
    if (!files.is_ok()) {
      std::fprintf(stderr, "Error: %s.gltf: %s\n", sample.name.c_str(),
                   files.status().message().c_str());
      return 3;
    }
    for (const lodbake::SceneOutputFile& file : files.value())
      if (!write(out / sample.name / file.name, file.bytes)) return 2;
    for (const std::string& warning : report.warnings)
      std::fprintf(stderr, "Warning: %s: %s\n", sample.name.c_str(), warning.c_str());
  }
  return 0;
}
