// Mode stream over real transports and across lost connections
// (lib/replay/stream_transport.h, stream_session.h): a tolerance-0 session
// over TCP on loopback ends with exactly the input mesh and the same bytes
// as in memory; several clients at once on one server each end exact, each
// with its own session; a connection cut mid-answer or between frames,
// resumed from the client's leaves, ends in the same final mesh with every
// split received once and nothing the client held sent again (in process
// and over TCP); malformed messages from a peer (a huge announced length,
// truncation, wrong types, non-fronts) are refused with a status, and a
// silent peer ends in a timeout; the resume and scene codecs round trip and
// refuse every truncation and header flip.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <set>
#include <thread>

#include "formats/support/bit_packing.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_transport.h"
#include "tests/unit/stream_test_support.h"

namespace lodbake {
namespace {
using namespace stream_test;

LoopbackAddress any_port() {
  return LoopbackAddress();  // 127.0.0.1:0
}

struct Db {
  Built b;
  std::unique_ptr<StreamHierarchy> db;
  size_t splits = 0;
};

Db make_db(const std::string& mesh) {
  Db d;
  d.b = build_mesh(mesh);
  Result<StreamHierarchy> db = StreamHierarchy::create(d.b.h, d.b.data);
  EXPECT_TRUE(db.is_ok()) << db.status().message();
  d.db = std::make_unique<StreamHierarchy>(std::move(db).value());
  d.splits = d.b.h.node_count() - d.b.input.positions.size();
  return d;
}

// Joins a thread when the scope ends, so a failed ASSERT does not leave a
// joinable thread behind (std::terminate); the thread itself ends within
// its transport's timeouts.
struct Joiner {
  std::thread& t;
  ~Joiner() {
    if (t.joinable()) t.join();
  }
};

// Forwards to another transport until `sends` sends or `receives` receives
// have passed (negative: no limit), then closes it and fails: a connection
// killed at a chosen message.
class CutTransport final : public StreamTransport {
 public:
  CutTransport(StreamTransport* inner, int sends, int receives)
      : inner_(inner), sends_(sends), receives_(receives) {}
  Status send(const Bytes& message) override {
    if (cut_ || sends_ == 0) return cut();
    if (sends_ > 0) --sends_;
    LODBAKE_RETURN_IF_ERROR(inner_->send(message));
    count_sent(message.size());
    return Status::ok();
  }
  Result<Bytes> receive(bool* closed) override {
    if (cut_ || receives_ == 0) return cut();
    if (receives_ > 0) --receives_;
    LODBAKE_ASSIGN_OR_RETURN(Bytes m, inner_->receive(closed));
    count_received(m.size());
    return m;
  }
  void close() override { inner_->close(); }
  bool was_cut() const { return cut_; }

