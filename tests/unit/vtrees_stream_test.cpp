// Mode vtrees (lib/replay/vtrees_*.h): a full session at tolerance 0 ends
// with the client holding exactly the input mesh (a mesh with a boundary,
// meshes of genus > 0); no record is sent twice; along a camera path the
// client's visible vertex list is the server's and its triangles are
// VisibleVertexList's for that list; the codec round-trips and rejects
// every truncation, every header bit flip and trailing bytes; the client
// refuses items it cannot take.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>

#include "lib/replay/replay_check.h"
#include "lib/replay/vtrees_session.h"
#include "tests/unit/test_meshes.h"
#include "tests/unit/vtrees_test_support.h"
#include "tests/unit/wire_corruption_support.h"

namespace lodbake {
namespace {
using namespace vtrees_test;

// The server's list applied to VisibleVertexList on the full trees gives
// the structure's own selection; the client's list must be the same.
void expect_client_is_server(const Built& b, const VtreesSession& s, const std::string& at) {
  const VisibleVertexList& list = s.server().list();
  const size_t vertices = b.trees.base_vertex_count + b.trees.split_count();
  for (uint32_t v = 0; v < vertices; ++v)
    ASSERT_EQ(s.client().visible_node(v), list.visible_node(v)) << at << ", vertex " << v;
  ASSERT_EQ(s.client().visible_count(), list.visible_count()) << at;
  ASSERT_EQ(sorted_canonical(s.triangles()), sorted_canonical(list.triangles())) << at;
}

void expect_nothing_twice(const VtreesSession& s) {
  std::vector<uint32_t> sent = s.server().sent_nodes();
  std::sort(sent.begin(), sent.end());
  EXPECT_EQ(std::adjacent_find(sent.begin(), sent.end()), sent.end());
  EXPECT_EQ(sent.size(), s.client().nodes_held());
}

class VtreesOnMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(VtreesOnMesh, FullSessionEndsAtTheInputMeshWithNothingSentTwice) {
  const std::unique_ptr<Built> b = build_mesh(GetParam());
  ASSERT_NE(b->db, nullptr);
  Result<VtreesSession> session = VtreesSession::create(*b->db, VtreesReplayOptions());
  ASSERT_TRUE(session.is_ok()) << session.status().message();
  VtreesSession& s = session.value();
  EXPECT_EQ(sorted_canonical(s.triangles()), sorted_canonical(b->pm.base.triangles));
  Result<VtreesFrameStats> stats = s.step(refine_everything(*b));
  ASSERT_TRUE(stats.is_ok()) << stats.status().message();
  const size_t splits = b->pm.splits.size();
  EXPECT_EQ(stats.value().left_records, splits);
  EXPECT_EQ(stats.value().right_records, splits);
  EXPECT_EQ(stats.value().downs + stats.value().ups, 0u);
  EXPECT_EQ(s.client().nodes_held(), b->trees.node_count());
  expect_nothing_twice(s);
  expect_client_is_server(*b, s, "full");

  // The client's mesh, in input vertex ids, is the input mesh: same
  // oriented triangles, same positions.
  std::vector<Triangle> tris = s.triangles();
  for (Triangle& t : tris) {
    for (uint32_t& v : t) {
      ASSERT_TRUE(s.client().holds(v));
      EXPECT_EQ(s.client().positions()[v], b->input.positions[b->pm.input_vertex[v]]);
      v = b->pm.input_vertex[v];
    }
  }
  EXPECT_EQ(sorted_canonical(tris), sorted_canonical(b->input.triangles));

