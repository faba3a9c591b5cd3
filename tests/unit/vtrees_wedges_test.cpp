// Mode vtrees on real assets (lib/replay/vtrees_wedges.h): over a camera
// path and at full refinement, every corner of the client's triangles has
// the wedge FrontWedges gives the same face at the same node of the
// complete hierarchy, from the records' wedge data alone, and at full
// refinement the input's own corners; records with wedges round trip and
// refuse truncations and out-of-range values; wedge data the server leaves
// out shows as corners without their wedge or with another one.
#include "lib/replay/vtrees_wedges.h"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/front_wedges.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/replay/replay_check.h"
#include "lib/replay/vtrees_session.h"
#include "lib/replay/vtrees_wedge_check.h"
#include "lib/scene/scene_lods.h"
#include "lib/simplify/wedge_replay.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "tests/unit/asset_hierarchy_support.h"
#include "tests/unit/asset_test_support.h"
#include "tests/unit/test_support.h"
#include "tests/unit/wire_corruption_support.h"

namespace lodbake {
namespace {

using test::kAssets;
using test::read_asset;

// One primitive group's structures; kept behind a pointer since the
// database points at the trees.
struct Built : test::AssetHierarchy {
  VertexTrees trees;
  std::unique_ptr<VtreesDatabase> db;
  std::optional<FrontWedges> front;
  std::optional<VtreesFrontReference> reference;
};

// `change` edits the wedge table before the database takes it.
template <typename Change>
std::vector<std::unique_ptr<Built>> build_all(const std::string& asset, Change change) {
  std::vector<std::unique_ptr<Built>> out;
  for (test::AssetHierarchy& a : test::build_asset_hierarchies(read_asset(kAssets + asset))) {
    auto b = std::make_unique<Built>();
    static_cast<test::AssetHierarchy&>(*b) = std::move(a);
    Result<VertexTrees> trees = build_vertex_trees(b->pm);
    EXPECT_TRUE(trees.is_ok());
    if (!trees.is_ok()) return {};
    b->trees = std::move(trees).value();
    Result<VtreesDatabase> db = VtreesDatabase::create(b->trees, b->h, b->data);
    Result<VtreesWedgeTable> table = vtrees_wedge_table(b->trees, b->pm, b->wedges);
    EXPECT_TRUE(db.is_ok() && table.is_ok()) << table.status().message();
    if (!db.is_ok() || !table.is_ok()) return {};
    b->db = std::make_unique<VtreesDatabase>(std::move(db).value());
    change(&table.value());
    EXPECT_TRUE(b->db->set_wedges(std::move(table).value()).is_ok());
    Result<FrontWedges> front = FrontWedges::create(b->h, b->pm, b->wedges);
    EXPECT_TRUE(front.is_ok()) << front.status().message();
    if (!front.is_ok()) return {};
    b->front.emplace(std::move(front).value());
    Result<VtreesFrontReference> reference =
        VtreesFrontReference::create(b->h, b->trees, *b->db->wedges, *b->front);
    EXPECT_TRUE(reference.is_ok()) << reference.status().message();
    if (!reference.is_ok()) return {};
    b->reference.emplace(std::move(reference).value());
    out.push_back(std::move(b));
  }
  return out;
}

std::vector<std::unique_ptr<Built>> build_all(const std::string& asset) {
  return build_all(asset, [](VtreesWedgeTable*) {});
}

// How many corners of the client's triangles differ from the reference
// (a corner without a wedge counts too).
size_t corners_off(const VtreesClient& client, const VtreesFrontReference& reference) {
  std::vector<uint32_t> slots;
  const std::vector<Triangle> tris = client.triangles(&slots);
  Result<std::vector<std::array<uint32_t, 3>>> corners = client.corner_wedges();
  if (!corners.is_ok()) return tris.size() * 3 + 1;
  size_t off = 0;
  for (size_t f = 0; f < tris.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t want = reference.wedge(slots[f], client.visible_node(tris[f][k]));
      off += want == kNoVertex || corners.value()[f][k] != want;
    }
  }
  return off;
}

ViewRequest everything(const BoundingSphere& sphere) {
  CameraFrame camera;
  camera.eye = {sphere.center[0], sphere.center[1], sphere.center[2] + 3 * sphere.radius};
  camera.target = sphere.center;
  return view_request_for(camera, Viewport(), 0.01f * sphere.radius, 0);
}

class VtreesWedgesTest : public testing::TestWithParam<std::string> {};

TEST_P(VtreesWedgesTest, ClientCornersAreTheServerFrontsOverAPathAndAtTheInput) {
  const std::vector<std::unique_ptr<Built>> all = build_all(GetParam());
  ASSERT_FALSE(all.empty());
  for (const std::unique_ptr<Built>& b : all) {
    Result<VtreesSession> session = VtreesSession::create(*b->db, VtreesReplayOptions());
    ASSERT_TRUE(session.is_ok()) << session.status().message();
    VtreesSession& s = session.value();
    ASSERT_TRUE(s.client().has_wedges());
    EXPECT_EQ(corners_off(s.client(), *b->reference), 0u) << "base mesh";
    const std::vector<CameraFrame> path = orbit_path(b->db->sphere, 60);
    size_t ups = 0, triangles = 0;
    for (size_t i = 0; i < path.size(); i += 3) {
      Result<VtreesFrameStats> f = s.frame(path[i], b->db->sphere);
      ASSERT_TRUE(f.is_ok()) << f.status().message();
      ups += f.value().ups;
      triangles += f.value().triangles;
      ASSERT_EQ(corners_off(s.client(), *b->reference), 0u) << "frame " << i;
      Result<std::vector<std::array<uint32_t, 3>>> corners = s.client().corner_wedges();
      ASSERT_TRUE(corners.is_ok());
      EXPECT_TRUE(corner_wedge_problems(corners.value(), b->wedges).empty()) << "frame " << i;
      EXPECT_TRUE(check_vtrees_wedges(s.client(), *b->reference, b->wedges).empty());
    }
    EXPECT_GT(ups, 0u);  // the path coarsens too
    EXPECT_GT(triangles, 0u);

    // Tolerance 0: every split; each triangle is its face slot's input
    // triangle with the input's corners (WedgeRefiner at full refinement).
    ASSERT_TRUE(s.step(everything(b->db->sphere)).is_ok());
    ASSERT_EQ(s.client().nodes_held(), b->trees.node_count());
    EXPECT_EQ(corners_off(s.client(), *b->reference), 0u) << "full refinement";
    Result<WedgeRefiner> replay = WedgeRefiner::create(b->pm, b->wedges);
    ASSERT_TRUE(replay.is_ok());
    while (replay.value().refiner().applied_splits() < b->pm.splits.size())
      ASSERT_TRUE(replay.value().split_next().is_ok());
    std::vector<uint32_t> slots;
    const std::vector<Triangle> tris = s.client().triangles(&slots);
    const std::vector<std::array<uint32_t, 3>> corners = s.client().corner_wedges().value();
    ASSERT_EQ(tris.size(), replay.value().mesh().triangles.size());
    std::vector<uint8_t> seen(tris.size(), 0);
    for (size_t f = 0; f < tris.size(); ++f) {
      const Triangle& want = replay.value().mesh().triangles[slots[f]];
      ASSERT_EQ(seen[slots[f]]++, 0) << "slot " << slots[f] << " twice";
      int r = 0;
      while (r < 3 && want[r] != tris[f][0])
        ++r;
      ASSERT_LT(r, 3);
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(tris[f][k], want[(r + k) % 3]);
        ASSERT_EQ(corners[f][k], replay.value().corners()[slots[f]][(r + k) % 3]);
      }
    }
  }
}

