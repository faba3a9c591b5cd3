// The view of a streaming session (Kim, Lee and Kobbelt 2005, section 5.3):
// a camera as the client's view request (4x4 modelview, fovy, aspect,
// tolerance), and the request as Hoppe's view parameters. Client and server
// both evaluate qrefine() on the parameters of the *decoded* request, so
// they agree bit for bit on which splits a view needs.
#pragma once

#include "formats/mesh/vertex_hierarchy.h"
#include "lib/hierarchy/view_criteria.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/stream_packets.h"

namespace lodbake {

struct StreamView {
  ViewParameters params;
  /// Tolerance 0: every internal node is to be split, whatever the view.
  bool refine_all = false;
};

/// The request for one camera: gluLookAt's modelview, the viewport's aspect,
/// tolerance = tolerance_pixels / viewport height (0 stays 0).
ViewRequest view_request_for(const CameraFrame& frame, const Viewport& viewport,
                             float near_distance, float tolerance_pixels);

/// The frustum (near and four side planes, no far plane, as
/// view_parameters()), the eye (the modelview's inverse applied to the
/// origin) and kappa = 2 tolerance tan(fovy / 2).
/// \pre `request` passed decode_view_request()'s checks.
StreamView stream_view(const ViewRequest& request);

/// qrefine() under the stream's view; true for any node when refine_all.
/// Callers ask only about internal nodes of the complete hierarchy.
inline bool stream_qrefine(const StreamView& view, const NodeRefinement& data,
                           const Vec3f& position) {
  return view.refine_all || qrefine(data, position, view.params);
}

}  // namespace lodbake
