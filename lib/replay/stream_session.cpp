// The streaming session of mode stream (Kim, Lee and Kobbelt 2005, section
// 5.1's main loop), over any transport. Choices: a connection opens with
// the client's resume message (a hello when it holds nothing), so a server
// tells a new session from a resumed one by the first message alone, and a
// new one gets the base and the scene (the bounding sphere: the client
// needs nothing but the server's address and its camera path); one thread
// per connection on the TCP server, the database shared read-only; the client sends its view only
// when its adapt loop finds a needed split it has not received (so frames
// that the received hierarchy already satisfies cost no byte either way,
// the paper's second round of Figure 7); the view it adapts to is the
// decoded request itself, the same bytes the server evaluates. The
// baseline's PM order is hierarchy_to_progressive_mesh()'s, the order
// `lodbake-hierarchy` stores as VSPL.
#include "lib/replay/stream_session.h"

#include <algorithm>
#include <new>
#include <tuple>

#include "lib/hierarchy/hierarchy_to_pm.h"

namespace lodbake {

Status StreamClientSession::send(const Bytes& message) {
  LODBAKE_RETURN_IF_ERROR(t_->send(message));
  return pump_ ? pump_() : Status::ok();
}

Result<StreamClientSession> StreamClientSession::start(StreamTransport* t,
                                                       const StreamReplayOptions& options,
                                                       StreamPump pump) {
  try {
    StreamClientSession s;
    s.t_ = t;
    s.pump_ = std::move(pump);
    s.options_ = options;
    const uint64_t up0 = t->bytes_sent(), down0 = t->bytes_received();
    LODBAKE_RETURN_IF_ERROR(s.send(encode_hello()));
    bool closed = false;
    LODBAKE_ASSIGN_OR_RETURN(Bytes base, t->receive(&closed));
    if (closed) return io_error("the server closed the connection before the base message");
    LODBAKE_ASSIGN_OR_RETURN(StreamClient client, StreamClient::create(base.data(), base.size()));
    s.client_ = std::make_unique<StreamClient>(std::move(client));
    s.base_bytes_ = base.size();
    LODBAKE_ASSIGN_OR_RETURN(Bytes scene, t->receive(&closed));
    if (closed) return io_error("the server closed the connection before the scene message");
    LODBAKE_ASSIGN_OR_RETURN(s.sphere_, decode_scene_message(scene.data(), scene.size()));
    s.start_up_ = t->bytes_sent() - up0;
    s.start_down_ = t->bytes_received() - down0;
    return s;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory starting a streaming session");
  }
}

Status StreamClientSession::resume(StreamTransport* t, StreamPump pump) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes message, client_->reconnect());
  t_ = t;
  pump_ = std::move(pump);
  ++connections_;
  return send(message);
}

Result<StreamFrameStats> StreamClientSession::frame(const CameraFrame& camera) {
  return step(view_request_for(camera, options_.viewport,
                               options_.viewport.near_fraction * sphere_.radius,
                               options_.tolerance_pixels));
}

Result<StreamFrameStats> StreamClientSession::step(const ViewRequest& request) {
  try {
    const Bytes message = encode_view_request(request);
    LODBAKE_ASSIGN_OR_RETURN(ViewRequest decoded,
                             decode_view_request(message.data(), message.size()));
    const StreamView view = stream_view(decoded);
    StreamFrameStats stats;
    const uint64_t up0 = t_->bytes_sent(), down0 = t_->bytes_received();
    const size_t received0 = client_->received().size();
    for (;;) {
      LODBAKE_ASSIGN_OR_RETURN(StreamClientAdapt a, client_->adapt(view, options_.max_passes));
      stats.splits += a.splits;
      stats.collapses += a.collapses;
      stats.passes += a.passes;
      stats.missing = a.missing;
      if (a.missing == 0 || stats.requests >= options_.max_requests_per_frame) break;
      LODBAKE_RETURN_IF_ERROR(send(message));
      ++stats.requests;
      do {
        bool closed = false;
        LODBAKE_ASSIGN_OR_RETURN(Bytes down, t_->receive(&closed));
        if (closed) return io_error("the server closed the connection before its answer ended");
        LODBAKE_RETURN_IF_ERROR(client_->receive(down.data(), down.size()));
      } while (!client_->answer_complete());
    }
    stats.uplink_bytes = t_->bytes_sent() - up0;
    stats.downlink_bytes = t_->bytes_received() - down0;
    stats.packets = client_->received().size() - received0;
    stats.triangles = client_->refiner().triangle_count();
    stats.front_size = client_->refiner().front_size();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory in a streaming frame");
  }
}