 private:
  Status cut() {
    cut_ = true;
    inner_->close();
    return io_error("connection killed by the test");
  }
  StreamTransport* inner_;
  int sends_, receives_;
  bool cut_ = false;
};

class StreamTcp : public ::testing::TestWithParam<const char*> {};

TEST_P(StreamTcp, FullSessionOverLoopbackEndsAtTheInputMeshWithTheInMemoryBytes) {
  const Db d = make_db(GetParam());
  Result<TcpListener> listener = TcpListener::listen(any_port());
  ASSERT_TRUE(listener.is_ok()) << listener.status().message();
  ASSERT_NE(listener.value().port(), 0);
  Result<std::vector<StreamServedClient>> served = runtime_error("not run");
  std::thread server(
      [&] { served = serve_stream_clients(*d.db, &listener.value(), 1, StreamServerOptions()); });
  Joiner join_server{server};
  LoopbackAddress to;
  to.port = listener.value().port();
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(to);
  ASSERT_TRUE(t.is_ok()) << t.status().message();
  Result<StreamClientSession> client = StreamClientSession::start(t.value().get(), {});
  ASSERT_TRUE(client.is_ok()) << client.status().message();
  EXPECT_EQ(client.value().sphere().radius, d.db->sphere.radius);
  Result<StreamFrameStats> stats = client.value().step(refine_everything(d.b));
  ASSERT_TRUE(stats.is_ok()) << stats.status().message();
  EXPECT_EQ(stats.value().requests, 1u);
  EXPECT_EQ(stats.value().packets, d.splits);
  EXPECT_EQ(input_mesh_problem(client.value().client(), *d.db, d.b), "");
  EXPECT_EQ(every_split_once(client.value().client(), *d.db), "");
  t.value()->close();
  server.join();
  ASSERT_TRUE(served.is_ok()) << served.status().message();
  const StreamServedClient& s = served.value()[0];
  EXPECT_TRUE(s.status.is_ok()) << s.status.message();
  EXPECT_EQ(s.packets, d.splits);
  EXPECT_EQ(s.requests, 1u);

  // The same session in memory: the same bytes both ways.
  Result<StreamSession> memory = StreamSession::create(*d.db, StreamReplayOptions());
  ASSERT_TRUE(memory.is_ok());
  Result<StreamFrameStats> in_memory = memory.value().step(refine_everything(d.b));
  ASSERT_TRUE(in_memory.is_ok());
  EXPECT_EQ(in_memory.value().downlink_bytes, stats.value().downlink_bytes);
  EXPECT_EQ(in_memory.value().uplink_bytes, stats.value().uplink_bytes);
  EXPECT_EQ(memory.value().start_downlink_bytes(), client.value().start_downlink_bytes());
  EXPECT_EQ(s.downlink_bytes, client.value().start_downlink_bytes() + stats.value().downlink_bytes);
  EXPECT_EQ(s.uplink_bytes, client.value().start_uplink_bytes() + stats.value().uplink_bytes);
}

INSTANTIATE_TEST_SUITE_P(Meshes, StreamTcp, ::testing::Values("cgal_mushroom.off", "torus"));

// A camera path turned about the sphere's vertical axis by `degrees`.
std::vector<CameraFrame> turned(std::vector<CameraFrame> path, const BoundingSphere& s,
                                float degrees) {
  const float a = degrees * 3.14159265f / 180, c = std::cos(a), sn = std::sin(a);
  for (CameraFrame& f : path) {
    for (Vec3f* p : {&f.eye, &f.target}) {
      const float x = (*p)[0] - s.center[0], z = (*p)[2] - s.center[2];
      (*p)[0] = s.center[0] + c * x + sn * z;
      (*p)[2] = s.center[2] - sn * x + c * z;
    }
  }
  return path;
}

TEST(StreamTcpClients, SeveralClientsAtOnceEachWithItsOwnSessionEndExact) {
  const Db d = make_db("cgal_mushroom.off");
  constexpr size_t kClients = 4;
  Result<TcpListener> listener = TcpListener::listen(any_port());
  ASSERT_TRUE(listener.is_ok()) << listener.status().message();
  Result<std::vector<StreamServedClient>> served = runtime_error("not run");
  std::thread server([&] {
    served = serve_stream_clients(*d.db, &listener.value(), kClients, StreamServerOptions());
  });
  Joiner join_server{server};
  LoopbackAddress to;
  to.port = listener.value().port();
  std::vector<std::string> problems(kClients);
  std::vector<size_t> packets(kClients, 0);
  std::vector<std::thread> clients;
  for (size_t k = 0; k < kClients; ++k) {
    clients.emplace_back([&, k] {
      Result<std::unique_ptr<StreamTransport>> t = tcp_connect(to);
      if (!t.is_ok()) {
        problems[k] = t.status().message();
        return;
      }
      Result<StreamClientSession> c = StreamClientSession::start(t.value().get(), {});
      if (!c.is_ok()) {
        problems[k] = c.status().message();
        return;
      }
      const BoundingSphere& sphere = c.value().sphere();
      const std::vector<CameraFrame> path =
          turned(k % 2 ? orbit_path(sphere, 60) : scan_path(sphere, 60), sphere, 90.0f * k);
      for (size_t i = 0; i < path.size(); i += 7) {  // every 7th frame: quicker, still moving
        Result<StreamFrameStats> f = c.value().frame(path[i]);
        if (!f.is_ok() || f.value().missing != 0) {
          problems[k] = "frame " + std::to_string(i) + ": " + f.status().message();
          return;
        }
        packets[k] += f.value().packets;
      }
      Result<StreamFrameStats> all = c.value().step(refine_everything(d.b));
      if (!all.is_ok()) {
        problems[k] = all.status().message();
        return;
      }
      packets[k] += all.value().packets;
      problems[k] = input_mesh_problem(c.value().client(), *d.db, d.b);
      if (problems[k].empty()) problems[k] = every_split_once(c.value().client(), *d.db);
    });
  }
  for (std::thread& t : clients)
    t.join();
  server.join();
  for (size_t k = 0; k < kClients; ++k) {
    EXPECT_EQ(problems[k], "") << "client " << k;
    EXPECT_EQ(packets[k], d.splits) << "client " << k;
  }
  ASSERT_TRUE(served.is_ok()) << served.status().message();
  for (const StreamServedClient& s : served.value()) {
    EXPECT_TRUE(s.status.is_ok()) << s.status.message();
    EXPECT_EQ(s.packets, d.splits);
    std::vector<uint32_t> sent = s.sent;
    std::sort(sent.begin(), sent.end());
    EXPECT_EQ(std::adjacent_find(sent.begin(), sent.end()), sent.end());
    EXPECT_EQ(s.memory.window_bytes, 0u);  // everything split: no tag left
  }
}

// The splits (node indices) a client holds.
std::set<uint32_t> held_splits(const StreamClient& c, const StreamHierarchy& db) {
  const std::map<HierarchyNodeId, uint32_t> ids = id_map(db);
  std::set<uint32_t> held;
  for (const HierarchyNodeId& id : c.received())
    held.insert(ids.at(id));
  return held;
}

// One process. With `server_sends` >= 0 the server's end is killed at that
// send of the first connection (the hello's base and scene are the first
// two), while the client runs the scan path and then asks for everything;
// with -1 the client closes the connection after `frames_before` frames.
// Then a new connection resumes, finishes the path and asks for everything.
// `expect_held`: the splits the client must hold when the first connection
// dies (-1: not checked).
void resume_in_process(int server_sends, size_t frames_before, size_t per_message,
                       long expect_held) {
  const Db d = make_db("cgal_mushroom.off");
  StreamReplayOptions options;
  options.server.max_packets_per_message = per_message;
  auto [client_end, server_end] = make_memory_transport_pair(0);
  CutTransport cut(server_end.get(), server_sends, -1);
  auto first = std::make_unique<StreamServerConnection>(*d.db, options.server);
  // The server's failure is its own: the client learns of it only by what
  // stops arriving, as over a socket.
  StreamPump pump1 = [&]() -> Status {
    bool closed = false;
    Result<Bytes> up = server_end->receive(&closed);
    if (up.is_ok() && !closed) (void)first->handle(up.value(), &cut);
    return Status::ok();
  };
  Result<StreamClientSession> started =
      StreamClientSession::start(client_end.get(), options, pump1);
  ASSERT_TRUE(started.is_ok()) << started.status().message();
  StreamClientSession& c = started.value();
  const std::vector<CameraFrame> path = scan_path(c.sphere(), 60);
  bool lost = false;
  size_t next = 0;
  for (; next < path.size() && !lost && (server_sends >= 0 || next < frames_before); ++next)
    lost = !c.frame(path[next]).is_ok();
  if (server_sends >= 0) {
    if (!lost) lost = !c.step(refine_everything(d.b)).is_ok();
    ASSERT_TRUE(lost) << "the cut came after the session's end";
    ASSERT_TRUE(cut.was_cut());
  } else {
    ASSERT_FALSE(lost);
    client_end->close();
  }
  const std::set<uint32_t> held = held_splits(c.client(), *d.db);
  const std::vector<uint32_t> first_sent = first->session().sent();
  ASSERT_LT(held.size(), d.splits);
  ASSERT_GT(held.size(), 0u);
  EXPECT_LE(held.size(), first_sent.size());
  if (expect_held >= 0) {
    EXPECT_EQ(held.size(), static_cast<size_t>(expect_held));
  }

  auto [client2, server2] = make_memory_transport_pair(0);
  StreamServerConnection second(*d.db, options.server);
  StreamPump pump2 = [&, s2 = server2.get()]() -> Status {
    bool closed = false;
    LODBAKE_ASSIGN_OR_RETURN(Bytes up, s2->receive(&closed));
    return second.handle(up, s2);
  };
  ASSERT_TRUE(c.resume(client2.get(), pump2).is_ok());
  EXPECT_EQ(second.session().resumed(), held.size());
  EXPECT_EQ(c.connections(), 2u);
  for (size_t i = next; i < path.size(); ++i) {
    Result<StreamFrameStats> f = c.frame(path[i]);
    ASSERT_TRUE(f.is_ok()) << "frame " << i << ": " << f.status().message();
    ASSERT_EQ(f.value().missing, 0u);
    ASSERT_LE(f.value().requests, 1u);
  }
  Result<StreamFrameStats> all = c.step(refine_everything(d.b));
  ASSERT_TRUE(all.is_ok()) << all.status().message();
  EXPECT_EQ(input_mesh_problem(c.client(), *d.db, d.b), "");
  EXPECT_EQ(every_split_once(c.client(), *d.db), "");
  // Nothing the client held was sent again; only what the first connection
  // sent and lost in flight was.
  size_t again = 0;
  const std::set<uint32_t> first_set(first_sent.begin(), first_sent.end());
  for (uint32_t s : second.session().sent()) {
    EXPECT_EQ(held.count(s), 0u) << "node " << s << " sent again";
    again += first_set.count(s);
  }
  EXPECT_EQ(again, first_sent.size() - held.size());
  EXPECT_EQ(held.size() + second.session().sent().size(), d.splits);
}

TEST(StreamResume, InProcessCutMidAnswerEndsExactWithNothingHeldSentAgain) {
  // Base and scene, then 5 vsplit messages of 8 packets of the first
  // answer arrive; the 6th send kills the connection.
  resume_in_process(2 + 5, 0, 8, 5 * 8);
}

TEST(StreamResume, InProcessCutAtAnAnswerEndsExact) {
  // Some whole answers along the scan path, then the connection dies at
  // the server's next send.
  resume_in_process(2 + 9, 0, 4096, -1);
}

TEST(StreamResume, InProcessClientClosesBetweenFramesEndsExact) {
  resume_in_process(-1, 60, 4096, -1);
}

TEST(StreamResume, OverTcpTheClientKillsTheConnectionMidAnswerAndResumes) {
  const Db d = make_db("torus");
  StreamReplayOptions options;
  options.server.max_packets_per_message = 16;
  Result<TcpListener> listener = TcpListener::listen(any_port());
  ASSERT_TRUE(listener.is_ok()) << listener.status().message();
  Result<std::vector<StreamServedClient>> served = runtime_error("not run");
  std::thread server(
      [&] { served = serve_stream_clients(*d.db, &listener.value(), 2, options.server); });
  Joiner join_server{server};
  LoopbackAddress to;
  to.port = listener.value().port();
  Result<std::unique_ptr<StreamTransport>> t1 = tcp_connect(to);
  ASSERT_TRUE(t1.is_ok()) << t1.status().message();
  // Base, scene, then 3 vsplit messages; the 4th receive kills the socket.
  CutTransport cut(t1.value().get(), -1, 2 + 3);
  Result<StreamClientSession> started = StreamClientSession::start(&cut, options);
  ASSERT_TRUE(started.is_ok()) << started.status().message();
  StreamClientSession& c = started.value();
  EXPECT_FALSE(c.step(refine_everything(d.b)).is_ok());
  const size_t held = c.client().received().size();
  EXPECT_EQ(held, 3u * 16);

  Result<std::unique_ptr<StreamTransport>> t2 = tcp_connect(to);
  ASSERT_TRUE(t2.is_ok()) << t2.status().message();
  ASSERT_TRUE(c.resume(t2.value().get()).is_ok());
  Result<StreamFrameStats> all = c.step(refine_everything(d.b));
  ASSERT_TRUE(all.is_ok()) << all.status().message();
  EXPECT_EQ(all.value().packets, d.splits - held);
  EXPECT_EQ(input_mesh_problem(c.client(), *d.db, d.b), "");
  EXPECT_EQ(every_split_once(c.client(), *d.db), "");
  t2.value()->close();
  server.join();
  ASSERT_TRUE(served.is_ok()) << served.status().message();
  // The first connection died under the server (its sends may or may not
  // have failed before it saw the close); the second resumed and ended well.
  const StreamServedClient& second = served.value()[1];
  EXPECT_TRUE(second.status.is_ok()) << second.status.message();
  EXPECT_EQ(second.resumed, held);
  EXPECT_EQ(second.packets, d.splits - held);
}

// ---- malformed peers ----

struct Peer {
  Result<TcpListener> listener = TcpListener::listen(any_port());
  LoopbackAddress to() const {
    LoopbackAddress a;
    a.port = listener.value().port();
    return a;
  }
};

// The status a server connection ends with after a raw peer sent `bytes`
// and closed.
Status serve_raw(const Db& d, const Bytes& bytes, bool hello_first) {
  Peer p;
  EXPECT_TRUE(p.listener.is_ok());
  Result<std::vector<StreamServedClient>> served = runtime_error("not run");
  TcpOptions tcp;
  tcp.io_timeout_ms = 2000;
  std::thread server([&] {
    served = serve_stream_clients(*d.db, &p.listener.value(), 1, StreamServerOptions(), tcp);
  });
  Joiner join_server{server};
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(p.to());
  EXPECT_TRUE(t.is_ok());
  if (hello_first) {
    EXPECT_TRUE(t.value()->send(encode_hello()).is_ok());
    bool closed = false;
    EXPECT_TRUE(t.value()->receive(&closed).is_ok());  // base
    EXPECT_TRUE(t.value()->receive(&closed).is_ok());  // scene
  }
  (void)t.value()->send(bytes);
  t.value()->close();
  server.join();
  EXPECT_TRUE(served.is_ok());
  return served.is_ok() ? served.value()[0].status : served.status();
}

Bytes header(uint8_t type, uint32_t length) {
  Bytes h = {kStreamMagicVersion, type};
  for (int k = 0; k < 4; ++k)
    h.push_back(static_cast<uint8_t>(length >> (8 * k)));
  return h;
}

TEST(StreamNetMalformed, TheServerRefusesWhatAPeerSendsWrongWithAStatus) {
  const Db d = make_db("torus");
  const Bytes view = encode_view_request(refine_everything(d.b));
  // A huge announced length: refused on the header, before any allocation.
  Status s = serve_raw(d, header(5, 0x7fffffffu), false);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  EXPECT_NE(s.message().find("exceeds the limit"), std::string::npos) << s.message();
  // Longer than any uplink message can be for this hierarchy, even within
  // the global limit.
  s = serve_raw(d, header(1, d.db->uplink_payload_limit() + 1), true);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  // Truncated: the peer closes inside a message.
  s = serve_raw(d, Bytes(view.begin(), view.begin() + 40), true);
  EXPECT_EQ(s.kind(), ErrorKind::kIo) << s.message();
  s = serve_raw(d, Bytes(view.begin(), view.begin() + 3), true);
  EXPECT_EQ(s.kind(), ErrorKind::kIo) << s.message();
  // Wrong types: a view before the hello, a hello after it, a downlink type,
  // an unknown type.
  s = serve_raw(d, view, false);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  s = serve_raw(d, encode_hello(), true);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  s = serve_raw(d, encode_end_of_answer(0), true);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  Bytes unknown = header(9, 0);
  s = serve_raw(d, unknown, true);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  // A resume whose leaves are not a front: the roots' left children only.
  std::vector<HierarchyNodeId> lefts;
  for (uint32_t r = 0; r < d.b.h.root_count(); ++r) {
    if (!d.b.h.is_leaf(r)) lefts.push_back({r, 2});
  }
  Result<Bytes> resume =
      encode_resume_message(lefts, d.db->widths, static_cast<uint32_t>(d.b.h.root_count()));
  ASSERT_TRUE(resume.is_ok());
  s = serve_raw(d, resume.value(), false);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  // A clean close right after the hello is a normal end.
  EXPECT_TRUE(serve_raw(d, Bytes(), true).is_ok());
}

// A fake server that accepts, sends `bytes`, then waits for the client.
Status client_against(const Bytes& bytes, int io_timeout_ms = 2000) {
  Peer p;
  EXPECT_TRUE(p.listener.is_ok());
  TcpOptions tcp;
  tcp.io_timeout_ms = io_timeout_ms;
  std::atomic<bool> done{false};
  std::thread fake([&] {
    Result<std::unique_ptr<StreamTransport>> t = p.listener.value().accept(tcp);
    if (!t.is_ok()) return;
    (void)t.value()->send(bytes);
    while (!done)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  Joiner join_fake{fake};
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(p.to(), tcp);
  EXPECT_TRUE(t.is_ok());
  Status s = StreamClientSession::start(t.value().get(), {}).status();
  done = true;
  fake.join();
  return s;
}

TEST(StreamNetMalformed, TheClientRefusesWhatAServerSendsWrongAndTimesOutOnSilence) {
  const Db d = make_db("torus");
  const Bytes base = d.db->base_message().value();
  Status s = client_against(header(2, 0x7fffffffu));
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  s = client_against(Bytes(base.begin(), base.begin() + 20), 300);  // truncated, then silence
  EXPECT_EQ(s.kind(), ErrorKind::kIo) << s.message();
  EXPECT_NE(s.message().find("within 300 ms"), std::string::npos) << s.message();
  s = client_against(encode_end_of_answer(0));  // wrong type for a base
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  Bytes scene_wrong = base;  // a base, then a view where the scene should be
  const Bytes view = encode_view_request(refine_everything(d.b));
  scene_wrong.insert(scene_wrong.end(), view.begin(), view.end());
  s = client_against(scene_wrong);
  EXPECT_EQ(s.kind(), ErrorKind::kInvalidInput) << s.message();
  s = client_against(Bytes(), 300);  // a server that never speaks
  EXPECT_EQ(s.kind(), ErrorKind::kIo) << s.message();
}

TEST(StreamNetMalformed, NobodyListeningIsAnIoErrorNamingTheAddress) {
  Peer p;  // take a free port, then close it
  ASSERT_TRUE(p.listener.is_ok());
  const LoopbackAddress to = p.to();
  p.listener = io_error("closed");
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(to);
  ASSERT_FALSE(t.is_ok());
  EXPECT_EQ(t.status().kind(), ErrorKind::kIo);
  EXPECT_NE(t.status().message().find("127.0.0.1:" + std::to_string(to.port)), std::string::npos)
      << t.status().message();
}

TEST(StreamNetAddress, ParsesLoopbackOnly) {
  EXPECT_EQ(parse_loopback_address("127.0.0.1:4000").value().port, 4000);
  EXPECT_EQ(parse_loopback_address("localhost:0").value().host, "127.0.0.1");
  EXPECT_EQ(parse_loopback_address("127.1.2.3:65535").value().host, "127.1.2.3");
  for (const char* bad : {"", "4000", ":4000", "127.0.0.1:", "127.0.0.1:65536", "127.0.0.1:-1",
                          "127.0.0.1:40x", "10.0.0.1:4000", "example.org:80", "127.0.0.1"}) {
    Result<LoopbackAddress> a = parse_loopback_address(bad);
    EXPECT_FALSE(a.is_ok()) << bad;
    if (!a.is_ok()) {
      EXPECT_EQ(a.status().kind(), ErrorKind::kUsage) << bad;
    }
  }
}

// ---- the resume and scene codecs ----

TEST(StreamResumeMessage, RoundTripsAndRefusesTruncationsFlipsAndBadIds) {
  const Db d = make_db("torus");
  const uint32_t roots = static_cast<uint32_t>(d.b.h.root_count());
  // A real client's leaves after a partial session.
  Result<StreamSession> session = StreamSession::create(*d.db, StreamReplayOptions());
  ASSERT_TRUE(session.is_ok());
  const std::vector<CameraFrame> path = scan_path(d.db->sphere, 60);
  for (size_t i = 0; i < 40; ++i)
    ASSERT_TRUE(session.value().frame(path[i], d.db->sphere).is_ok());
  std::vector<HierarchyNodeId> leaves;
  const VertexHierarchy& partial = session.value().client().partial();
  for (uint32_t v = 0; v < partial.node_count(); ++v) {
    if (partial.is_leaf(v)) leaves.push_back(session.value().client().id_of(v));
  }
  Result<Bytes> m = encode_resume_message(leaves, d.db->widths, roots);
  ASSERT_TRUE(m.is_ok());
  const uint64_t max = d.b.h.node_count();
  Result<std::vector<HierarchyNodeId>> back =
      decode_resume_message(m.value().data(), m.value().size(), d.db->widths, roots, max);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  std::sort(leaves.begin(), leaves.end());
  EXPECT_EQ(back.value(), leaves);
  EXPECT_EQ(encode_resume_message(back.value(), d.db->widths, roots).value(), m.value());
  EXPECT_EQ(resume_leaf_count(m.value().data(), m.value().size()).value(), leaves.size());
  // A server resumes from them to the same tags.
  StreamServerSession resumed(*d.db, StreamServerOptions());
  ASSERT_TRUE(resumed.resume(back.value()).is_ok());
  EXPECT_EQ(resumed.resumed(), session.value().server().sent().size());
  for (size_t k = 0; k < d.b.h.node_count(); ++k)
    ASSERT_EQ(resumed.tags().test(k), session.value().server().tags().test(k)) << k;
  EXPECT_EQ(resumed.memory().front_nodes, session.value().server().memory().front_nodes);

  const Bytes& bytes = m.value();
  auto decodes = [&](const Bytes& b) {
    return decode_resume_message(b.data(), b.size(), d.db->widths, roots, max).is_ok();
  };
  for (size_t n = 0; n < bytes.size(); ++n)
    EXPECT_FALSE(decodes(Bytes(bytes.begin(), bytes.begin() + static_cast<ptrdiff_t>(n)))) << n;
  for (size_t bit = 0; bit < kStreamHeaderBytes * 8; ++bit) {
    Bytes flipped = bytes;
    flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_FALSE(decodes(flipped)) << "header bit " << bit;
  }
  Bytes longer = bytes;
  longer.push_back(0);
  EXPECT_FALSE(decodes(longer));
  // More leaves than the server's nodes: refused on the count.
  EXPECT_FALSE(
      decode_resume_message(bytes.data(), bytes.size(), d.db->widths, roots, leaves.size() - 1)
          .is_ok());
  // Out of order, repeated, heap id 0, a tree id out of range.
  const StreamIdWidths& w = d.db->widths;
  auto raw = [&](const std::vector<HierarchyNodeId>& ids) {
    Bytes payload;
    const uint32_t n = static_cast<uint32_t>(ids.size());
    for (int k = 0; k < 4; ++k)
      payload.push_back(static_cast<uint8_t>(n >> (8 * k)));
    BitWriter bw(&payload);
    for (const HierarchyNodeId& id : ids) {
      bw.write(id.tree, w.tree_bits);
      bw.write(static_cast<uint32_t>(id.heap), w.node_bits);
    }
    bw.finish();
    Bytes out = header(5, static_cast<uint32_t>(payload.size()));
    out.insert(out.end(), payload.begin(), payload.end());
    return out;
  };
  ASSERT_TRUE(decodes(raw({{0, 2}, {0, 3}})));
  EXPECT_FALSE(decodes(raw({{0, 3}, {0, 2}})));
  EXPECT_FALSE(decodes(raw({{0, 2}, {0, 2}})));
  EXPECT_FALSE(decodes(raw({{0, 0}})));
  if (roots < (1u << w.tree_bits)) {
    EXPECT_FALSE(decodes(raw({{roots, 1}})));
  }
  EXPECT_FALSE(encode_resume_message({{0, 2}, {0, 2}}, w, roots).is_ok());
  // The hello: no widths needed, zero leaves.
  const Bytes hello = encode_hello();
  EXPECT_EQ(resume_leaf_count(hello.data(), hello.size()).value(), 0u);
  EXPECT_TRUE(decode_resume_message(hello.data(), hello.size(), w, roots, 0).is_ok());
}

TEST(StreamResumeMessage, TheServerRefusesLeavesThatAreNotAFront) {
  const Db d = make_db("torus");
  const VertexHierarchy& h = d.b.h;
  std::vector<HierarchyNodeId> roots;
  for (uint32_t r = 0; r < h.root_count(); ++r)
    roots.push_back({r, 1});
  StreamServerSession ok(*d.db, StreamServerOptions());
  EXPECT_TRUE(ok.resume(roots).is_ok());  // the base mesh: nothing held
  EXPECT_EQ(ok.resumed(), 0u);
  uint32_t split_root = 0;
  while (h.is_leaf(split_root))
    ++split_root;
  auto refused = [&](std::vector<HierarchyNodeId> ids) {
    StreamServerSession s(*d.db, StreamServerOptions());
    const Status st = s.resume(ids);
    return !st.is_ok() && st.kind() == ErrorKind::kInvalidInput;
  };
  std::vector<HierarchyNodeId> missing_tree(roots.begin() + 1, roots.end());
  EXPECT_TRUE(refused(missing_tree));
  std::vector<HierarchyNodeId> one_child = roots;  // a split root with one child only
  one_child[split_root] = {split_root, 2};
  EXPECT_TRUE(refused(one_child));
  std::vector<HierarchyNodeId> above = roots;  // a leaf above another
  above.push_back({split_root, 2});
  EXPECT_TRUE(refused(above));
  std::vector<HierarchyNodeId> no_node = roots;
  uint32_t leaf_root = 0;
  while (leaf_root < h.root_count() && !h.is_leaf(leaf_root))
    ++leaf_root;
  if (leaf_root < h.root_count()) {
    no_node[leaf_root] = {leaf_root, 2};  // a real leaf has no children
    no_node.push_back({leaf_root, 3});
    EXPECT_TRUE(refused(no_node));
  }
  // After an answer a session cannot resume.
  StreamServerSession used(*d.db, StreamServerOptions());
  const Bytes view = encode_view_request(refine_everything(d.b));
  ASSERT_TRUE(used.answer(view.data(), view.size()).is_ok());
  EXPECT_FALSE(used.resume(roots).is_ok());
}

TEST(StreamSceneMessage, RoundTripsAndRefusesBadSpheres) {
  BoundingSphere s;
  s.center = {1, -2, 3.5f};
  s.radius = 4;
  const Bytes m = encode_scene_message(s);
  EXPECT_EQ(m.size(), kStreamHeaderBytes + 16);
  Result<BoundingSphere> back = decode_scene_message(m.data(), m.size());
  ASSERT_TRUE(back.is_ok());
  EXPECT_EQ(back.value().center, s.center);
  EXPECT_EQ(back.value().radius, s.radius);
  for (size_t n = 0; n < m.size(); ++n)
    EXPECT_FALSE(decode_scene_message(m.data(), n).is_ok());
  for (float r : {0.0f, -1.0f, std::numeric_limits<float>::infinity()}) {
    BoundingSphere bad = s;
    bad.radius = r;
    const Bytes b = encode_scene_message(bad);
    EXPECT_FALSE(decode_scene_message(b.data(), b.size()).is_ok()) << r;
  }
  BoundingSphere nan = s;
  nan.center[1] = std::numeric_limits<float>::quiet_NaN();
  const Bytes b = encode_scene_message(nan);
  EXPECT_FALSE(decode_scene_message(b.data(), b.size()).is_ok());
}

}  // namespace
}  // namespace lodbake
