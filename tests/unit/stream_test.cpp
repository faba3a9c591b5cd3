// Mode stream (lib/replay/stream_*.h): a full session at tolerance 0 ends
// with the client holding exactly the input mesh on a mesh with a boundary
// and on meshes of genus > 0; no split is sent twice; the windowed active
// tags equal a plain bit array at every frame of a camera path; a second
// round over the same path costs next to nothing; the packet codec round
// trips and rejects every truncation, every header bit flip and trailing
// bytes; the client refuses packets it cannot take.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/support/bit_packing.h"
#include "lib/replay/stream_session.h"
#include "tests/unit/stream_test_support.h"
#include "tests/unit/test_support.h"
#include "tests/unit/wire_corruption_support.h"

namespace lodbake {
namespace {

using namespace stream_test;

class StreamOnMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(StreamOnMesh, FullSessionEndsAtTheInputMeshWithNothingSentTwice) {
  const Built b = build_mesh(GetParam());
  Result<StreamHierarchy> db = StreamHierarchy::create(b.h, b.data);
  ASSERT_TRUE(db.is_ok()) << db.status().message();
  Result<StreamSession> session = StreamSession::create(db.value(), StreamReplayOptions());
  ASSERT_TRUE(session.is_ok()) << session.status().message();
  StreamSession& s = session.value();
  Result<StreamFrameStats> stats = s.step(refine_everything(b));
  ASSERT_TRUE(stats.is_ok()) << stats.status().message();
  EXPECT_EQ(stats.value().requests, 1u);
  EXPECT_EQ(stats.value().missing, 0u);
  const size_t splits = b.h.node_count() - b.input.positions.size();
  EXPECT_EQ(stats.value().packets, splits);
  EXPECT_EQ(s.server().sent().size(), splits);

  // Every split exactly once, by the client's count.
  const std::map<HierarchyNodeId, uint32_t> ids = id_map(db.value());
  std::vector<int> count(b.h.node_count(), 0);
  for (const HierarchyNodeId& id : s.client().received()) {
    auto it = ids.find(id);
    ASSERT_NE(it, ids.end());
    ++count[it->second];
  }
  for (uint32_t i = 0; i < b.h.node_count(); ++i)
    EXPECT_EQ(count[i], b.h.is_leaf(i) ? 0 : 1) << "node " << i;

  // The client's mesh, in input vertex ids, is the input mesh: same
  // oriented triangles, same positions.
  const StreamClient& c = s.client();
  ASSERT_EQ(c.refiner().front_size(), b.input.positions.size());
  std::vector<Triangle> tris;
  for (const Triangle& t : c.refiner().triangles()) {
    Triangle u;
    for (int k = 0; k < 3; ++k) {
      const uint32_t node = ids.at(c.id_of(t[k]));
      ASSERT_TRUE(b.h.is_leaf(node));
      u[k] = b.h.input_vertex[node];
      EXPECT_EQ(c.partial().position[t[k]], b.input.positions[u[k]]);
    }
    tris.push_back(u);
  }
  EXPECT_EQ(sorted_canonical(tris), sorted_canonical(b.input.triangles));
  EXPECT_TRUE(check_vhier_mesh(c.refiner()).empty());

  // Nothing is left to ask for: the next frame costs nothing.
  Result<StreamFrameStats> again = s.step(refine_everything(b));
  ASSERT_TRUE(again.is_ok());
  EXPECT_EQ(again.value().uplink_bytes + again.value().downlink_bytes, 0u);