TEST_P(VtreesWedgesTest, RecordsWithWedgesRoundTripAndRefuseDamage) {
  const std::vector<std::unique_ptr<Built>> all = build_all(GetParam());
  ASSERT_FALSE(all.empty());
  const Built& b = *all.front();
  const VtreesWidths& w = b.db->widths;
  ASSERT_TRUE(w.has_wedges());
  EXPECT_EQ(w.wedge_count, b.wedges.wedge_count());
  const Bytes trees = b.db->trees_message().value();
  Result<VtreesTreesMessage> decoded = decode_vtrees_trees(trees.data(), trees.size());
  ASSERT_TRUE(decoded.is_ok()) << decoded.status().message();
  EXPECT_EQ(decoded.value().widths, w);
  EXPECT_EQ(encode_vtrees_trees(decoded.value()).value(), trees);
  expect_refuses_corruptions(trees, kVtreesHeaderBytes, [](const Bytes& bytes) {
    return decode_vtrees_trees(bytes.data(), bytes.size()).is_ok();
  });

  // Every split as a kSplit item (no traces: the records alone).
  std::vector<VtreesItem> items;
  size_t changes = 0;
  for (uint32_t k = 0; k < b.trees.split_count(); ++k) {
    VtreesItem it;
    it.kind = VtreesItemKind::kSplit;
    it.split = k;
    it.left = b.db->record(b.trees.base_vertex_count + 2 * k);
    it.right = b.db->record(b.trees.base_vertex_count + 2 * k + 1);
    it.wings[0] = b.db->wedges->wings[k][0];
    it.wings[1] = b.db->wedges->wings[k][1];
    changes += it.wings[0].changes.size() + it.wings[1].changes.size();
    items.push_back(std::move(it));
  }
  EXPECT_GT(changes, 0u);
  const Bytes frame = encode_vtrees_frame(items, w).value();
  Result<std::vector<VtreesItem>> back = decode_vtrees_frame(frame.data(), frame.size(), w);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  ASSERT_EQ(back.value(), items);
  uint64_t bits = 0;
  for (const VtreesItem& it : items) {
    bits += kVtreesItemTagBits + vtrees_record_bits(it.left, VertexTreeNodeKind::kLeft, w) +
            vtrees_record_bits(it.right, VertexTreeNodeKind::kRight, w) +
            vtrees_wing_bits(it.wings, w);
  }
  EXPECT_EQ(frame.size(), kVtreesHeaderBytes + 4 + (bits + 7) / 8);

  const std::vector<VtreesItem> few(items.begin(), items.begin() + 3);
  const Bytes small = encode_vtrees_frame(few, w).value();
  expect_refuses_corruptions(small, kVtreesHeaderBytes, [&](const Bytes& bytes) {
    return decode_vtrees_frame(bytes.data(), bytes.size(), w).is_ok();
  });
  // Under a mesh's widths the same bytes do not decode; wedges out of range
  // are refused both ways.
  VtreesWidths plain = w;
  plain.slot_count = plain.wedge_count = 0;
  EXPECT_FALSE(decode_vtrees_frame(small.data(), small.size(), plain).is_ok());
  EXPECT_FALSE(encode_vtrees_frame(few, plain).is_ok());
  VtreesWidths fewer = w;
  fewer.wedge_count = 1;  // every wedge but 0 is then out of range
  EXPECT_FALSE(decode_vtrees_frame(small.data(), small.size(), fewer).is_ok());
  std::vector<VtreesItem> wrong = few;
  wrong[0].left.pairs[0].wedge = w.wedge_count;
  EXPECT_FALSE(encode_vtrees_frame(wrong, w).is_ok());
  wrong = few;
  wrong[0].left.pairs.pop_back();
  EXPECT_FALSE(encode_vtrees_frame(wrong, w).is_ok());
}

