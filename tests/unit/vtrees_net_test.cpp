// Mode vtrees over real transports (lib/replay/vtrees_session.h over
// lib/replay/stream_transport.h): a tolerance-0 session over TCP on
// loopback ends with exactly the input mesh, the same oriented triangles
// as the one-process session, nothing sent twice (a mesh with a boundary,
// meshes of genus > 0); over an in-memory pipe the client's list and
// triangles are the one-process session's along a camera path; several
// clients at once on one server each end exact with their own visible
// vertex list; a transport end refuses another family's magic, an
// oversized length and truncation from a peer with a status; malformed
// answers are refused; the scene and end-of-answer codecs round trip and
// refuse every truncation and header flip.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <string>
#include <thread>
#include <tuple>

#include "lib/replay/replay_check.h"
#include "lib/replay/vtrees_session.h"
#include "tests/unit/vtrees_test_support.h"

namespace lodbake {
namespace {
using namespace vtrees_test;

// Joins a thread when the scope ends, so a failed ASSERT does not leave a
// joinable thread behind; the thread ends within its transport's timeouts.
struct Joiner {
  std::thread& t;
  ~Joiner() {
    if (t.joinable()) t.join();
  }
};

struct Peer {
  Result<TcpListener> listener = TcpListener::listen(LoopbackAddress());
  LoopbackAddress to() const {
    LoopbackAddress a;
    a.port = listener.value().port();
    return a;
  }
};

// The client's triangles in input vertex ids (every vertex held).
std::vector<Triangle> in_input_ids(const Built& b, const VtreesClient& client,
                                   std::vector<Triangle> tris) {
  for (Triangle& t : tris) {
    for (uint32_t& v : t) {
      EXPECT_TRUE(client.holds(v));
      EXPECT_EQ(client.positions()[v], b.input.positions[b.pm.input_vertex[v]]);
      v = b.pm.input_vertex[v];
    }
  }
  return sorted_canonical(std::move(tris));
}

bool unique_nodes(std::vector<uint32_t> sent) {
  std::sort(sent.begin(), sent.end());
  return std::adjacent_find(sent.begin(), sent.end()) == sent.end();
}

class VtreesTcp : public ::testing::TestWithParam<const char*> {};

TEST_P(VtreesTcp, FullSessionOverLoopbackEndsAtTheInputMeshAsInMemory) {
  const std::unique_ptr<Built> b = build_mesh(GetParam());
  ASSERT_NE(b->db, nullptr);
  // The one-process session, for comparison.
  Result<VtreesSession> memory = VtreesSession::create(*b->db, VtreesReplayOptions());
  ASSERT_TRUE(memory.is_ok()) << memory.status().message();
  Result<VtreesFrameStats> memory_stats = memory.value().step(refine_everything(*b));
  ASSERT_TRUE(memory_stats.is_ok()) << memory_stats.status().message();

  Peer p;
  ASSERT_TRUE(p.listener.is_ok()) << p.listener.status().message();
  Result<std::vector<VtreesServedClient>> served = runtime_error("not run");
  std::thread server([&] { served = serve_vtrees_clients(*b->db, &p.listener.value(), 1); });
  Joiner join_server{server};
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(p.to(), TcpOptions(), kVtreesMessages);
  ASSERT_TRUE(t.is_ok()) << t.status().message();
  Result<VtreesClientSession> client = VtreesClientSession::start(t.value().get(), {});
  ASSERT_TRUE(client.is_ok()) << client.status().message();
  VtreesClientSession& c = client.value();
  EXPECT_EQ(c.sphere().radius, b->db->sphere.radius);
  EXPECT_EQ(c.sphere().center, b->db->sphere.center);
  EXPECT_EQ(c.trees_bytes(), memory.value().trees_bytes());
  EXPECT_EQ(c.start_downlink_bytes(), c.trees_bytes() + kVtreesHeaderBytes + 16);
  EXPECT_EQ(sorted_canonical(c.triangles()), sorted_canonical(b->pm.base.triangles));

  Result<VtreesFrameStats> stats = c.step(refine_everything(*b));
  ASSERT_TRUE(stats.is_ok()) << stats.status().message();
  const size_t splits = b->pm.splits.size();
  EXPECT_EQ(stats.value().left_records, splits);
  EXPECT_EQ(stats.value().right_records, splits);
  EXPECT_EQ(stats.value().messages, memory_stats.value().messages);
  // The same frame messages, and the end of answer.
  EXPECT_EQ(stats.value().downlink_bytes,
            memory_stats.value().downlink_bytes + kVtreesHeaderBytes + 4);
  EXPECT_EQ(stats.value().uplink_bytes, memory_stats.value().uplink_bytes);
  EXPECT_EQ(c.client().nodes_held(), b->trees.node_count());
  // Exactly the one-process session's oriented triangles, and the input mesh.
  EXPECT_EQ(sorted_canonical(c.triangles()), sorted_canonical(memory.value().triangles()));
  EXPECT_EQ(in_input_ids(*b, c.client(), c.triangles()), sorted_canonical(b->input.triangles));

  // Nothing moves any more: one empty frame message and the end of answer.
  Result<VtreesFrameStats> again = c.step(refine_everything(*b));
  ASSERT_TRUE(again.is_ok()) << again.status().message();
  EXPECT_EQ(again.value().left_records + again.value().downs + again.value().ups, 0u);
  EXPECT_EQ(again.value().downlink_bytes, 2 * (kVtreesHeaderBytes + 4));
  t.value()->close();
  server.join();
  ASSERT_TRUE(served.is_ok()) << served.status().message();
  const VtreesServedClient& s = served.value()[0];
  EXPECT_TRUE(s.status.is_ok()) << s.status.message();
  EXPECT_EQ(s.requests, 2u);
  EXPECT_TRUE(unique_nodes(s.sent_nodes));
  EXPECT_EQ(s.sent_nodes.size(), c.client().nodes_held());
  EXPECT_EQ(s.downlink_bytes, t.value()->bytes_received());
  EXPECT_EQ(s.uplink_bytes, t.value()->bytes_sent());
  EXPECT_EQ(s.visible, c.client().visible_count());
}

INSTANTIATE_TEST_SUITE_P(Meshes, VtreesTcp,
                         ::testing::Values("cgal_mushroom.off",  // boundary
                                           "cgal_elephant.off",  // genus 3
                                           "torus"));            // genus 1

TEST(VtreesNet, PipeSessionIsTheOneProcessSessionAlongACameraPath) {
  const std::unique_ptr<Built> b = build_mesh("cgal_mushroom.off");
  ASSERT_NE(b->db, nullptr);
  VtreesReplayOptions options;
  options.max_items_per_message = 50;  // several messages per answer
  Result<VtreesSession> memory = VtreesSession::create(*b->db, options);
  ASSERT_TRUE(memory.is_ok());
  auto [client_end, server_end] = make_memory_transport_pair(0, kVtreesMessages, kStreamMessages);
  server_end->set_max_payload(kViewRequestPayloadBytes);
  Result<VtreesServerConnection> server = VtreesServerConnection::create(*b->db, 50);
  ASSERT_TRUE(server.is_ok());
  ASSERT_TRUE(server.value().start(server_end.get()).is_ok());
  StreamTransport* end = server_end.get();
  VtreesServerConnection* connection = &server.value();
  StreamPump pump = [end, connection]() -> Status {
    bool closed = false;
    LODBAKE_ASSIGN_OR_RETURN(Bytes up, end->receive(&closed));
    if (closed) return io_error("the client closed the connection");
    return connection->handle(up, end);
  };
  Result<VtreesClientSession> client = VtreesClientSession::start(client_end.get(), options, pump);
  ASSERT_TRUE(client.is_ok()) << client.status().message();
  const BoundingSphere sphere = bounding_sphere(b->h.position);
  const std::vector<CameraFrame> path = scan_path(sphere, 60);
  size_t several = 0;
  for (size_t i = 0; i < path.size(); ++i) {
    Result<VtreesFrameStats> m = memory.value().frame(path[i], sphere);
    Result<VtreesFrameStats> f = client.value().frame(path[i]);
    ASSERT_TRUE(m.is_ok() && f.is_ok()) << "frame " << i << ": " << f.status().message();
    EXPECT_EQ(f.value().messages, m.value().messages) << "frame " << i;
    EXPECT_EQ(f.value().downlink_bytes, m.value().downlink_bytes + kVtreesHeaderBytes + 4);
    several += f.value().messages > 1;
    ASSERT_EQ(sorted_canonical(client.value().triangles()),
              sorted_canonical(memory.value().triangles()))
        << "frame " << i;
    for (uint32_t v = 0; v < b->trees.positions.size(); ++v) {
      ASSERT_EQ(client.value().client().visible_node(v),
                connection->session().list().visible_node(v))
          << "frame " << i << ", vertex " << v;
    }
  }
  EXPECT_GT(several, 0u);
  EXPECT_TRUE(unique_nodes(connection->session().sent_nodes()));
}

TEST(VtreesNet, SeveralClientsAtOnceEachEndExactWithTheirOwnList) {
  const std::unique_ptr<Built> b = build_mesh("torus");
  ASSERT_NE(b->db, nullptr);
  constexpr size_t kClients = 6;
  Peer p;
  ASSERT_TRUE(p.listener.is_ok());
  Result<std::vector<VtreesServedClient>> served = runtime_error("not run");
  std::thread server(
      [&] { served = serve_vtrees_clients(*b->db, &p.listener.value(), kClients, 64); });
  Joiner join_server{server};
  const BoundingSphere sphere = bounding_sphere(b->h.position);
  const std::vector<CameraFrame> path = scan_path(sphere, 60);
  std::vector<std::string> problems(kClients);
  std::vector<size_t> partial_visible(kClients, 0);
  std::vector<std::thread> clients;
  for (size_t k = 0; k < kClients; ++k) {
    clients.emplace_back([&, k] {
      auto fail = [&](const std::string& why) { problems[k] = why; };
      Result<std::unique_ptr<StreamTransport>> t =
          tcp_connect(p.to(), TcpOptions(), kVtreesMessages);
      if (!t.is_ok()) return fail(t.status().message());
      VtreesReplayOptions options;
      options.tolerance_pixels = 2.0f + 3.0f * static_cast<float>(k);  // a list of its own
      Result<VtreesClientSession> c = VtreesClientSession::start(t.value().get(), options);
      if (!c.is_ok()) return fail(c.status().message());
      for (size_t i = k; i < path.size(); i += 3) {
        Result<VtreesFrameStats> f = c.value().frame(path[i]);
        if (!f.is_ok()) return fail(f.status().message());
      }
      partial_visible[k] = c.value().client().visible_count();
      Result<VtreesFrameStats> all = c.value().step(refine_everything(*b));
      if (!all.is_ok()) return fail(all.status().message());
      if (in_input_ids(*b, c.value().client(), c.value().triangles()) !=
          sorted_canonical(b->input.triangles)) {
        return fail("not the input mesh");
      }
      if (c.value().client().nodes_held() != b->trees.node_count()) return fail("nodes missing");
      // One more frame on the path, so each server session ends on its own list.
      Result<VtreesFrameStats> last = c.value().frame(path[k]);
      if (!last.is_ok()) return fail(last.status().message());
      partial_visible[k] = c.value().client().visible_count();
      t.value()->close();
    });
  }
  for (std::thread& t : clients)
    t.join();
  server.join();
  for (size_t k = 0; k < kClients; ++k)
    EXPECT_EQ(problems[k], "") << "client " << k;
  ASSERT_TRUE(served.is_ok()) << served.status().message();
  std::vector<size_t> server_visible;
  for (const VtreesServedClient& s : served.value()) {
    EXPECT_TRUE(s.status.is_ok()) << s.status.message();
    EXPECT_TRUE(unique_nodes(s.sent_nodes));
    EXPECT_EQ(s.sent_nodes.size(), b->trees.node_count());
    server_visible.push_back(s.visible);
  }
  // Connections are accepted in any order: compare the lists as sets.
  std::sort(server_visible.begin(), server_visible.end());
  std::sort(partial_visible.begin(), partial_visible.end());
  EXPECT_EQ(server_visible, partial_visible);
  EXPECT_GT(partial_visible.back(), partial_visible.front());  // they differ
}

Bytes header(uint8_t magic, uint8_t type, uint32_t length) {
  Bytes h = {magic, type};
  for (int k = 0; k < 4; ++k)
    h.push_back(static_cast<uint8_t>(length >> (8 * k)));
  return h;
}

// The status a vtrees server connection ends with after a raw peer
// received the opening, sent `bytes` and closed.
Status serve_raw(const Built& b, const Bytes& bytes) {
  Peer p;
  EXPECT_TRUE(p.listener.is_ok());
  Result<std::vector<VtreesServedClient>> served = runtime_error("not run");
  TcpOptions tcp;
  tcp.io_timeout_ms = 2000;
  std::thread server(
      [&] { served = serve_vtrees_clients(*b.db, &p.listener.value(), 1, kMaxVtreesItems, tcp); });
  Joiner join_server{server};
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(p.to(), tcp, kVtreesMessages);
  EXPECT_TRUE(t.is_ok());
  bool closed = false;
  EXPECT_TRUE(t.value()->receive(&closed).is_ok());  // trees
  EXPECT_TRUE(t.value()->receive(&closed).is_ok());  // scene
  (void)t.value()->send(bytes);
  t.value()->close();
  server.join();
  EXPECT_TRUE(served.is_ok());
  return served.is_ok() ? served.value()[0].status : served.status();
}

TEST(VtreesNetMalformed, TheServerRefusesWhatAPeerSendsWrongWithAStatus) {
  const std::unique_ptr<Built> b = build_mesh("torus");
  ASSERT_NE(b->db, nullptr);
  const Bytes view = encode_view_request(refine_everything(*b));
  // Another family's magic: a vtrees message where a view should be.
  Status s = serve_raw(*b, encode_vtrees_end_of_answer(0));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  EXPECT_NE(s.message().find("bad magic"), std::string::npos) << s.message();
  // Oversized: over any family limit, and over a view request's size.
  s = serve_raw(*b, header(kStreamMagicVersion, 1, 0x7fffffffu));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  EXPECT_NE(s.message().find("exceeds the limit"), std::string::npos) << s.message();
  s = serve_raw(*b, header(kStreamMagicVersion, 1, kViewRequestPayloadBytes + 1));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  // Truncated: the peer closes inside a message or its header.
  s = serve_raw(*b, Bytes(view.begin(), view.begin() + 40));
  EXPECT_EQ(s.kind(), ErrorKind::kIo) << s.message();
  s = serve_raw(*b, Bytes(view.begin(), view.begin() + 3));
  EXPECT_EQ(s.kind(), ErrorKind::kIo) << s.message();
  // Mode stream's hello, or any stream message but a view.
  s = serve_raw(*b, encode_hello());
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  EXPECT_NE(s.message().find("view request was expected"), std::string::npos) << s.message();
  // A view with a bad payload (a non-finite entry).
  Bytes bad_view = view;
  bad_view[kStreamHeaderBytes + 3] = 0x7f;
  bad_view[kStreamHeaderBytes + 2] = 0xc0;
  s = serve_raw(*b, bad_view);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  // A clean close after the opening is a normal end.
  EXPECT_TRUE(serve_raw(*b, Bytes()).is_ok());
}

// A fake server that accepts, sends `bytes`, then waits; the status of a
// vtrees client session that starts and asks for one frame against it.
Status client_against(const Bytes& bytes, int io_timeout_ms = 2000) {
  Peer p;
  EXPECT_TRUE(p.listener.is_ok());
  TcpOptions tcp;
  tcp.io_timeout_ms = io_timeout_ms;
  std::atomic<bool> done{false};
  std::thread fake([&] {
    Result<std::unique_ptr<StreamTransport>> t = p.listener.value().accept(tcp, kStreamMessages);
    if (!t.is_ok()) return;
    (void)t.value()->send(bytes);
    while (!done)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  Joiner join_fake{fake};
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(p.to(), tcp, kVtreesMessages);
  EXPECT_TRUE(t.is_ok());
  Result<VtreesClientSession> c = VtreesClientSession::start(t.value().get(), {});
  Status s = c.status();
  if (c.is_ok()) {
    ViewRequest view;
    view.modelview = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1};
    s = c.value().step(view).status();
  }
  done = true;
  fake.join();
  return s;
}

TEST(VtreesNetMalformed, TheClientRefusesWhatAServerSendsWrong) {
  const std::unique_ptr<Built> b = build_mesh("torus");
  ASSERT_NE(b->db, nullptr);
  const Bytes trees = b->db->trees_message().value();
  const Bytes scene = encode_vtrees_scene(b->db->sphere);
  auto cat = [](std::initializer_list<Bytes> parts) {
    Bytes all;
    for (const Bytes& p : parts)
      all.insert(all.end(), p.begin(), p.end());
    return all;
  };
  // Another family's magic: mode stream's scene message where the trees should be.
  Status s = client_against(encode_scene_message(b->db->sphere));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  EXPECT_NE(s.message().find("vtrees message: bad magic"), std::string::npos) << s.message();
  // Oversized: refused on the header.
  s = client_against(header(kVtreesMagicVersion, 2, 0x7fffffffu));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  EXPECT_NE(s.message().find("exceeds the limit"), std::string::npos) << s.message();
  // Truncated, then silence.
  s = client_against(Bytes(trees.begin(), trees.begin() + trees.size() / 2), 300);
  EXPECT_EQ(s.kind(), ErrorKind::kIo) << s.message();
  // Wrong order: the scene first, the trees twice, no scene.
  s = client_against(scene);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  s = client_against(cat({trees, trees}));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  // An answer whose end counts messages that did not come, or a trees
  // message inside an answer.
  s = client_against(cat({trees, scene, encode_vtrees_end_of_answer(2)}));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  EXPECT_NE(s.message().find("counts 2 frame messages"), std::string::npos) << s.message();
  s = client_against(cat({trees, scene, trees}));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  // A well-formed opening and an empty answer: fine.
  Result<std::vector<Bytes>> empty_answer = runtime_error("");
  {
    Result<VtreesServerSession> server = VtreesServerSession::create(*b->db);
    ASSERT_TRUE(server.is_ok());
    ViewRequest far;
    far.modelview = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1e6f, 1};
    far.tolerance = 1;
    const Bytes v = encode_view_request(far);
    empty_answer = server.value().answer(v.data(), v.size());
    ASSERT_TRUE(empty_answer.is_ok()) << empty_answer.status().message();
  }
  s = client_against(cat({trees, scene, empty_answer.value()[0], encode_vtrees_end_of_answer(1)}));
  EXPECT_TRUE(s.is_ok()) << s.message();
}

TEST(VtreesNetMalformed, ATransportEndRefusesTheOtherFamilyBeforeAllocating) {
  auto [a, b] = make_memory_transport_pair(0, kVtreesMessages, kStreamMessages);
  bool closed = false;
  // a receives vtrees messages: a stream message is refused, a vtrees one taken.
  ASSERT_TRUE(b->send(encode_hello()).is_ok());
  Result<Bytes> got = a->receive(&closed);
  EXPECT_EQ(got.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(got.status().message().find("vtrees message: bad magic"), std::string::npos);
  ASSERT_TRUE(b->send(encode_vtrees_end_of_answer(3)).is_ok());
  EXPECT_TRUE(a->receive(&closed).is_ok());
  // b receives stream messages: the reverse.
  ASSERT_TRUE(a->send(encode_vtrees_end_of_answer(3)).is_ok());
  got = b->receive(&closed);
  EXPECT_EQ(got.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(got.status().message().find("stream message: bad magic"), std::string::npos);
  // A length that does not match, a newer version.
  Bytes longer = encode_vtrees_end_of_answer(3);
  longer.push_back(0);
  ASSERT_TRUE(b->send(longer).is_ok());
  EXPECT_EQ(a->receive(&closed).status().kind(), ErrorKind::kInvalidInput);
  Bytes newer = encode_vtrees_end_of_answer(3);
  newer[0] = kVtreesMagicVersion + 1;
  ASSERT_TRUE(b->send(newer).is_ok());
  EXPECT_EQ(a->receive(&closed).status().kind(), ErrorKind::kUnsupported);
  EXPECT_EQ(a->receives().magic_version, kVtreesMagicVersion);
  EXPECT_EQ(a->max_payload(), kMaxVtreesPayloadBytes);
  EXPECT_EQ(b->max_payload(), kMaxStreamPayloadBytes);
}

TEST(VtreesNetRecords, SceneAndEndOfAnswerRoundTripAndRefuseTruncationsAndFlips) {
  BoundingSphere sphere;
  sphere.center = {1.5f, -2, 3};
  sphere.radius = 4;
  const Bytes scene = encode_vtrees_scene(sphere);
  const Bytes end = encode_vtrees_end_of_answer(77);
  ASSERT_EQ(scene.size(), kVtreesHeaderBytes + 16);
  ASSERT_EQ(end.size(), kVtreesHeaderBytes + 4);
  Result<BoundingSphere> s = decode_vtrees_scene(scene.data(), scene.size());
  ASSERT_TRUE(s.is_ok());
  EXPECT_EQ(s.value().center, sphere.center);
  EXPECT_EQ(s.value().radius, sphere.radius);
  EXPECT_EQ(decode_vtrees_end_of_answer(end.data(), end.size()).value(), 77u);
  for (size_t n = 0; n < scene.size(); ++n)
    EXPECT_FALSE(decode_vtrees_scene(scene.data(), n).is_ok()) << n;
  for (size_t n = 0; n < end.size(); ++n)
    EXPECT_FALSE(decode_vtrees_end_of_answer(end.data(), n).is_ok()) << n;
  for (size_t bit = 0; bit < 8 * kVtreesHeaderBytes; ++bit) {
    Bytes a = scene, e = end;
    a[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    e[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_FALSE(decode_vtrees_scene(a.data(), a.size()).is_ok()) << bit;
    EXPECT_FALSE(decode_vtrees_end_of_answer(e.data(), e.size()).is_ok()) << bit;
  }
  Bytes trailing = end;
  trailing.push_back(0);
  EXPECT_FALSE(decode_vtrees_end_of_answer(trailing.data(), trailing.size()).is_ok());
  sphere.radius = 0;
  const Bytes flat = encode_vtrees_scene(sphere);
  EXPECT_FALSE(decode_vtrees_scene(flat.data(), flat.size()).is_ok());
  sphere.radius = 1;
  sphere.center[1] = std::numeric_limits<float>::infinity();
  const Bytes inf = encode_vtrees_scene(sphere);
  EXPECT_FALSE(decode_vtrees_scene(inf.data(), inf.size()).is_ok());
}

}  // namespace
}  // namespace lodbake