  // Nothing moves any more: the next frame is one empty frame message.
  Result<VtreesFrameStats> again = s.step(refine_everything(*b));
  ASSERT_TRUE(again.is_ok());
  EXPECT_EQ(again.value().left_records + again.value().downs + again.value().ups, 0u);
  EXPECT_EQ(again.value().downlink_bytes, kVtreesHeaderBytes + 4);
}

TEST_P(VtreesOnMesh, CameraPathClientListAndTrianglesAreTheServersEveryFrame) {
  const std::unique_ptr<Built> b = build_mesh(GetParam());
  ASSERT_NE(b->db, nullptr);
  VtreesReplayOptions options;
  options.max_items_per_message = 50;  // several messages per frame
  Result<VtreesSession> session = VtreesSession::create(*b->db, options);
  ASSERT_TRUE(session.is_ok()) << session.status().message();
  VtreesSession& s = session.value();
  const BoundingSphere sphere = bounding_sphere(b->h.position);
  const std::vector<CameraFrame> path = scan_path(sphere, 60);
  size_t ups = 0, traces = 0, second_round_records = 0, downs = 0, max_triangles = 0;
  for (int round = 0; round < 2; ++round) {
    for (size_t i = 0; i < path.size(); i += 2) {
      Result<VtreesFrameStats> stats = s.frame(path[i], sphere);
      ASSERT_TRUE(stats.is_ok()) << "frame " << i << ": " << stats.status().message();
      const VtreesFrameStats& f = stats.value();
      ups += f.ups;
      downs += f.downs;
      traces += f.traces + f.trace_updates;
      if (round == 1) second_round_records += f.left_records;
      max_triangles = std::max(max_triangles, f.triangles);
      EXPECT_EQ(f.left_records, f.right_records);
      expect_client_is_server(*b, s,
                              "round " + std::to_string(round) + ", frame " + std::to_string(i));
      if (HasFatalFailure()) return;
    }
  }
  expect_nothing_twice(s);
  EXPECT_GT(ups, 0u);
  EXPECT_GT(downs, 0u);  // the second round moves over held nodes
  EXPECT_GT(traces, 0u);
  EXPECT_EQ(second_round_records, 0u);  // the same views again: nothing new
  EXPECT_GT(max_triangles, b->pm.base.triangle_count());
}

INSTANTIATE_TEST_SUITE_P(Meshes, VtreesOnMesh,
                         ::testing::Values("cgal_mushroom.off",  // boundary
                                           "cgal_elephant.off",  // genus 3
                                           "torus"));            // genus 1

// Messages of every kind from a real session on the torus, and a frame
// with every item kind.
struct Messages {
  std::unique_ptr<Built> b;
  Bytes trees, frame, mixed;
};

Messages messages() {
  Messages m;
  m.b = build(test_meshes::torus(12, 8));
  m.trees = m.b->db->trees_message().value();
  Result<VtreesServerSession> server = VtreesServerSession::create(*m.b->db);
  EXPECT_TRUE(server.is_ok());
  // A view that refines part of the torus: records with traces.
  const BoundingSphere sphere = bounding_sphere(m.b->h.position);
  const std::vector<CameraFrame> path = scan_path(sphere, 60);
  const Bytes view =
      encode_view_request(view_request_for(path[40], Viewport(), 0.01f * sphere.radius, 0.5f));
  Result<std::vector<Bytes>> answer = server.value().answer(view.data(), view.size());
  EXPECT_TRUE(answer.is_ok());
  m.frame = answer.value().front();
  std::vector<VtreesItem> items =
      decode_vtrees_frame(m.frame.data(), m.frame.size(), m.b->db->widths).value();
  VtreesItem down, up, update;
  down.kind = VtreesItemKind::kDown;
  down.split = 3;
  up.kind = VtreesItemKind::kUp;
  up.split = static_cast<uint32_t>(m.b->trees.split_count() - 1);
  update.kind = VtreesItemKind::kTraceUpdate;
  update.vertex = static_cast<uint32_t>(m.b->trees.base_vertex_count + 5);
  update.parent = 2;
  items.resize(std::min<size_t>(items.size(), 3));
  items.push_back(down);
  items.push_back(up);
  items.push_back(update);
  m.mixed = encode_vtrees_frame(items, m.b->db->widths).value();
  return m;
}

bool decodes(const Messages& m, const Bytes& like, const Bytes& bytes) {
  if (&like == &m.trees) return decode_vtrees_trees(bytes.data(), bytes.size()).is_ok();
  return decode_vtrees_frame(bytes.data(), bytes.size(), m.b->db->widths).is_ok();
}

TEST(VtreesRecords, RoundTripAndRecordSizes) {
  const Messages m = messages();
  const VtreesWidths& w = m.b->db->widths;
  Result<VtreesTreesMessage> trees = decode_vtrees_trees(m.trees.data(), m.trees.size());
  ASSERT_TRUE(trees.is_ok()) << trees.status().message();
  EXPECT_TRUE(trees.value().widths == w);
  uint64_t bits = 0;
  for (uint32_t v = 0; v < m.b->trees.base_vertex_count; ++v) {
    EXPECT_TRUE(trees.value().base[v] == vtrees_node_record(m.b->trees, v));
    bits += vtrees_record_bits(trees.value().base[v], VertexTreeNodeKind::kBase, w);
  }
  EXPECT_EQ(m.trees.size(), kVtreesHeaderBytes + 12 + (bits + 7) / 8);
  EXPECT_EQ(encode_vtrees_trees(trees.value()).value(), m.trees);

  for (const Bytes* message : {&m.frame, &m.mixed}) {
    Result<std::vector<VtreesItem>> items =
        decode_vtrees_frame(message->data(), message->size(), w);
    ASSERT_TRUE(items.is_ok()) << items.status().message();
    bits = 0;
    size_t traces = 0;
    for (const VtreesItem& it : items.value()) {
      bits += kVtreesItemTagBits;
      if (it.kind == VtreesItemKind::kSplit) {
        const uint32_t node = w.base_count + 2 * it.split;
        VtreesNodeRecord left = it.left, right = it.right;
        traces += left.traces.size() + right.traces.size();
        left.traces.clear();
        right.traces.clear();
        EXPECT_TRUE(left == vtrees_node_record(m.b->trees, node));
        EXPECT_TRUE(right == vtrees_node_record(m.b->trees, node + 1));
        bits += vtrees_record_bits(it.left, VertexTreeNodeKind::kLeft, w) +
                vtrees_record_bits(it.right, VertexTreeNodeKind::kRight, w);
      } else if (it.kind == VtreesItemKind::kTraceUpdate) {
        bits += 2 * static_cast<uint64_t>(w.id_bits());
      } else {
        bits += static_cast<uint64_t>(w.split_bits());
      }
    }
    EXPECT_EQ(message->size(), kVtreesHeaderBytes + 4 + (bits + 7) / 8);
    EXPECT_EQ(encode_vtrees_frame(items.value(), w).value(), *message);
    if (message == &m.frame) {
      EXPECT_GT(traces, 0u);
    }
  }
}

TEST(VtreesRecords, RejectsTruncationsHeaderBitFlipsAndTrailingBytes) {
  const Messages m = messages();
  for (const Bytes* message : {&m.trees, &m.frame, &m.mixed}) {
    expect_refuses_corruptions(*message, kVtreesHeaderBytes,
                               [&](const Bytes& b) { return decodes(m, *message, b); });
  }
  // The trees message's fixed fields too: every bit of B, the widths and
  // the reserved bytes. S sets only the id width here; a flip of S that
  // keeps it is another valid message (the client then refuses frames that
  // name splits beyond it), with its own single encoding.
  for (size_t bit = kVtreesHeaderBytes * 8; bit < (kVtreesHeaderBytes + 12) * 8; ++bit) {
    Bytes flipped = m.trees;
    flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    const bool split_count_bit =
        bit >= (kVtreesHeaderBytes + 4) * 8 && bit < (kVtreesHeaderBytes + 8) * 8;
    Result<VtreesTreesMessage> d = decode_vtrees_trees(flipped.data(), flipped.size());
    if (!split_count_bit || !d.is_ok()) {
      EXPECT_FALSE(d.is_ok()) << "accepted a flip of fixed bit " << bit;
      continue;
    }
    EXPECT_NE(d.value().widths.split_count, m.b->db->widths.split_count);
    EXPECT_EQ(d.value().widths.id_bits(), m.b->db->widths.id_bits());
    EXPECT_EQ(encode_vtrees_trees(d.value()).value(), flipped);
  }
  Bytes newer = m.frame;
  newer[0] = 0xC2;
  EXPECT_EQ(vtrees_message_type(newer.data(), newer.size()).status().kind(),
            ErrorKind::kUnsupported);
  // A stream message is not a vertex-tree message.
  const Bytes view = encode_view_request(refine_everything(*m.b));
  EXPECT_FALSE(vtrees_message_type(view.data(), view.size()).is_ok());
}

TEST(VtreesRecords, RandomPayloadCorruptionNeverCrashes) {
  const Messages m = messages();
  std::mt19937 rng(11);
  for (int i = 0; i < 3000; ++i) {
    for (const Bytes* message : {&m.trees, &m.frame, &m.mixed}) {
      Bytes bad = *message;
      const size_t k = kVtreesHeaderBytes + rng() % (bad.size() - kVtreesHeaderBytes);
      bad[k] ^= static_cast<uint8_t>(1u << (rng() % 8));
      (void)decodes(m, *message, bad);  // any result, no crash (ASan build)
    }
  }
}

TEST(VtreesClientTest, RefusesItemsItCannotTake) {
  const Messages m = messages();
  const VtreesWidths& w = m.b->db->widths;
  Result<VtreesClient> client = VtreesClient::create(m.trees.data(), m.trees.size());
  ASSERT_TRUE(client.is_ok()) << client.status().message();
  std::vector<VtreesItem> items = decode_vtrees_frame(m.frame.data(), m.frame.size(), w).value();
  ASSERT_FALSE(items.empty());
  // A move over a split it does not hold.
  VtreesItem down;
  down.kind = VtreesItemKind::kDown;
  down.split = items.front().split;
  const Bytes early = encode_vtrees_frame({down}, w).value();
  EXPECT_FALSE(client.value().receive(early.data(), early.size()).is_ok());

  client = VtreesClient::create(m.trees.data(), m.trees.size());
  // A record whose trace-up was dropped names a vertex it cannot place.
  for (VtreesItem& it : items) {
    if (it.kind != VtreesItemKind::kSplit || (it.left.traces.empty() && it.right.traces.empty()))
      continue;
    std::vector<VtreesItem> stripped(items.begin(), items.end());
    for (VtreesItem& s : stripped) {
      s.left.traces.clear();
      s.right.traces.clear();
    }
    const Bytes bad = encode_vtrees_frame(stripped, w).value();
    const Status refused = client.value().receive(bad.data(), bad.size());
    EXPECT_FALSE(refused.is_ok());
    EXPECT_NE(refused.message().find("trace"), std::string::npos) << refused.message();
    break;
  }
  client = VtreesClient::create(m.trees.data(), m.trees.size());
  ASSERT_TRUE(client.value().receive(m.frame.data(), m.frame.size()).is_ok());
  // The same records again: sent twice.
  const Status twice = client.value().receive(m.frame.data(), m.frame.size());
  EXPECT_FALSE(twice.is_ok());
  EXPECT_NE(twice.message().find("twice"), std::string::npos) << twice.message();
}

// With LODBAKE_VTREES_CORPUS_OUT set, writes the seeds of
// tests/fuzz/corpus/vtrees_records there (how they were made); otherwise
// only checks that the seeds decode.
TEST(VtreesRecords, FuzzCorpusSeeds) {
  const Messages m = messages();
  Bytes newer = m.frame;
  newer[0] = 0xC2;
  std::vector<std::pair<std::string, Bytes>> seeds = {
      {"trees_torus.bin", m.trees},
      {"frame_torus.bin", m.frame},
      {"mixed_torus.bin", m.mixed},
      {"newer_version.bin", newer},
      {"truncated_trees.bin", Bytes(m.trees.begin(), m.trees.begin() + 20)}};
  // Whole downlinks: the trees message, then a frame.
  for (const auto& [name, frame] : {std::make_pair("session_torus.bin", &m.frame),
                                    std::make_pair("session_mixed_torus.bin", &m.mixed)}) {
    Bytes session = m.trees;
    session.insert(session.end(), frame->begin(), frame->end());
    seeds.push_back({name, session});
  }
  // A connection's downlink: trees, scene, a frame, its end of answer.
  Bytes connection = m.trees;
  for (const Bytes& next : {encode_vtrees_scene(bounding_sphere(m.b->h.position)), m.frame,
                            encode_vtrees_end_of_answer(1)}) {
    connection.insert(connection.end(), next.begin(), next.end());
  }
  seeds.push_back({"connection_torus.bin", connection});
  for (size_t i = 0; i < 3; ++i)
    EXPECT_TRUE(decodes(m, i == 0 ? m.trees : m.frame, seeds[i].second));
  const char* out = std::getenv("LODBAKE_VTREES_CORPUS_OUT");
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