// Without the wings' carried changes some corner along a path differs from
// the server's front; without the right records' pairs, full refinement
// has corners with no wedge.
TEST_P(VtreesWedgesTest, MissingWedgeDataShows) {
  size_t off = 0, flagged = 0;
  for (const std::unique_ptr<Built>& b : build_all(GetParam(), [](VtreesWedgeTable* t) {
         for (auto& wings : t->wings)
           for (VtreesWing& w : wings)
             w.changes.clear();
       })) {
    Result<VtreesSession> session = VtreesSession::create(*b->db, VtreesReplayOptions());
    ASSERT_TRUE(session.is_ok());
    const std::vector<CameraFrame> path = orbit_path(b->db->sphere, 60);
    for (size_t i = 0; i < path.size(); i += 3) {
      ASSERT_TRUE(session.value().frame(path[i], b->db->sphere).is_ok());
      off += corners_off(session.value().client(), *b->reference);
      flagged += !check_vtrees_wedges(session.value().client(), *b->reference, b->wedges).empty();
    }
  }
  EXPECT_GT(off, 0u);
  EXPECT_GT(flagged, 0u);

  const std::vector<std::unique_ptr<Built>> cut = build_all(GetParam(), [](VtreesWedgeTable* t) {
    const size_t b = t->pairs.size() - 2 * t->wings.size();
    for (size_t k = 0; k < t->wings.size(); ++k)
      for (VtreesPairWedge& p : t->pairs[b + 2 * k + 1])
        p.wedge = 0;  // the right records' pairs, all wedge 0
  });
  ASSERT_FALSE(cut.empty());
  Result<VtreesSession> session = VtreesSession::create(*cut.front()->db, VtreesReplayOptions());
  ASSERT_TRUE(session.is_ok());
  // The right record repeats its parent's entries with another wedge: the
  // client refuses the contradiction.
  Result<VtreesFrameStats> refused = session.value().step(everything(cut.front()->db->sphere));
  ASSERT_FALSE(refused.is_ok());
  EXPECT_NE(refused.status().message().find("differs from an earlier record's"), std::string::npos)
      << refused.status().message();
}