Result<StreamSession> StreamSession::create(const StreamHierarchy& db,
                                            const StreamReplayOptions& options) {
  try {
    StreamSession s;
    std::tie(s.client_end_, s.server_end_) = make_memory_transport_pair(0);
    s.server_end_->set_max_payload(db.uplink_payload_limit());
    s.server_ = std::make_unique<StreamServerConnection>(db, options.server);
    StreamServerConnection* server = s.server_.get();
    StreamTransport* server_end = s.server_end_.get();
    // Single thread: the server handles each message as it is sent.
    StreamPump pump = [server, server_end]() -> Status {
      bool closed = false;
      LODBAKE_ASSIGN_OR_RETURN(Bytes up, server_end->receive(&closed));
      if (closed) return io_error("the client closed the connection");
      return server->handle(up, server_end);
    };
    LODBAKE_ASSIGN_OR_RETURN(StreamClientSession client,
                             StreamClientSession::start(s.client_end_.get(), options, pump));
    s.client_ = std::make_unique<StreamClientSession>(std::move(client));
    return s;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory starting a streaming session");
  }
}

Result<StreamFrameStats> StreamSession::frame(const CameraFrame& camera,
                                              const BoundingSphere& sphere) {
  (void)sphere;  // the client's own, from the scene message: the same sphere
  LODBAKE_ASSIGN_OR_RETURN(StreamFrameStats stats, client_->frame(camera));
  stats.server = server_->session().memory();
  return stats;
}

Result<StreamFrameStats> StreamSession::step(const ViewRequest& request) {
  LODBAKE_ASSIGN_OR_RETURN(StreamFrameStats stats, client_->step(request));
  stats.server = server_->session().memory();
  return stats;
}

Result<std::vector<StreamServedClient>> serve_stream_clients(const StreamHierarchy& db,
                                                             TcpListener* listener, size_t clients,
                                                             const StreamServerOptions& options,
                                                             const TcpOptions& tcp) {
  std::vector<StreamServedClient> served(clients);
  LODBAKE_RETURN_IF_ERROR(serve_connections(
      listener, clients, tcp, kStreamMessages,
      [&db, &options, &served](size_t k, std::unique_ptr<StreamTransport> transport) {
        StreamServedClient* out = &served[k];
        try {
          StreamServerConnection connection(db, options);
          out->status = connection.serve(transport.get());
          transport->close();
          out->uplink_bytes = transport->bytes_received();
          out->downlink_bytes = transport->bytes_sent();
          out->started = connection.started();
          out->requests = connection.requests();
          out->resumed = connection.session().resumed();
          out->sent = connection.session().sent();
          out->packets = out->sent.size();
          out->memory = connection.session().memory();
        } catch (const std::bad_alloc&) {
          out->status = runtime_error("out of memory serving a client");
        }
      }));
  return served;
}

Result<StreamBaseline> view_independent_baseline(const StreamHierarchy& db,
                                                 const std::vector<uint32_t>& sent,
                                                 uint64_t base_bytes) {
  try {
    std::vector<uint32_t> order;
    LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh pm, hierarchy_to_progressive_mesh(*db.h, &order));
    (void)pm;
    std::vector<uint32_t> rank(db.h->node_count(), kNoNode);
    for (uint32_t k = 0; k < order.size(); ++k)
      rank[order[k]] = k;
    StreamBaseline b;
    b.pm_splits = order.size();
    for (uint32_t s : sent) {
      if (s >= rank.size() || rank[s] == kNoNode) {
        return invalid_input("node " + std::to_string(s) + " is not a split of the hierarchy");
      }
      b.prefix = std::max<size_t>(b.prefix, size_t{rank[s]} + 1);
      b.sent_bits += vsplit_packet_bits(db.packet(s), db.widths);
    }
    uint64_t all_bits = 0;
    for (size_t k = 0; k < order.size(); ++k) {
      const uint64_t bits = vsplit_packet_bits(db.packet(order[k]), db.widths);
      if (k < b.prefix) b.prefix_bits += bits;
      all_bits += bits;
    }
    const uint64_t framing = kStreamHeaderBytes + 4;
    b.bytes = base_bytes + framing + (b.prefix_bits + 7) / 8;
    b.full_bytes = base_bytes + framing + (all_bits + 7) / 8;
    return b;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory computing the view-independent baseline");
  }
}

}  // namespace lodbake
