// lodbake-replay's per-frame pieces shared by the camera-driven modes
// (vhier, dag, fan, stream, vtrees): the camera path a run replays and the
// failure of one frame, numbered, as every mode reports it.
#pragma once

#include <string>
#include <vector>

#include "formats/support/status.h"
#include "lib/replay/camera_path.h"
#include "tools/replay/replay_request.h"

namespace lodbake::cli::replay {

/// --path: the built-in scan or orbit around `sphere`, or the camera path
/// FILE; on failure `*failed_file` names the file that failed (empty for a
/// built-in path).
Result<std::vector<CameraFrame>> read_path(const Request& request, const BoundingSphere& sphere,
                                           std::string* failed_file);

/// "frame I: MESSAGE", of the status' kind.
Status frame_failure(size_t i, const Status& status);

/// --validate's failure of frame I: "frame I: invalid mesh: P1; P2 ...",
/// kValidation; ok when `problems` is empty.
Status invalid_mesh(size_t i, const std::vector<std::string>& problems);

}  // namespace lodbake::cli::replay
