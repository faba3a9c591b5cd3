// Fuzz target: the camera-path readers (CSV and JSON) must reject or accept
// any bytes without reading past them, and every accepted frame must be
// finite with a fov in (0, 180) and produce finite view parameters.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "lib/replay/camera_path.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  for (auto* parse : {&parse_camera_path_csv, &parse_camera_path_json}) {
    Result<std::vector<CameraFrame>> path = parse(data, size);
    if (!path.is_ok()) continue;
    if (path.value().empty()) std::abort();
    for (const CameraFrame& f : path.value()) {
      if (!(f.fov_degrees > 0 && f.fov_degrees < 180)) std::abort();
      const ViewParameters view = view_parameters(f, Viewport(), 0.01f, 1.0f);
      if (!std::isfinite(view.kappa) || view.kappa < 0) std::abort();
    }
  }
  return 0;
}
