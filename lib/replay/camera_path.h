// Camera paths for replaying a view-dependent hierarchy (issue 8): the two
// built-in routes of Zheng and Chan's DAG paper (section 6), placed relative
// to the model's bounding sphere, a bounded CSV reader for recorded paths,
// and the conversion of one camera to Hoppe's view parameters.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/hierarchy/view_criteria.h"

namespace lodbake {

struct CameraFrame {
  Vec3f eye{};
  Vec3f target{};
  Vec3f up{0, 1, 0};
  float fov_degrees = 60;  ///< vertical field of view, in (0, 180)
};

struct BoundingSphere {
  Vec3f center{};
  float radius = 0;
};

/// Centre of the bounding box, radius = the largest distance of a point from
/// it (at least a tiny positive value, so an empty or one-point model still
/// gets a path).
BoundingSphere bounding_sphere(const std::vector<Vec3f>& points);

inline constexpr size_t kScanFrames = 180;
inline constexpr size_t kOrbitFrames = 194;

/// `scan`: 30 frames approaching along +z from 4 R to 1.25 R at the height
/// of the model's bottom (centre - 0.8 R), then 150 frames rising to
/// centre + 0.8 R at 1.25 R, always looking horizontally at the model's axis.
std::vector<CameraFrame> scan_path(const BoundingSphere& sphere, float fov_degrees);
/// `orbit`: 30 frames approaching from 4 R to 2 R, then 164 frames around the
/// +y axis through the centre, angle growing quadratically (increasing
/// speed) to two full turns.
std::vector<CameraFrame> orbit_path(const BoundingSphere& sphere, float fov_degrees);
/// `path` turned by `degrees` about the vertical (+y) axis through the
/// sphere's centre: eyes and targets rotate, up vectors stay. The streaming
/// modes' several clients use it to look at the model from around it.
std::vector<CameraFrame> turned_about_vertical(std::vector<CameraFrame> path,
                                               const BoundingSphere& sphere, float degrees);
/// "scan" or "orbit"; kInvalidInput naming the choices otherwise.
Result<std::vector<CameraFrame>> builtin_path(const std::string& name, const BoundingSphere& sphere,
                                              float fov_degrees);

inline constexpr size_t kMaxPathFrames = 1000000;
inline constexpr size_t kMaxPathLineBytes = 4096;

/// A recorded path: one frame per line, ten comma-separated numbers
/// eye x,y,z, target x,y,z, up x,y,z, vertical fov in degrees. Blank lines
/// and lines starting with '#' are skipped. Rejected with "line N: ..." for
/// a wrong field count, a field that is not a finite number, fov outside
/// (0, 180), eye = target, up zero or parallel to the view direction, a line
/// longer than kMaxPathLineBytes, more than kMaxPathFrames frames; an empty
/// path is rejected too.
Result<std::vector<CameraFrame>> parse_camera_path_csv(const uint8_t* data, size_t size);

/// A recorded path as JSON: an array of frames, or an object whose only key
/// "frames" holds one; each frame an object with exactly the keys "eye",
/// "target", "up" (arrays of 3 numbers) and "fov" (vertical, degrees), e.g.
/// [{"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 60}].
/// Frames pass the CSV reader's checks; rejected with "frame N: ..." or
/// "byte N: not valid JSON". Read by SAX events: memory is one frame per
/// frame whatever the document's nesting.
Result<std::vector<CameraFrame>> parse_camera_path_json(const uint8_t* data, size_t size);

/// JSON when the first non-blank byte is '[' or '{', CSV otherwise.
Result<std::vector<CameraFrame>> parse_camera_path(const uint8_t* data, size_t size);

struct Viewport {
  uint32_t width = 1024;
  uint32_t height = 768;
  /// Near plane distance as a fraction of the bounding-sphere radius.
  float near_fraction = 0.01f;
};

/// Hoppe's view parameters for one camera: the frustum's near and four side
/// planes (no far plane: the whole model stays a candidate), and kappa =
/// 2 tau tan(fov / 2) for a tolerance tau = tolerance_pixels / height.
ViewParameters view_parameters(const CameraFrame& frame, const Viewport& viewport,
                               float near_distance, float tolerance_pixels);

}  // namespace lodbake
