// Mode vtrees of the replay runtime (issue 9): a vertex-tree server session
// and its client in one process, joined by mode stream's in-memory channel
// (every byte counted both ways), driven frame by frame along a camera path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/support/status.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/message_channel.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/vtrees_client.h"
#include "lib/replay/vtrees_server.h"

namespace lodbake {

struct VtreesReplayOptions {
  Viewport viewport;
  /// Screen-space tolerance in pixels of the viewport's height; 0 asks for
  /// every split.
  float tolerance_pixels = 1.0f;
  size_t max_items_per_message = kMaxVtreesItems;
};

/// One frame: what travelled, what the client did with it.
struct VtreesFrameStats {
  uint64_t uplink_bytes = 0;
  uint64_t downlink_bytes = 0;
  size_t messages = 0;  ///< downlink frame messages
  size_t left_records = 0, right_records = 0;
  uint64_t left_bits = 0, right_bits = 0;  ///< traces included
  size_t traces = 0;
  uint64_t trace_bits = 0;
  size_t trace_updates = 0, downs = 0, ups = 0;
  size_t visible = 0;         ///< the client's visible vertices
  size_t triangles = 0;       ///< the client's triangle list
  double reconstruct_ms = 0;  ///< the client decoding and applying the frame's messages
  double select_ms = 0;       ///< the client selecting its triangles
};

class VtreesSession {
 public:
  /// The server session and the client, which receives the trees message
  /// (downlink bytes before the first frame). `db` must outlive the session.
  static Result<VtreesSession> create(const VtreesDatabase& db, const VtreesReplayOptions& options);

  /// One camera: the client sends its view, the server answers, the client
  /// applies the answer and selects its triangles. `sphere` places the near
  /// plane (viewport.near_fraction of its radius).
  Result<VtreesFrameStats> frame(const CameraFrame& camera, const BoundingSphere& sphere);
  /// The same for a view request given as is (tests: tolerance 0).
  Result<VtreesFrameStats> step(const ViewRequest& request);

  const VtreesClient& client() const { return client_; }
  const VtreesServerSession& server() const { return server_; }
  const MessageChannel& channel() const { return channel_; }
  /// The client's triangles after the last frame.
  const std::vector<Triangle>& triangles() const { return triangles_; }
  uint64_t trees_bytes() const { return trees_bytes_; }
  /// Time the client took to start from the trees message.
  double trees_reconstruct_ms() const { return trees_ms_; }

 private:
  VtreesSession(const VtreesReplayOptions& options, VtreesServerSession server, VtreesClient client)
      : options_(options), server_(std::move(server)), client_(std::move(client)) {}
  VtreesReplayOptions options_;
  VtreesServerSession server_;
  VtreesClient client_;
  MessageChannel channel_;
  std::vector<Triangle> triangles_;
  uint64_t trees_bytes_ = 0;
  double trees_ms_ = 0;
};

}  // namespace lodbake
