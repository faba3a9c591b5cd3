// The one-process streaming session of mode stream (Kim, Lee and Kobbelt
// 2005, section 5.1's main loop). Choices: the client sends its view only
// when its adapt loop finds a needed split it has not received (so frames
// that the received hierarchy already satisfies cost no byte either way,
// the paper's second round of Figure 7); the view it adapts to is the
// decoded request itself, the same bytes the server evaluates. The
// baseline's PM order is hierarchy_to_progressive_mesh()'s, the order
// `lodbake-hierarchy` stores as VSPL.
#include "lib/replay/stream_session.h"

#include <algorithm>
#include <new>

#include "lib/hierarchy/hierarchy_to_pm.h"

namespace lodbake {

void StreamChannel::send_up(Bytes message) {
  up_bytes_ += message.size();
  ++up_messages_;
  up_.push_back(std::move(message));
}

void StreamChannel::send_down(Bytes message) {
  down_bytes_ += message.size();
  ++down_messages_;
  down_.push_back(std::move(message));
}

bool StreamChannel::receive_up(Bytes* message) {
  if (up_.empty()) return false;
  *message = std::move(up_.front());
  up_.pop_front();
  return true;
}

bool StreamChannel::receive_down(Bytes* message) {
  if (down_.empty()) return false;
  *message = std::move(down_.front());
  down_.pop_front();
  return true;
}

StreamSession::StreamSession(const StreamHierarchy& db, const StreamReplayOptions& options,
                             StreamClient client)
    : db_(&db),
      options_(options),
      server_(std::make_unique<StreamServerSession>(db, options.server)),
      client_(std::move(client)) {}

Result<StreamSession> StreamSession::create(const StreamHierarchy& db,
                                            const StreamReplayOptions& options) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(Bytes base, db.base_message());
    const uint64_t base_bytes = base.size();
    StreamChannel channel;
    channel.send_down(std::move(base));
    Bytes received;
    channel.receive_down(&received);
    LODBAKE_ASSIGN_OR_RETURN(StreamClient client,
                             StreamClient::create(received.data(), received.size()));
    StreamSession session(db, options, std::move(client));
    session.channel_ = std::move(channel);
    session.base_bytes_ = base_bytes;
    return session;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory starting a streaming session");
  }
}

Result<StreamFrameStats> StreamSession::frame(const CameraFrame& camera,
                                              const BoundingSphere& sphere) {
  return step(view_request_for(camera, options_.viewport,
                               options_.viewport.near_fraction * sphere.radius,
                               options_.tolerance_pixels));
}

Result<StreamFrameStats> StreamSession::step(const ViewRequest& request) {
  try {
    const Bytes message = encode_view_request(request);
    LODBAKE_ASSIGN_OR_RETURN(ViewRequest decoded,
                             decode_view_request(message.data(), message.size()));
    const StreamView view = stream_view(decoded);
    StreamFrameStats stats;
    const uint64_t up0 = channel_.uplink_bytes(), down0 = channel_.downlink_bytes();
    const size_t received0 = client_.received().size();
    for (;;) {
      LODBAKE_ASSIGN_OR_RETURN(StreamClientAdapt a, client_.adapt(view, options_.max_passes));
      stats.splits += a.splits;
      stats.collapses += a.collapses;
      stats.passes += a.passes;
      stats.missing = a.missing;
      if (a.missing == 0 || stats.requests >= options_.max_requests_per_frame) break;
      channel_.send_up(message);
      ++stats.requests;
      Bytes up;
      while (channel_.receive_up(&up)) {
        LODBAKE_ASSIGN_OR_RETURN(std::vector<Bytes> answer, server_->answer(up.data(), up.size()));
        for (Bytes& m : answer)
          channel_.send_down(std::move(m));
      }
      Bytes down;
      while (channel_.receive_down(&down))
        LODBAKE_RETURN_IF_ERROR(client_.receive(down.data(), down.size()));
      if (!client_.answer_complete()) return runtime_error("the server's answer did not end");
    }
    stats.uplink_bytes = channel_.uplink_bytes() - up0;
    stats.downlink_bytes = channel_.downlink_bytes() - down0;
    stats.packets = client_.received().size() - received0;
    stats.triangles = client_.refiner().triangle_count();
    stats.front_size = client_.refiner().front_size();
    stats.server = server_->memory();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory in a streaming frame");
  }
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
