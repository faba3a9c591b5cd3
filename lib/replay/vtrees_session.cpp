// The vertex-tree sessions of mode vtrees (To, Lau & Green 2001, section
// 5), in one process and over a transport. Choices: the client sends its
// view every frame (it has no refinement data to decide by itself what it
// lacks, so the server, as in the paper, decides); the server always
// answers, with an empty frame message when the list does not move. Over a
// transport the server speaks first (trees, then scene: the client needs
// nothing but the address and its camera path) and closes each answer with
// an end of answer, since a client reading a socket cannot tell the last
// frame message of an answer by itself; no hello (nothing to negotiate:
// every session starts at the base) and no resume (a client that loses
// its connection starts a new session). The one-process session keeps
// its plain channel and does without scene and end-of-answer messages, so
// its byte counts are the paper's records and framing alone.
#include "lib/replay/vtrees_session.h"

#include <chrono>
#include <new>
#include <string>

namespace lodbake {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// What the client received between `before` and `after`, and its list.
VtreesFrameStats received_stats(const VtreesReceived& before, const VtreesClient& client) {
  const VtreesReceived& after = client.received();
  VtreesFrameStats stats;
  stats.messages = after.messages - before.messages;
  stats.left_records = after.left_records - before.left_records;
  stats.right_records = after.right_records - before.right_records;
  stats.left_bits = after.left_bits - before.left_bits;
  stats.right_bits = after.right_bits - before.right_bits;
  stats.traces = after.traces - before.traces;
  stats.trace_bits = after.trace_bits - before.trace_bits;
  stats.trace_updates = after.trace_updates - before.trace_updates;
  stats.downs = after.downs - before.downs;
  stats.ups = after.ups - before.ups;
  stats.visible = client.visible_count();
  return stats;
}

ViewRequest frame_request(const CameraFrame& camera, const VtreesReplayOptions& options,
                          const BoundingSphere& sphere) {
  return view_request_for(camera, options.viewport, options.viewport.near_fraction * sphere.radius,
                          options.tolerance_pixels);
}

}  // namespace

Result<VtreesSession> VtreesSession::create(const VtreesDatabase& db,
                                            const VtreesReplayOptions& options) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(VtreesServerSession server,
                             VtreesServerSession::create(db, options.max_items_per_message));
    LODBAKE_ASSIGN_OR_RETURN(Bytes trees, db.trees_message());
    MessageChannel channel;
    channel.send_down(std::move(trees));
    Bytes received;
    channel.receive_down(&received);
    const auto start = std::chrono::steady_clock::now();
    LODBAKE_ASSIGN_OR_RETURN(VtreesClient client,
                             VtreesClient::create(received.data(), received.size()));
    const double ms = ms_since(start);
    VtreesSession session(options, std::move(server), std::move(client));
    session.trees_bytes_ = channel.downlink_bytes();
    session.channel_ = std::move(channel);
    session.trees_ms_ = ms;
    session.triangles_ = session.client_.triangles();
    return session;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory starting a vertex-tree session");
  }
}

Result<VtreesFrameStats> VtreesSession::frame(const CameraFrame& camera,
                                              const BoundingSphere& sphere) {
  return step(frame_request(camera, options_, sphere));
}

Result<VtreesFrameStats> VtreesSession::step(const ViewRequest& request) {
  try {
    const uint64_t up0 = channel_.uplink_bytes(), down0 = channel_.downlink_bytes();
    const VtreesReceived before = client_.received();
    channel_.send_up(encode_view_request(request));
    Bytes up;
    while (channel_.receive_up(&up)) {
      LODBAKE_ASSIGN_OR_RETURN(std::vector<Bytes> answer, server_.answer(up.data(), up.size()));
      for (Bytes& m : answer)
        channel_.send_down(std::move(m));
    }
    Bytes down;
    const auto start = std::chrono::steady_clock::now();
    while (channel_.receive_down(&down))
      LODBAKE_RETURN_IF_ERROR(client_.receive(down.data(), down.size()));
    const double reconstruct_ms = ms_since(start);
    const auto select = std::chrono::steady_clock::now();
    triangles_ = client_.triangles();
    VtreesFrameStats stats = received_stats(before, client_);
    stats.select_ms = ms_since(select);
    stats.reconstruct_ms = reconstruct_ms;
    stats.uplink_bytes = channel_.uplink_bytes() - up0;
    stats.downlink_bytes = channel_.downlink_bytes() - down0;
    stats.triangles = triangles_.size();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory in a vertex-tree frame");
  }
}

