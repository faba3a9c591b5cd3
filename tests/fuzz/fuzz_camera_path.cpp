// Fuzz target: the camera-path CSV reader must reject or accept any bytes
// without reading past them, and every accepted frame must be finite with a
// fov in (0, 180) and produce finite view parameters.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "lib/replay/camera_path.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  Result<std::vector<CameraFrame>> path = parse_camera_path_csv(data, size);
  if (!path.is_ok()) return 0;
  if (path.value().empty()) std::abort();
  for (const CameraFrame& f : path.value()) {
    if (!(f.fov_degrees > 0 && f.fov_degrees < 180)) std::abort();
    const ViewParameters view = view_parameters(f, Viewport(), 0.01f, 1.0f);
    if (!std::isfinite(view.kappa) || view.kappa < 0) std::abort();
  }
  return 0;
}
