// Mode stream of the replay runtime (issue 9): the client's side of a
// streaming session over any transport (lib/replay/stream_transport.h), a
// server session and its client in one process over an in-memory transport
// that counts every byte both ways, a multi-client TCP server, and the
// view-independent baseline the paper compares with (section 8, Figure 9).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/stream_client.h"
#include "lib/replay/stream_server.h"
#include "lib/replay/stream_transport.h"

namespace lodbake {

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
  /// The server session's memory (one-process sessions only; a remote
  /// client does not know it).
  StreamServerMemory server;
};

/// Runs after every message the client sends: in one process, it lets the
/// server handle what was sent before the client reads the answer.
using StreamPump = std::function<Status()>;

/// The client's side of a session over any transport (section 5.1's main
/// loop): a hello answered by the base and scene messages, then per frame
/// the client adapts with what it has, sends its view when a needed split
/// is missing, applies the answer and adapts again. After a lost
/// connection, resume() continues on a new one.
class StreamClientSession {
 public:
  /// Sends the hello over `t` (which must outlive its use) and reads the
  /// base and scene messages.
  static Result<StreamClientSession> start(StreamTransport* t, const StreamReplayOptions& options,
                                           StreamPump pump = {});
  /// Continues over a new connection `t`: sends the resume message (the
  /// partial hierarchy's leaves). Packets of an answer cut short stay
  /// applied; the next frame asks for what is still missing.
  Status resume(StreamTransport* t, StreamPump pump = {});

  /// One camera, the near plane at viewport.near_fraction of the scene's radius.
  Result<StreamFrameStats> frame(const CameraFrame& camera);
  /// The same for a view request given as is (tests: tolerance 0).
  Result<StreamFrameStats> step(const ViewRequest& request);

  const StreamClient& client() const { return *client_; }
  /// From the scene message: what the client places its camera path around.
  const BoundingSphere& sphere() const { return sphere_; }
  uint64_t base_bytes() const { return base_bytes_; }
  /// The opening exchange: the hello up, the base and scene messages down.
  uint64_t start_uplink_bytes() const { return start_up_; }
  uint64_t start_downlink_bytes() const { return start_down_; }
  /// Connections used (1 + resumes).
  size_t connections() const { return connections_; }

 private:
  StreamClientSession() = default;
  Status send(const Bytes& message);
  StreamTransport* t_ = nullptr;
  StreamPump pump_;
  StreamReplayOptions options_;
  std::unique_ptr<StreamClient> client_;
  BoundingSphere sphere_;
  uint64_t base_bytes_ = 0, start_up_ = 0, start_down_ = 0;
  size_t connections_ = 1;
};

/// One server session and its client in one process, joined by an
/// in-memory transport that counts every byte both ways.
class StreamSession {
 public:
  /// Creates the server connection and the client and runs the opening
  /// exchange. `db` must outlive the session.
  static Result<StreamSession> create(const StreamHierarchy& db,
                                      const StreamReplayOptions& options);

  /// One camera (`sphere` places the near plane).
  Result<StreamFrameStats> frame(const CameraFrame& camera, const BoundingSphere& sphere);
  Result<StreamFrameStats> step(const ViewRequest& request);

  const StreamClient& client() const { return client_->client(); }
  const StreamServerSession& server() const { return server_->session(); }
  /// The base message alone, and the opening exchange's bytes both ways.
  uint64_t base_bytes() const { return client_->base_bytes(); }
  uint64_t start_uplink_bytes() const { return client_->start_uplink_bytes(); }
  uint64_t start_downlink_bytes() const { return client_->start_downlink_bytes(); }

 private:
  StreamSession() = default;
  std::unique_ptr<StreamTransport> client_end_, server_end_;
  std::unique_ptr<StreamServerConnection> server_;
  std::unique_ptr<StreamClientSession> client_;
};

/// What one connection of serve_stream_clients() did.
struct StreamServedClient {
  Status status;  ///< ok when the client closed between two messages
  uint64_t uplink_bytes = 0;
  uint64_t downlink_bytes = 0;
  size_t requests = 0;
  size_t packets = 0;  ///< vsplit packets sent
  size_t resumed = 0;  ///< splits the client held when it resumed
  bool started = false;
  StreamServerMemory memory;
  std::vector<uint32_t> sent;
};

/// Accepts `clients` connections on `listener` and serves each on its own
/// thread with its own session (active tags, window) over the shared
/// database; returns when every connection has ended. A connection's own
/// failure (a malformed message, a dead peer) is in its entry; the result
/// fails only when a client does not connect within the accept timeout
/// (after the connections already accepted ended).
Result<std::vector<StreamServedClient>> serve_stream_clients(const StreamHierarchy& db,
                                                             TcpListener* listener, size_t clients,
                                                             const StreamServerOptions& options,
                                                             const TcpOptions& tcp = TcpOptions());

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
