// The one-process vertex-tree session of mode vtrees (To, Lau & Green
// 2001, section 5). Choices: the client sends its view every frame (it has
// no refinement data to decide by itself what it lacks, so the server, as
// in the paper, decides); the server always answers, with an empty frame
// message when the list does not move. The channel is mode stream's.
#include "lib/replay/vtrees_session.h"

#include <chrono>
#include <new>

namespace lodbake {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
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
  return step(view_request_for(camera, options_.viewport,
                               options_.viewport.near_fraction * sphere.radius,
                               options_.tolerance_pixels));
}

Result<VtreesFrameStats> VtreesSession::step(const ViewRequest& request) {
  try {
    VtreesFrameStats stats;
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
    stats.reconstruct_ms = ms_since(start);
    const auto select = std::chrono::steady_clock::now();
    triangles_ = client_.triangles();
    stats.select_ms = ms_since(select);

    const VtreesReceived& after = client_.received();
    stats.uplink_bytes = channel_.uplink_bytes() - up0;
    stats.downlink_bytes = channel_.downlink_bytes() - down0;
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
    stats.visible = client_.visible_count();
    stats.triangles = triangles_.size();
    return stats;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory in a vertex-tree frame");
  }
}

}  // namespace lodbake