Result<VtreesServerConnection> VtreesServerConnection::create(const VtreesDatabase& db,
                                                              size_t max_items_per_message) {
  LODBAKE_ASSIGN_OR_RETURN(VtreesServerSession session,
                           VtreesServerSession::create(db, max_items_per_message));
  return VtreesServerConnection(db, std::move(session));
}

Status VtreesServerConnection::start(StreamTransport* out) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(Bytes trees, db_->trees_message());
    LODBAKE_RETURN_IF_ERROR(out->send(trees));
    return out->send(encode_vtrees_scene(db_->sphere));
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory sending the trees message");
  }
}

Status VtreesServerConnection::handle(const Bytes& message, StreamTransport* out) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(StreamMessageType type,
                             stream_message_type(message.data(), message.size()));
    if (type != StreamMessageType::kView) {
      return invalid_input("stream message: type " + std::to_string(static_cast<int>(type)) +
                           " where a view request was expected (a vtrees server takes views only)");
    }
    LODBAKE_ASSIGN_OR_RETURN(std::vector<Bytes> answer,
                             session_.answer(message.data(), message.size()));
    ++requests_;
    for (const Bytes& m : answer)
      LODBAKE_RETURN_IF_ERROR(out->send(m));
    frame_messages_ += answer.size();
    return out->send(encode_vtrees_end_of_answer(static_cast<uint32_t>(answer.size())));
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory answering a view");
  }
}

Status VtreesServerConnection::serve(StreamTransport* t) {
  t->set_max_payload(kViewRequestPayloadBytes);
  LODBAKE_RETURN_IF_ERROR(start(t));
  for (;;) {
    bool closed = false;
    LODBAKE_ASSIGN_OR_RETURN(Bytes message, t->receive(&closed));
    if (closed) return Status::ok();
    LODBAKE_RETURN_IF_ERROR(handle(message, t));
  }
}

Result<VtreesClientSession> VtreesClientSession::start(StreamTransport* t,
                                                       const VtreesReplayOptions& options,
                                                       StreamPump pump) {
  try {
    VtreesClientSession s;
    s.t_ = t;
    s.pump_ = std::move(pump);
    s.options_ = options;
    const uint64_t down0 = t->bytes_received();
    bool closed = false;
    Result<Bytes> first = t->receive(&closed);
    if (!first.is_ok()) {
      // A mode vtrees server speaks first; a silent one may be mode stream's.
      return Status(first.status().kind(),
                    "waiting for the trees message (a mode vtrees server "
                    "sends it at once): " +
                        first.status().message());
    }
    if (closed) return io_error("the server closed the connection before the trees message");
    const Bytes trees = std::move(first).value();
    const auto start = std::chrono::steady_clock::now();
    LODBAKE_ASSIGN_OR_RETURN(VtreesClient client, VtreesClient::create(trees.data(), trees.size()));
    s.trees_ms_ = ms_since(start);
    s.client_ = std::make_unique<VtreesClient>(std::move(client));
    s.trees_bytes_ = trees.size();
    LODBAKE_ASSIGN_OR_RETURN(Bytes scene, t->receive(&closed));
    if (closed) return io_error("the server closed the connection before the scene message");
    LODBAKE_ASSIGN_OR_RETURN(s.sphere_, decode_vtrees_scene(scene.data(), scene.size()));
    s.start_down_ = t->bytes_received() - down0;
    s.triangles_ = s.client_->triangles();
    return s;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory starting a vertex-tree session");
  }
}

