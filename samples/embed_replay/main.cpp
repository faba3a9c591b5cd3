// embed_replay FILE.lbk [scan|orbit]: what an engine embedding lodbake's
// replay runtime does with a container from lodbake-hierarchy. It opens the
// container (every codec lodbake-pack may have chosen is decoded), loads the
// balanced vertex hierarchy (BASE + VHIE + RFIN), and adapts the mesh to each
// camera of a built-in path with the default view criteria, printing the
// frame's triangle count: the same numbers as `lodbake-replay FILE --mode
// vhier --path scan|orbit --csv`'s triangles column.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "formats/sections/open_container.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/structure_loading.h"
#include "lib/replay/vhier_replay.h"

namespace {

// The Status's kind is the lodbake exit code (2 I/O, 3 invalid, 5 unsupported).
int fail(const std::string& file, const lodbake::Status& status) {
  std::fprintf(stderr, "embed_replay: error: %s: %s\n", file.c_str(), status.message().c_str());
  return static_cast<int>(status.kind());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: embed_replay FILE.lbk [scan|orbit]\n");
    return 1;
  }
  const std::string file_name = argv[1];
  const std::string path_name = argc == 3 ? argv[2] : "scan";

  lodbake::Result<lodbake::OpenedContainer> file = lodbake::open_container_file(file_name);
  if (!file.is_ok()) return fail(file_name, file.status());
  lodbake::Result<uint32_t> group =
      lodbake::structure_group(file.value(), lodbake::ReplayStructure::kVhier);
  if (!group.is_ok()) return fail(file_name, group.status());
  lodbake::Result<lodbake::VhierStructure> loaded =
      lodbake::load_vhier_structure(file.value().decoded(), group.value());
  if (!loaded.is_ok()) return fail(file_name, loaded.status());
  lodbake::VhierStructure& vhier = loaded.value();

  // The built-in paths are placed around the model's bounding sphere.
  const lodbake::BoundingSphere sphere = lodbake::bounding_sphere(vhier.h->position);
  const float fov_degrees = 60;
  lodbake::Result<std::vector<lodbake::CameraFrame>> path =
      lodbake::builtin_path(path_name, sphere, fov_degrees);
  if (!path.is_ok()) return fail(path_name, path.status());

  const lodbake::VhierReplayOptions options;  // 1024 x 768, 1 pixel of tolerance
  size_t splits = 0;
  size_t collapses = 0;
  size_t max_triangles = 0;
  std::printf("frame,triangles\n");
  for (size_t i = 0; i < path.value().size(); ++i) {
    lodbake::Result<lodbake::VhierFrameStats> frame = lodbake::adapt_vhier_frame(
        &*vhier.refiner, *vhier.h, vhier.data, sphere, path.value()[i], options);
    if (!frame.is_ok()) return fail(file_name, frame.status());
    std::printf("%zu,%zu\n", i, frame.value().triangles);
    splits += frame.value().splits;
    collapses += frame.value().collapses;
    max_triangles = std::max(max_triangles, frame.value().triangles);
  }
  std::fprintf(stderr,
               "embed_replay: %zu frames, %zu splits, %zu collapses, at most %zu triangles\n",
               path.value().size(), splits, collapses, max_triangles);
  return 0;
}
