// mesh_distance INPUT OUTPUT...: the Hausdorff and mean distance of each
// OUTPUT to INPUT, relative to INPUT's diagonal, with the metrics the
// simplifier reports (lib/metrics): for results written without them, such
// as an out-of-core run's (tests/bench/scaling.sh).
#include <cstdio>

#include "lib/meshio/import_report.h"
#include "lib/meshio/mesh_import.h"
#include "lib/metrics/surface_distance.h"

int main(int argc, char** argv) {
  using namespace lodbake;
  if (argc < 3) {
    std::fprintf(stderr, "usage: mesh_distance INPUT OUTPUT...\n");
    return 1;
  }
  ImportReport report;
  Result<TriangleMesh> input = import_mesh_file(argv[1], &report);
  if (!input.is_ok()) {
    std::fprintf(stderr, "mesh_distance: %s: %s\n", argv[1], input.status().message().c_str());
    return input.status().kind() == ErrorKind::kIo ? 2 : 3;
  }
  for (int i = 2; i < argc; ++i) {
    Result<TriangleMesh> output = import_mesh_file(argv[i], &report);
    if (!output.is_ok()) {
      std::fprintf(stderr, "mesh_distance: %s: %s\n", argv[i], output.status().message().c_str());
      return 3;
    }
    Result<SurfaceDistance> d = measure_surface_distance(input.value(), output.value());
    if (!d.is_ok()) {
      std::fprintf(stderr, "mesh_distance: %s: %s\n", argv[i], d.status().message().c_str());
      return 4;
    }
    std::printf("%s hausdorff %.6g mean %.6g triangles %zu\n", argv[i],
                d.value().hausdorff_relative, d.value().mean_relative,
                output.value().triangle_count());
  }
  return 0;
}