// The fuzz target's seeds with wedges: Fox's downlink (the trees message
// and the answer to one view), and a frame of three splits' records alone,
// which the target decodes under Fox's widths (its wedge context). Written
// again with LODBAKE_REGENERATE_GOLDEN=1.
TEST(VtreesWedgesSeeds, FoxDownlinkAndFrame) {
  const std::vector<std::unique_ptr<Built>> all = build_all("Fox/Fox.gltf");
  ASSERT_EQ(all.size(), 1u);
  const Built& b = *all.front();
  const VtreesWidths& w = b.db->widths;
  // (fuzz_vtrees_records.cpp's wedge context)
  EXPECT_EQ(w.base_count, 4u);
  EXPECT_EQ(w.split_count, 286u);
  EXPECT_EQ(w.run_count_bits, 1);
  EXPECT_EQ(w.run_length_bits, 4);
  EXPECT_EQ(w.slot_count, 576u);
  EXPECT_EQ(w.wedge_count, 434u);
  Result<VtreesServerSession> server = VtreesServerSession::create(*b.db);
  ASSERT_TRUE(server.is_ok());
  CameraFrame camera;
  camera.eye = {b.db->sphere.center[0], b.db->sphere.center[1],
                b.db->sphere.center[2] + 3 * b.db->sphere.radius};
  camera.target = b.db->sphere.center;
  const Bytes request =
      encode_view_request(view_request_for(camera, Viewport(), 0.01f * b.db->sphere.radius, 8));
  Result<std::vector<Bytes>> answer = server.value().answer(request.data(), request.size());
  ASSERT_TRUE(answer.is_ok());
  ASSERT_GT(server.value().last_answer().splits, 0u);
  Bytes downlink = b.db->trees_message().value();
  Result<VtreesClient> client = VtreesClient::create(downlink.data(), downlink.size());
  ASSERT_TRUE(client.is_ok());
  for (const Bytes& m : answer.value()) {
    ASSERT_TRUE(client.value().receive(m.data(), m.size()).is_ok());
    downlink.insert(downlink.end(), m.begin(), m.end());
  }
  EXPECT_TRUE(client.value().corner_wedges().is_ok());
  std::vector<VtreesItem> items;
  for (uint32_t k = 0; k < 3; ++k) {
    VtreesItem it;
    it.kind = VtreesItemKind::kSplit;
    it.split = k;
    it.left = b.db->record(w.base_count + 2 * k);
    it.right = b.db->record(w.base_count + 2 * k + 1);
    it.wings[0] = b.db->wedges->wings[k][0];
    it.wings[1] = b.db->wedges->wings[k][1];
    items.push_back(std::move(it));
  }
  const Bytes frame = encode_vtrees_frame(items, w).value();
  const std::string corpus = testing_util::env_or("LODBAKE_SOURCE_DIR", LODBAKE_TEST_SOURCE_DIR) +
                             "/tests/fuzz/corpus/vtrees_records/";
  if (testing_util::env_or("LODBAKE_REGENERATE_GOLDEN", "0") == "1") {
    ASSERT_TRUE(write_file_atomic(corpus + "session_fox_wedges.bin", downlink).is_ok());
    ASSERT_TRUE(write_file_atomic(corpus + "frame_fox_wedges.bin", frame).is_ok());
  }
  EXPECT_EQ(testing_util::read_bytes(corpus + "session_fox_wedges.bin"), downlink);
  EXPECT_EQ(testing_util::read_bytes(corpus + "frame_fox_wedges.bin"), frame);
}

INSTANTIATE_TEST_SUITE_P(Assets, VtreesWedgesTest, testing::Values("Duck/Duck.glb", "Fox/Fox.gltf"),
                         [](const testing::TestParamInfo<std::string>& param) {
                           return param.param.substr(0, param.param.find('/'));
                         });

}  // namespace
}  // namespace lodbake
