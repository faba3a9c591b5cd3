// lodbake-replay's per-frame pieces (frame_support.h).
#include "tools/replay/frame_support.h"

namespace lodbake::cli::replay {

Result<std::vector<CameraFrame>> read_path(const Request& request, const BoundingSphere& sphere,
                                           std::string* failed_file) {
  if (request.path == "scan" || request.path == "orbit")
    return builtin_path(request.path, sphere, request.fov_degrees);
  *failed_file = request.path;
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, read_file(request.path, uint64_t{1} << 30));
  return parse_camera_path(bytes.data(), bytes.size());
}

Status frame_failure(size_t i, const Status& status) {
  return Status(status.kind(), "frame " + std::to_string(i) + ": " + status.message());
}

Status invalid_mesh(size_t i, const std::vector<std::string>& problems) {
  if (problems.empty()) return Status::ok();
  std::string message = "frame " + std::to_string(i) + ": invalid mesh: " + problems[0];
  for (size_t k = 1; k < problems.size(); ++k)
    message += "; " + problems[k];
  return Status(ErrorKind::kValidation, message);
}

}  // namespace lodbake::cli::replay
