// Mode vtrees of the replay runtime (issue 9): a vertex-tree server session
// and its client in one process, joined by an in-memory channel (every byte
// counted both ways), driven frame by frame along a camera path; and the
// same client and server over any transport (lib/replay/stream_transport.h:
// an in-memory pipe or TCP on loopback), with a multi-client TCP server.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "formats/support/status.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/message_channel.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_transport.h"
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

/// The server's side of one connection. The server speaks first: the trees
/// message, then the scene message (the database's bounding sphere); then
/// each view request (mode stream's, the only message a client sends) is
/// answered by VtreesServerSession::answer()'s frame messages and an end of
/// answer giving their count. There is no hello (a new connection is a new
/// session at the base mesh) and no resume.
class VtreesServerConnection {
 public:
  /// `db` must outlive the connection. \pre 1 <= max_items_per_message <=
  /// kMaxVtreesItems.
  static Result<VtreesServerConnection> create(const VtreesDatabase& db,
                                               size_t max_items_per_message = kMaxVtreesItems);

  /// Sends the trees and scene messages through `out`.
  Status start(StreamTransport* out);
  /// Handles one whole uplink message (a view request), sending its answer
  /// through `out`; refuses anything else with kInvalidInput.
  Status handle(const Bytes& message, StreamTransport* out);
  /// Bounds `t`'s reads by a view request's size, start()s, then receives
  /// and handles messages until the client closes between two of them (ok)
  /// or anything fails (that status).
  Status serve(StreamTransport* t);

  const VtreesServerSession& session() const { return session_; }
  size_t requests() const { return requests_; }
  /// Frame messages sent (end-of-answer messages not counted).
  size_t frame_messages() const { return frame_messages_; }

 private:
  VtreesServerConnection(const VtreesDatabase& db, VtreesServerSession session)
      : db_(&db), session_(std::move(session)) {}
  const VtreesDatabase* db_;
  VtreesServerSession session_;
  size_t requests_ = 0;
  size_t frame_messages_ = 0;
};

/// The client's side of a session over any transport: it reads the trees
/// and scene messages, then per frame sends its view and applies the
/// answer up to its end.
class VtreesClientSession {
 public:
  /// Reads the opening over `t` (which must outlive its use; it should
  /// receive kVtreesMessages). `pump` runs after every message the client
  /// sends (one process: the server handles it before the client reads).
  static Result<VtreesClientSession> start(StreamTransport* t, const VtreesReplayOptions& options,
                                           StreamPump pump = {});

  /// One camera, the near plane at viewport.near_fraction of the scene's radius.
  Result<VtreesFrameStats> frame(const CameraFrame& camera);
  /// The same for a view request given as is (tests: tolerance 0).
  /// Refuses (kInvalidInput) an answer that is not frame messages closed by
  /// an end of answer with their count; after an error the session ends.
  Result<VtreesFrameStats> step(const ViewRequest& request);

  const VtreesClient& client() const { return *client_; }
  /// The client's triangles after the last frame.
  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// From the scene message.
  const BoundingSphere& sphere() const { return sphere_; }
  uint64_t trees_bytes() const { return trees_bytes_; }
  /// The opening: the trees and scene messages.
  uint64_t start_downlink_bytes() const { return start_down_; }
  double trees_reconstruct_ms() const { return trees_ms_; }

 private:
  VtreesClientSession() = default;
  StreamTransport* t_ = nullptr;
  StreamPump pump_;
  VtreesReplayOptions options_;
  std::unique_ptr<VtreesClient> client_;
  std::vector<Triangle> triangles_;
  BoundingSphere sphere_;
  uint64_t trees_bytes_ = 0, start_down_ = 0;
  double trees_ms_ = 0;
};

/// What one connection of serve_vtrees_clients() did.
struct VtreesServedClient {
  Status status;  ///< ok when the client closed between two messages
  uint64_t uplink_bytes = 0;
  uint64_t downlink_bytes = 0;
  size_t requests = 0;
  size_t messages = 0;  ///< frame messages sent
  size_t visible = 0;   ///< the server's visible vertex list at the end
  size_t state_bytes = 0;
  std::vector<uint32_t> sent_nodes;  ///< nodes whose records were sent
};

/// Accepts `clients` connections on `listener` and serves each on its own
/// thread with its own session (its own visible vertex list) over the
/// shared database; returns when every connection has ended. A
/// connection's own failure is in its entry; the result fails only when a
/// client does not connect within the accept timeout.
Result<std::vector<VtreesServedClient>> serve_vtrees_clients(
    const VtreesDatabase& db, TcpListener* listener, size_t clients,
    size_t max_items_per_message = kMaxVtreesItems, const TcpOptions& tcp = TcpOptions());

}  // namespace lodbake