Result<VtreesFrameStats> VtreesClientSession::frame(const CameraFrame& camera) {
  return step(frame_request(camera, options_, sphere_));
}

Result<VtreesFrameStats> VtreesClientSession::step(const ViewRequest& request) {
  try {
    const uint64_t up0 = t_->bytes_sent(), down0 = t_->bytes_received();
    const VtreesReceived before = client_->received();
    LODBAKE_RETURN_IF_ERROR(t_->send(encode_view_request(request)));
    if (pump_) LODBAKE_RETURN_IF_ERROR(pump_());
    double reconstruct_ms = 0;
    uint32_t frames = 0;
    for (;;) {
      bool closed = false;
      LODBAKE_ASSIGN_OR_RETURN(Bytes down, t_->receive(&closed));
      if (closed) return io_error("the server closed the connection before its answer ended");
      LODBAKE_ASSIGN_OR_RETURN(VtreesMessageType type,
                               vtrees_message_type(down.data(), down.size()));
      if (type == VtreesMessageType::kEndOfAnswer) {
        LODBAKE_ASSIGN_OR_RETURN(uint32_t count,
                                 decode_vtrees_end_of_answer(down.data(), down.size()));
        if (count != frames) {
          return invalid_input("vtrees message: the end of answer counts " + std::to_string(count) +
                               " frame messages, " + std::to_string(frames) + " came");
        }
        break;
      }
      if (type != VtreesMessageType::kFrame) {
        return invalid_input("vtrees message: type " + std::to_string(static_cast<int>(type)) +
                             " inside an answer");
      }
      const auto start = std::chrono::steady_clock::now();
      LODBAKE_RETURN_IF_ERROR(client_->receive(down.data(), down.size()));
      reconstruct_ms += ms_since(start);
      ++frames;
    }
    const auto select = std::chrono::steady_clock::now();
    triangles_ = client_->triangles();
    VtreesFrameStats stats = received_stats(before, *client_);
    stats.select_ms = ms_since(select);
    stats.reconstruct_ms = reconstruct_ms;
    stats.uplink_bytes = t_->bytes_sent() - up0;
    stats.downlink_bytes = t_->bytes_received() - down0;
    stats.triangles = triangles_.size();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory in a vertex-tree frame");
  }
}

Result<std::vector<VtreesServedClient>> serve_vtrees_clients(const VtreesDatabase& db,
                                                             TcpListener* listener, size_t clients,
                                                             size_t max_items_per_message,
                                                             const TcpOptions& tcp) {
  std::vector<VtreesServedClient> served(clients);
  LODBAKE_RETURN_IF_ERROR(
      serve_connections(listener, clients, tcp, kStreamMessages,
                        [&](size_t k, std::unique_ptr<StreamTransport> transport) {
                          VtreesServedClient* out = &served[k];
                          try {
                            Result<VtreesServerConnection> connection =
                                VtreesServerConnection::create(db, max_items_per_message);
                            if (!connection.is_ok()) {
                              out->status = connection.status();
                              return;
                            }
                            VtreesServerConnection& c = connection.value();
                            out->status = c.serve(transport.get());
                            transport->close();
                            out->uplink_bytes = transport->bytes_received();
                            out->downlink_bytes = transport->bytes_sent();
                            out->requests = c.requests();
                            out->messages = c.frame_messages();
                            out->visible = c.session().list().visible_count();
                            out->state_bytes = c.session().state_bytes();
                            out->sent_nodes = c.session().sent_nodes();
                          } catch (const std::bad_alloc&) {
                            out->status = runtime_error("out of memory serving a client");
                          }
                        }));
  return served;
}

}  // namespace lodbake