  // The baseline's prefix is then the whole progressive mesh.
  Result<StreamBaseline> base =
      view_independent_baseline(db.value(), s.server().sent(), s.base_bytes());
  ASSERT_TRUE(base.is_ok()) << base.status().message();
  EXPECT_EQ(base.value().prefix, splits);
  EXPECT_EQ(base.value().bytes, base.value().full_bytes);
  EXPECT_EQ(base.value().prefix_bits, base.value().sent_bits);
}

// The active tags as a plain bit array, rebuilt from what the server sent.
std::vector<uint8_t> plain_tags(const VertexHierarchy& h, const std::vector<uint32_t>& sent) {
  std::vector<uint8_t> tags(h.node_count(), 0);
  for (uint32_t r = 0; r < h.root_count(); ++r)
    tags[r] = h.is_leaf(r) ? 0 : 1;
  for (uint32_t s : sent) {
    tags[s] = 0;
    for (uint32_t c : {h.first_child[s], h.first_child[s] + 1})
      tags[c] = h.is_leaf(c) ? 0 : 1;
  }
  return tags;
}

TEST_P(StreamOnMesh, CameraPathWindowedTagsEqualAPlainBitArray) {
  const Built b = build_mesh(GetParam());
  Result<StreamHierarchy> db = StreamHierarchy::create(b.h, b.data);
  ASSERT_TRUE(db.is_ok()) << db.status().message();
  Result<StreamSession> session = StreamSession::create(db.value(), StreamReplayOptions());
  ASSERT_TRUE(session.is_ok()) << session.status().message();
  StreamSession& s = session.value();
  const BoundingSphere sphere = bounding_sphere(b.h.position);
  const std::vector<CameraFrame> path = scan_path(sphere, 60);
  uint64_t first_round = 0, second_round = 0;
  size_t collapses = 0, max_triangles = 0;
  for (int round = 0; round < 2; ++round) {
    for (size_t i = 0; i < path.size(); ++i) {
      Result<StreamFrameStats> stats = s.frame(path[i], sphere);
      ASSERT_TRUE(stats.is_ok()) << "frame " << i << ": " << stats.status().message();
      const StreamFrameStats& f = stats.value();
      EXPECT_LE(f.requests, 1u) << "frame " << i;
      EXPECT_EQ(f.missing, 0u) << "frame " << i;
      (round == 0 ? first_round : second_round) += f.uplink_bytes + f.downlink_bytes;
      collapses += f.collapses;
      max_triangles = std::max(max_triangles, f.triangles);
      const std::vector<std::string> problems = check_vhier_mesh(s.client().refiner());
      ASSERT_TRUE(problems.empty()) << "frame " << i << ": " << problems.front();

      const std::vector<uint8_t> plain = plain_tags(b.h, s.server().sent());
      const ActiveTagWindow& w = s.server().tags();
      size_t ones = 0;
      for (size_t k = 0; k < plain.size(); ++k) {
        ASSERT_EQ(w.test(k), plain[k] != 0) << "frame " << i << ", node " << k;
        if (plain[k]) {
          ++ones;
          ASSERT_GE(k, w.win_min());
          ASSERT_LT(k, w.win_max());
        }
      }
      EXPECT_EQ(ones, w.set_count());
      if (ones > 0) {
        EXPECT_TRUE(plain[w.win_min()] && plain[w.win_max() - 1]) << "window not tight";
      }
      EXPECT_GE(w.buffer_bytes() * 8, w.win_max() - w.win_min());
    }
  }
  // Nothing twice over both rounds.
  std::vector<uint32_t> sent = s.server().sent();
  std::sort(sent.begin(), sent.end());
  EXPECT_EQ(std::adjacent_find(sent.begin(), sent.end()), sent.end());
  EXPECT_GT(first_round, s.base_bytes());
  EXPECT_GT(collapses, 0u);
  EXPECT_GT(max_triangles, b.h.base.triangle_count());
  // The paper's Figure 7: the second look around needs (next to) nothing.
  EXPECT_LE(second_round * 20, first_round);
  const StreamServerMemory m = s.server().memory();
  EXPECT_LT(m.window_bytes, m.front_bytes);
}

INSTANTIATE_TEST_SUITE_P(Meshes, StreamOnMesh,
                         ::testing::Values("cgal_mushroom.off",  // boundary
                                           "cgal_elephant.off",  // genus 3
                                           "torus"));            // genus 1

TEST(StreamTagWindow, MatchesAPlainBitArrayUnderRandomSetsAndClears) {
  std::mt19937 rng(7);
  ActiveTagWindow w;
  std::vector<uint8_t> plain(5000, 0);
  // Mostly rightward motion, as a hierarchy's front moves, plus noise.
  size_t centre = 0, widest = 0;
  for (int step = 0; step < 40000; ++step) {
    centre = std::min<size_t>(plain.size() - 200, centre + (rng() % 3 == 0 ? 1 : 0));
    const size_t i = centre + rng() % 200;
    if (rng() % 2) {
      w.set(i);
      plain[i] = 1;
    } else {
      w.clear(i);
      plain[i] = 0;
    }
    widest = std::max(widest, w.win_max() - w.win_min());
    if (step % 97 == 0) {
      for (size_t k = 0; k < plain.size(); ++k)
        ASSERT_EQ(w.test(k), plain[k] != 0) << "step " << step << ", bit " << k;
      size_t first = w.win_max();
      for (size_t k = w.win_min(); k < w.win_max(); ++k) {
        if (plain[k]) {
          first = k;
          break;
        }
      }
      if (w.set_count() > 0) {
        EXPECT_EQ(first, w.win_min());
      }
      EXPECT_EQ(w.next(0), w.set_count() > 0 ? w.win_min() : w.win_max());
    }
  }
  // The buffer never exceeds twice the widest window (in words) seen.
  EXPECT_LE(w.buffer_bytes(), 2 * (widest / 64 + 2) * 8);
}

// Messages of every kind from a real session on the torus.
struct Messages {
  Built b;
  std::unique_ptr<StreamHierarchy> db;
  Bytes view, base, vsplits, end;
};

Messages messages() {
  Messages m;
  m.b = build(test_meshes::torus(12, 8));
  Result<StreamHierarchy> db = StreamHierarchy::create(m.b.h, m.b.data);
  EXPECT_TRUE(db.is_ok());
  m.db = std::make_unique<StreamHierarchy>(std::move(db).value());
  m.view = encode_view_request(refine_everything(m.b));
  m.base = m.db->base_message().value();
  StreamServerSession server(*m.db, StreamServerOptions());
  Result<std::vector<Bytes>> answer = server.answer(m.view.data(), m.view.size());
  EXPECT_TRUE(answer.is_ok());
  EXPECT_EQ(answer.value().size(), 2u);
  m.vsplits = answer.value()[0];
  m.end = answer.value()[1];
  return m;
}

// Decodes `bytes` as the message kind of `like`; true when accepted.
bool decodes(const Messages& m, const Bytes& like, const Bytes& bytes) {
  const uint32_t roots = static_cast<uint32_t>(m.b.h.root_count());
  if (&like == &m.view) return decode_view_request(bytes.data(), bytes.size()).is_ok();
  if (&like == &m.base) return decode_base_message(bytes.data(), bytes.size()).is_ok();
  if (&like == &m.vsplits) {
    return decode_vsplit_message(bytes.data(), bytes.size(), m.db->widths, roots).is_ok();
  }
  return decode_end_of_answer(bytes.data(), bytes.size()).is_ok();
}

// A torus whose hierarchy has damaged cut vertices that still pass the
// structural checks: both cuts of a root's split on one leaf of another tree.
Built torus_with_damaged_cuts(int rings, int sides) {
  Built b = build(test_meshes::torus(rings, sides));
  const VertexHierarchy& h = b.h;
  uint32_t s = kNoNode, leaf = kNoNode;
  for (uint32_t r = 0; r < h.root_count() && s == kNoNode; ++r) {
    if (!h.is_leaf(r)) s = r;
  }
  EXPECT_NE(s, kNoNode);
  for (uint32_t v = 0; v < h.node_count() && leaf == kNoNode && s != kNoNode; ++v) {
    uint32_t top = v;
    while (h.parent[top] != kNoNode)
      top = h.parent[top];
    if (h.is_leaf(v) && top != s && !h.is_leaf(top)) leaf = v;
  }
  EXPECT_NE(leaf, kNoNode);
  if (leaf == kNoNode) return b;
  b.h.cut_left[s] = b.h.cut_right[s] = leaf;
  EXPECT_EQ(validate_hierarchy(b.h), std::vector<std::string>{});
  return b;
}

// The damaged cuts make the partial order ask for a node that cannot split:
// the server refuses the data as invalid input (exit 3), not as a runtime
// failure.
TEST(StreamServer, DamagedCutVerticesAreInvalidInput) {
  for (int rings : {8, 24}) {
    SCOPED_TRACE(rings);
    const Built b = torus_with_damaged_cuts(rings, rings * 2 / 3);
    Result<StreamHierarchy> db = StreamHierarchy::create(b.h, b.data);
    ASSERT_TRUE(db.is_ok()) << db.status().message();
    Result<StreamSession> session = StreamSession::create(db.value(), StreamReplayOptions());
    ASSERT_TRUE(session.is_ok()) << session.status().message();
    Result<StreamFrameStats> stats = session.value().step(refine_everything(b));
    ASSERT_FALSE(stats.is_ok());
    EXPECT_EQ(stats.status().kind(), ErrorKind::kInvalidInput) << stats.status().message();
    EXPECT_NE(stats.status().message().find("which is not splittable"), std::string::npos)
        << stats.status().message();
  }
}

// tests/data/containers/torus_vhie_damaged_cuts.lbk (the CLI cases' damaged
// input for mode stream) is BASE + VHIE + RFIN of the 8 x 5 torus above;
// LODBAKE_WRITE_CONTAINERS=<dir> writes it there instead of comparing.
TEST(StreamServer, DamagedCliContainerIsTheCurrentEncoding) {
  const Built b = torus_with_damaged_cuts(8, 5);
  Result<Bytes> base = encode_base(b.h.base, BaseEncodeOptions());
  Result<Bytes> vhie = encode_vhie(b.h);
  Result<Bytes> rfin = encode_rfin(b.h, b.data);
  ASSERT_TRUE(base.is_ok() && vhie.is_ok() && rfin.is_ok());
  ContainerWriter writer;
  ASSERT_TRUE(writer.add_section(kBaseTag, std::move(base).value(), true).is_ok());
  ASSERT_TRUE(writer.add_section(kVhieTag, std::move(vhie).value(), true).is_ok());
  ASSERT_TRUE(writer.add_section(kRfinTag, std::move(rfin).value(), true).is_ok());
  Result<Bytes> file = writer.finish();
  ASSERT_TRUE(file.is_ok());
  EXPECT_LT(file.value().size(), 4096u);
  const std::string name = "torus_vhie_damaged_cuts.lbk";
  const std::string write_dir = testing_util::env_or("LODBAKE_WRITE_CONTAINERS", "");
  if (!write_dir.empty()) {
    ASSERT_TRUE(write_file_atomic(write_dir + "/" + name, file.value()).is_ok());
  } else {
    const std::string dir =
        testing_util::env_or_fail("LODBAKE_SOURCE_DIR") + "/tests/data/containers/";
    EXPECT_EQ(testing_util::read_bytes(dir + name), file.value()) << name;
  }
}

TEST(StreamPackets, RoundTripAndBitWidths) {
  const Messages m = messages();
  const ViewRequest view = refine_everything(m.b);
  EXPECT_EQ(m.view.size(), kStreamHeaderBytes + kViewRequestPayloadBytes);
  EXPECT_TRUE(decode_view_request(m.view.data(), m.view.size()).value() == view);

  Result<BaseMessage> base = decode_base_message(m.base.data(), m.base.size());
  ASSERT_TRUE(base.is_ok()) << base.status().message();
  EXPECT_EQ(base.value().mesh.positions, m.b.h.base.positions);
  EXPECT_EQ(base.value().mesh.triangles, m.b.h.base.triangles);
  EXPECT_EQ(base.value().node_bits, static_cast<int>(hierarchy_shape(m.b.h).depth));
  EXPECT_EQ(encode_base_message(base.value()).value(), m.base);

  const uint32_t roots = static_cast<uint32_t>(m.b.h.root_count());
  Result<std::vector<VsplitPacket>> packets =
      decode_vsplit_message(m.vsplits.data(), m.vsplits.size(), m.db->widths, roots);
  ASSERT_TRUE(packets.is_ok()) << packets.status().message();
  ASSERT_EQ(packets.value().size(), (m.b.h.node_count() - roots) / 2);
  uint64_t bits = 0;
  for (const VsplitPacket& p : packets.value()) {
    const uint32_t s = id_map(*m.db).at(p.vs);
    EXPECT_TRUE(p == m.db->packet(s));
    bits += vsplit_packet_bits(p, m.db->widths);
  }
  EXPECT_EQ(m.vsplits.size(), kStreamHeaderBytes + 4 + (bits + 7) / 8);
  EXPECT_EQ(encode_vsplit_message(packets.value(), m.db->widths, roots).value(), m.vsplits);
  EXPECT_EQ(decode_end_of_answer(m.end.data(), m.end.size()).value(), packets.value().size());
  // Topology: three ids of tree + node bits each (the paper: 3 x 32).
  const HierarchyShape shape = hierarchy_shape(m.b.h);
  EXPECT_EQ(m.db->widths.id_bits(), shape.tree_bits + static_cast<int>(shape.depth));
}

TEST(StreamPackets, RejectsTruncationsHeaderBitFlipsAndTrailingBytes) {
  const Messages m = messages();
  for (const Bytes* message : {&m.view, &m.base, &m.vsplits, &m.end}) {
    expect_refuses_corruptions(*message, kStreamHeaderBytes,
                               [&](const Bytes& b) { return decodes(m, *message, b); });
  }
  // A newer version is unsupported, not malformed.
  Bytes newer = m.vsplits;
  newer[0] = 0xB2;
  EXPECT_EQ(stream_message_type(newer.data(), newer.size()).status().kind(),
            ErrorKind::kUnsupported);
}

TEST(StreamPackets, RandomPayloadCorruptionNeverCrashes) {
  const Messages m = messages();
  std::mt19937 rng(11);
  for (int i = 0; i < 3000; ++i) {
    for (const Bytes* message : {&m.view, &m.base, &m.vsplits}) {
      Bytes bad = *message;
      const size_t k = kStreamHeaderBytes + rng() % (bad.size() - kStreamHeaderBytes);
      bad[k] ^= static_cast<uint8_t>(1u << (rng() % 8));
      (void)decodes(m, *message, bad);  // any result, no crash (ASan build)
    }
  }
}

TEST(StreamClientTest, RefusesPacketsItCannotTake) {
  const Messages m = messages();
  Result<StreamClient> client = StreamClient::create(m.base.data(), m.base.size());
  ASSERT_TRUE(client.is_ok()) << client.status().message();
  // Vsplits before their parents' would name nodes the client does not hold.
  const uint32_t roots = static_cast<uint32_t>(m.b.h.root_count());
  std::vector<VsplitPacket> packets =
      decode_vsplit_message(m.vsplits.data(), m.vsplits.size(), m.db->widths, roots).value();
  std::vector<VsplitPacket> last{packets.back()};
  const Bytes orphan = encode_vsplit_message(last, m.db->widths, roots).value();
  if (packets.back().vs.heap > 1) {
    EXPECT_FALSE(client.value().receive(orphan.data(), orphan.size()).is_ok());
  }
  ASSERT_TRUE(client.value().receive(m.vsplits.data(), m.vsplits.size()).is_ok());
  ASSERT_TRUE(client.value().receive(m.end.data(), m.end.size()).is_ok());
  // The same packets again: sent twice.
  const Status twice = client.value().receive(m.vsplits.data(), m.vsplits.size());
  EXPECT_FALSE(twice.is_ok());
  EXPECT_NE(twice.message().find("twice"), std::string::npos) << twice.message();
  // An end of answer that miscounts.
  const Bytes wrong = encode_end_of_answer(3);
  EXPECT_FALSE(client.value().receive(wrong.data(), wrong.size()).is_ok());
  // A view request is not a downlink message.
  EXPECT_FALSE(client.value().receive(m.view.data(), m.view.size()).is_ok());
}

}  // namespace
}  // namespace lodbake

