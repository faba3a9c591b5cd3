// Mode stream of the replay runtime (issue 9): a streaming server session
// and its client in one process, joined by an in-memory channel that counts
// every byte both ways, driven frame by frame along a camera path; and the
// view-independent baseline the paper compares with (section 8, Figure 9).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/stream_client.h"
#include "lib/replay/stream_server.h"

namespace lodbake {

/// Two message queues, client -> server (uplink) and server -> client
/// (downlink), with their byte and message counts.
class StreamChannel {
 public:
  void send_up(Bytes message);
  void send_down(Bytes message);
  /// False when the queue is empty.
  bool receive_up(Bytes* message);
  bool receive_down(Bytes* message);
  uint64_t uplink_bytes() const { return up_bytes_; }
  uint64_t downlink_bytes() const { return down_bytes_; }
  uint64_t uplink_messages() const { return up_messages_; }
  uint64_t downlink_messages() const { return down_messages_; }

 private:
  std::deque<Bytes> up_;
  std::deque<Bytes> down_;
  uint64_t up_bytes_ = 0, down_bytes_ = 0, up_messages_ = 0, down_messages_ = 0;
};

struct StreamReplayOptions {
  Viewport viewport;
  /// Screen-space tolerance in pixels of the viewport's height; 0 asks for
  /// every split.
  float tolerance_pixels = 1.0f;
  /// The client's adapt passes per request.
  size_t max_passes = 64;
  /// Requests a frame may send (one is always enough when the server
  /// completes its answers; more are counted as a failure of that rule).
  size_t max_requests_per_frame = 4;
  StreamServerOptions server;
};

struct StreamFrameStats {
  uint64_t uplink_bytes = 0;
  uint64_t downlink_bytes = 0;
  size_t requests = 0;  ///< view requests sent
  size_t packets = 0;   ///< vsplit packets received
  size_t splits = 0;    ///< client vsplits (received or not this frame)
  size_t collapses = 0;
  size_t passes = 0;
  size_t missing = 0;  ///< splits still missing at the end of the frame
  size_t triangles = 0;
  size_t front_size = 0;  ///< the client's active nodes
  StreamServerMemory server;
};

class StreamSession {
 public:
  /// Creates the server session and the client, and sends the base message
  /// (downlink bytes before the first frame). `db` must outlive the session.
  static Result<StreamSession> create(const StreamHierarchy& db,
                                      const StreamReplayOptions& options);

  /// One camera: the client adapts with what it has, sends its view when a
  /// needed split is missing, applies the answer and adapts again.
  /// `sphere` places the near plane (viewport.near_fraction of its radius).
  Result<StreamFrameStats> frame(const CameraFrame& camera, const BoundingSphere& sphere);
  /// The same for a view request given as is (tests: tolerance 0).
  Result<StreamFrameStats> step(const ViewRequest& request);

  const StreamClient& client() const { return client_; }
  const StreamServerSession& server() const { return *server_; }
  const StreamChannel& channel() const { return channel_; }
  uint64_t base_bytes() const { return base_bytes_; }

 private:
  StreamSession(const StreamHierarchy& db, const StreamReplayOptions& options, StreamClient client);
  const StreamHierarchy* db_;
  StreamReplayOptions options_;
  std::unique_ptr<StreamServerSession> server_;
  StreamClient client_;
  StreamChannel channel_;
  uint64_t base_bytes_ = 0;
};

/// View-independent streaming of the same hierarchy's progressive mesh in
/// its fixed order (hierarchy_to_progressive_mesh()), with vsplit records of
/// the same size as the view-dependent packets (vsplit_packet_bits() of the
/// same node). `prefix` is the smallest prefix of that order holding every
/// split in `sent` (what the view-dependent client used: the PM client needs
/// at least these splits to show the same meshes, and with the prefix it
/// has them); bytes = base message + one vsplit message holding the prefix.
struct StreamBaseline {
  size_t pm_splits = 0;  ///< all splits of the PM
  size_t prefix = 0;
  uint64_t bytes = 0;        ///< base + header + count + ceil(prefix bits / 8)
  uint64_t full_bytes = 0;   ///< the same for the whole PM
  uint64_t prefix_bits = 0;  ///< the prefix's packet bits
  uint64_t sent_bits = 0;    ///< the packet bits of `sent` alone
};
Result<StreamBaseline> view_independent_baseline(const StreamHierarchy& db,
                                                 const std::vector<uint32_t>& sent,
                                                 uint64_t base_bytes);

}  // namespace lodbake