namespace lodbake {
namespace {
using namespace stream_test;

// With LODBAKE_STREAM_CORPUS_OUT set, writes the seeds of
// tests/fuzz/corpus/stream_packets there (how they were made); otherwise
// only checks that the seeds decode.
TEST(StreamPackets, FuzzCorpusSeeds) {
  const Messages m = messages();
  std::vector<std::pair<std::string, Bytes>> seeds = {
      {"view.bin", m.view}, {"base_torus.bin", m.base}, {"end.bin", m.end}};
  const uint32_t contexts[3][2] = {{15, 16}, {18, 11}, {1, 40}};
  for (const auto& c : contexts) {
    StreamIdWidths widths;
    widths.tree_bits = bits_for_count(c[0]);
    widths.node_bits = static_cast<int>(c[1]);
    std::vector<VsplitPacket> packets(3);
    packets[0].vs = {c[0] - 1, 1};
    packets[0].cut_left = {0, 5};
    packets[0].position = {1.5f, -2, 0.25f};
    packets[0].left.internal = true;
    packets[0].left.record = m.db->records[0];
    packets[1].vs = {0, 3};
    packets[1].cut_left = {0, 9};
    packets[1].cut_right = {c[0] - 1, (uint64_t{1} << (c[1] - 1)) + 1};
    packets[1].right.internal = true;
    packets[2].vs = {0, uint64_t{1} << (c[1] - 2)};
    packets[2].cut_right = {0, 2};
    Result<Bytes> bytes = encode_vsplit_message(packets, widths, c[0]);
    ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
    ASSERT_TRUE(
        decode_vsplit_message(bytes.value().data(), bytes.value().size(), widths, c[0]).is_ok());
    seeds.push_back(
        {"vsplits_" + std::to_string(c[0]) + "_" + std::to_string(c[1]) + ".bin", bytes.value()});
  }
  // Resume messages (hello, and leaves under each context) and a scene.
  seeds.push_back({"hello.bin", encode_hello()});
  for (const auto& c : contexts) {
    StreamIdWidths widths;
    widths.tree_bits = bits_for_count(c[0]);
    widths.node_bits = static_cast<int>(c[1]);
    const std::vector<HierarchyNodeId> leaves = {
        {0, 2}, {0, 7}, {0, (uint64_t{1} << (c[1] - 1)) + 1}, {c[0] - 1, 1}};
    Result<Bytes> bytes = encode_resume_message(leaves, widths, c[0]);
    ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
    ASSERT_TRUE(
        decode_resume_message(bytes.value().data(), bytes.value().size(), widths, c[0], 1u << 20)
            .is_ok());
    seeds.push_back(
        {"resume_" + std::to_string(c[0]) + "_" + std::to_string(c[1]) + ".bin", bytes.value()});
  }
  BoundingSphere sphere;
  sphere.center = {0.5f, -1, 2};
  sphere.radius = 3;
  seeds.push_back({"scene.bin", encode_scene_message(sphere)});
  Bytes newer = m.end;
  newer[0] = 0xB2;
  seeds.push_back({"newer_version.bin", newer});
  seeds.push_back({"truncated_base.bin", Bytes(m.base.begin(), m.base.begin() + 20)});
  const char* out = std::getenv("LODBAKE_STREAM_CORPUS_OUT");
  if (out == nullptr) return;
  for (const auto& [name, bytes] : seeds) {
    FILE* f = std::fopen((std::string(out) + "/" + name).c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
  }
}

}  // namespace
}  // namespace lodbake
