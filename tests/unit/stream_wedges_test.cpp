// Mode stream on real assets (lib/replay/stream_wedges.h): over a camera
// path and at full refinement, every corner of the client's mesh has the
// wedge the server's FrontWedges gives the same face at the same node, from
// the packets' wedge data alone; the base and vsplit messages with wedges
// round trip and refuse truncations and out-of-range wedges; wedge data the
// server leaves out shows as client corners without their wedge.
#include "lib/replay/stream_wedges.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "formats/sections/vhie.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/front_wedges.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_wedge_check.h"
#include "lib/scene/scene_lods.h"
#include "tests/unit/asset_hierarchy_support.h"
#include "tests/unit/asset_test_support.h"
#include "tests/unit/test_support.h"
#include "tests/unit/wire_corruption_support.h"

namespace lodbake {
namespace {

using test::kAssets;
using test::read_asset;

using Built = test::AssetHierarchy;

std::vector<Built> build_all(const std::string& asset) {
  return test::build_asset_hierarchies(read_asset(kAssets + asset));
}

// The client's corners equal FrontWedges' on the complete hierarchy, one
// by one (what check_stream_wedges() also asks, written out here).
void expect_server_corners(const StreamClient& client, const StreamHierarchy& db,
                           const FrontWedges& front, const std::string& where) {
  Result<std::vector<std::array<uint32_t, 3>>> corners = client.corner_wedges();
  ASSERT_TRUE(corners.is_ok()) << where << ": " << corners.status().message();
  const std::vector<Triangle> faces = client.refiner().triangles();
  const std::vector<uint32_t> origins = client.refiner().face_origins();
  const auto base = static_cast<uint32_t>(db.h->base.triangles.size());
  ASSERT_EQ(corners.value().size(), faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    const WedgeFace face = client.face_of(origins[f]);
    const uint32_t origin =
        face.heap == 0 ? face.tree : base + 2 * db.node_of({face.tree, face.heap}) + face.side;
    for (int k = 0; k < 3; ++k) {
      const uint32_t node = db.node_of(client.id_of(faces[f][k]));
      ASSERT_NE(node, kNoNode);
      const uint32_t want = front.wedge(origin, node);
      ASSERT_NE(want, kNoVertex) << where;
      ASSERT_EQ(corners.value()[f][k], want) << where << ", face " << f << " corner " << k;
    }
  }
}

class StreamWedgesTest : public testing::TestWithParam<std::string> {};

TEST_P(StreamWedgesTest, ClientCornersAreTheServerFrontsOverAPathAndAtTheInput) {
  for (const Built& b : build_all(GetParam())) {
    Result<StreamHierarchy> db = StreamHierarchy::create(b.h, b.data);
    ASSERT_TRUE(db.is_ok()) << db.status().message();
    Result<StreamWedgeTable> table = stream_wedge_table(b.h, b.pm, b.wedges);
    ASSERT_TRUE(table.is_ok()) << table.status().message();
    ASSERT_TRUE(db.value().set_wedges(std::move(table).value()).is_ok());
    Result<FrontWedges> front = FrontWedges::create(b.h, b.pm, b.wedges);
    ASSERT_TRUE(front.is_ok()) << front.status().message();
    Result<StreamSession> session = StreamSession::create(db.value(), StreamReplayOptions());
    ASSERT_TRUE(session.is_ok()) << session.status().message();
    StreamSession& s = session.value();
    ASSERT_TRUE(s.client().has_wedges());
    const BoundingSphere sphere = bounding_sphere(b.h.position);
    const std::vector<CameraFrame> path = orbit_path(sphere, 60);
    size_t collapses = 0;
    for (size_t i = 0; i < path.size(); i += 3) {
      Result<StreamFrameStats> f = s.frame(path[i], sphere);
      ASSERT_TRUE(f.is_ok()) << f.status().message();
      collapses += f.value().collapses;
      expect_server_corners(s.client(), db.value(), front.value(), "frame " + std::to_string(i));
      EXPECT_TRUE(check_stream_wedges(s.client(), db.value(), front.value(), b.wedges).empty());
    }
    EXPECT_GT(collapses, 0u);  // the path coarsens too, so collapses carried wedges back
    // Tolerance 0: every split, the input's corners.
    CameraFrame everything;
    everything.eye = {sphere.center[0], sphere.center[1], sphere.center[2] + 3 * sphere.radius};
    everything.target = sphere.center;
    Result<StreamFrameStats> all =
        s.step(view_request_for(everything, Viewport(), 0.01f * sphere.radius, 0));
    ASSERT_TRUE(all.is_ok()) << all.status().message();
    ASSERT_EQ(s.client().refiner().front_size(), b.pm.full_vertex_count());
    expect_server_corners(s.client(), db.value(), front.value(), "full refinement");
  }
}

TEST_P(StreamWedgesTest, MessagesWithWedgesRoundTripAndRefuseDamage) {
  const std::vector<Built> all = build_all(GetParam());
  ASSERT_FALSE(all.empty());
  const Built& b = all.front();
  Result<StreamHierarchy> created = StreamHierarchy::create(b.h, b.data);
  ASSERT_TRUE(created.is_ok());
  StreamHierarchy& db = created.value();
  ASSERT_TRUE(db.set_wedges(stream_wedge_table(b.h, b.pm, b.wedges).value()).is_ok());
  const auto roots = static_cast<uint32_t>(b.h.root_count());

  const Bytes base = db.base_message().value();
  Result<BaseMessage> decoded_base = decode_base_message(base.data(), base.size());
  ASSERT_TRUE(decoded_base.is_ok()) << decoded_base.status().message();
  EXPECT_EQ(decoded_base.value().wedge_count, b.wedges.wedge_count());
  EXPECT_EQ(decoded_base.value().corners, b.wedges.base);
  EXPECT_EQ(encode_base_message(decoded_base.value()).value(), base);
  expect_refuses_corruptions(base, kStreamHeaderBytes, [](const Bytes& bytes) {
    return decode_base_message(bytes.data(), bytes.size()).is_ok();
  });

  // Every split's packet, in one message, with the wings' changes and the
  // moved faces that the asset has.
  std::vector<VsplitPacket> packets;
  size_t moved = 0, changes = 0;
  for (uint32_t s = 0; s < b.h.node_count(); ++s) {
    if (b.h.is_leaf(s)) continue;
    packets.push_back(db.packet(s));
    moved += packets.back().wedges.moved.size();
    for (const WingWedges& w : packets.back().wedges.wings)
      changes += w.changes.size();
  }
  EXPECT_GT(moved, 0u);
  EXPECT_GT(changes, 0u);
  const Bytes message = encode_vsplit_message(packets, db.widths, roots).value();
  Result<std::vector<VsplitPacket>> decoded =
      decode_vsplit_message(message.data(), message.size(), db.widths, roots);
  ASSERT_TRUE(decoded.is_ok()) << decoded.status().message();
  ASSERT_EQ(decoded.value(), packets);
  EXPECT_EQ(encode_vsplit_message(decoded.value(), db.widths, roots).value(), message);
  uint64_t bits = 0;
  for (const VsplitPacket& p : packets)
    bits += vsplit_packet_bits(p, db.widths);
  EXPECT_EQ(message.size(), kStreamHeaderBytes + 4 + (bits + 7) / 8);
  // Without the widths' wedges the same packets are the position-only ones.
  StreamIdWidths plain = db.widths;
  plain.wedges = 0;
  const Bytes shorter = encode_vsplit_message(packets, plain, roots).value();
  EXPECT_LT(shorter.size(), message.size());

  // Truncations of a short message (every length) and wedges out of range.
  const std::vector<VsplitPacket> few(packets.begin(), packets.begin() + 3);
  const Bytes small = encode_vsplit_message(few, db.widths, roots).value();
  expect_refuses_corruptions(small, kStreamHeaderBytes, [&](const Bytes& bytes) {
    return decode_vsplit_message(bytes.data(), bytes.size(), db.widths, roots).is_ok();
  });
  StreamIdWidths fewer = db.widths;
  fewer.wedges = 1;  // every wedge id but 0 is then out of range
  EXPECT_FALSE(decode_vsplit_message(small.data(), small.size(), fewer, roots).is_ok());
  std::vector<VsplitPacket> wrong = few;
  wrong[0].wedges.added[0] = db.widths.wedges;
  EXPECT_FALSE(encode_vsplit_message(wrong, db.widths, roots).is_ok());

  // The fuzz target's seeds with wedges are Fox's base message and this
  // short message, decoded there under Fox's widths (written again with
  // LODBAKE_REGENERATE_GOLDEN=1).
  if (GetParam() != "Fox/Fox.gltf") return;
  // (fuzz_stream_packets.cpp's wedge context)
  EXPECT_EQ(roots, 4u);
  EXPECT_EQ(db.widths.node_bits, 8);
  EXPECT_EQ(db.widths.wedges, 434u);
  EXPECT_EQ(db.widths.base_faces, 4u);
  const std::string corpus = testing_util::env_or("LODBAKE_SOURCE_DIR", LODBAKE_TEST_SOURCE_DIR) +
                             "/tests/fuzz/corpus/stream_packets/";
  if (testing_util::env_or("LODBAKE_REGENERATE_GOLDEN", "0") == "1") {
    ASSERT_TRUE(write_file_atomic(corpus + "base_fox_wedges.bin", base).is_ok());
    ASSERT_TRUE(write_file_atomic(corpus + "vsplits_fox_wedges.bin", small).is_ok());
  }
  EXPECT_EQ(testing_util::read_bytes(corpus + "base_fox_wedges.bin"), base);
  EXPECT_EQ(testing_util::read_bytes(corpus + "vsplits_fox_wedges.bin"), small);
}

TEST_P(StreamWedgesTest, MissingWedgeDataLeavesCornersWithoutTheirWedge) {
  const std::vector<Built> all = build_all(GetParam());
  ASSERT_FALSE(all.empty());
  const Built& b = all.front();
  Result<StreamHierarchy> db = StreamHierarchy::create(b.h, b.data);
  ASSERT_TRUE(db.is_ok());
  StreamWedgeTable table = stream_wedge_table(b.h, b.pm, b.wedges).value();
  for (VsplitWedges& d : table.splits)
    d.moved.clear();
  ASSERT_TRUE(db.value().set_wedges(std::move(table)).is_ok());
  Result<FrontWedges> front = FrontWedges::create(b.h, b.pm, b.wedges);
  ASSERT_TRUE(front.is_ok());
  Result<StreamSession> session = StreamSession::create(db.value(), StreamReplayOptions());
  ASSERT_TRUE(session.is_ok());
  const BoundingSphere sphere = bounding_sphere(b.h.position);
  CameraFrame everything;
  everything.eye = {sphere.center[0], sphere.center[1], sphere.center[2] + 3 * sphere.radius};
  everything.target = sphere.center;
  ASSERT_TRUE(session.value()
                  .step(view_request_for(everything, Viewport(), 0.01f * sphere.radius, 0))
                  .is_ok());
  EXPECT_FALSE(session.value().client().corner_wedges().is_ok());
  EXPECT_FALSE(
      check_stream_wedges(session.value().client(), db.value(), front.value(), b.wedges).empty());
}

// A wing corner coarser than the PM had it takes the wedge carried up the
// collapses: without the wings' changes, some frame of a path differs from
// the server's front.
TEST_P(StreamWedgesTest, WingsWithoutTheirChangesDifferFromTheServer) {
  size_t differ = 0;
  for (const Built& b : build_all(GetParam())) {
    Result<StreamHierarchy> db = StreamHierarchy::create(b.h, b.data);
    ASSERT_TRUE(db.is_ok());
    StreamWedgeTable table = stream_wedge_table(b.h, b.pm, b.wedges).value();
    for (VsplitWedges& d : table.splits)
      for (WingWedges& w : d.wings)
        w.changes.clear();
    ASSERT_TRUE(db.value().set_wedges(std::move(table)).is_ok());
    Result<FrontWedges> front = FrontWedges::create(b.h, b.pm, b.wedges);
    ASSERT_TRUE(front.is_ok());
    Result<StreamSession> session = StreamSession::create(db.value(), StreamReplayOptions());
    ASSERT_TRUE(session.is_ok());
    const BoundingSphere sphere = bounding_sphere(b.h.position);
    const std::vector<CameraFrame> path = orbit_path(sphere, 60);
    for (size_t i = 0; i < path.size(); i += 3) {
      ASSERT_TRUE(session.value().frame(path[i], sphere).is_ok());
      differ += !check_stream_wedges(session.value().client(), db.value(), front.value(), b.wedges)
                     .empty();
    }
  }
  EXPECT_GT(differ, 0u);
}

// A server that contradicts itself (a pair (face, vertex) given two
// wedges) is refused, and the client keeps what it had.
TEST_P(StreamWedgesTest, ClientRefusesContradictingWedgeData) {
  const std::vector<Built> all = build_all(GetParam());
  ASSERT_FALSE(all.empty());
  const Built& b = all.front();
  Result<StreamHierarchy> created = StreamHierarchy::create(b.h, b.data);
  ASSERT_TRUE(created.is_ok());
  StreamHierarchy& db = created.value();
  ASSERT_TRUE(db.set_wedges(stream_wedge_table(b.h, b.pm, b.wedges).value()).is_ok());
  const auto roots = static_cast<uint32_t>(b.h.root_count());
  uint32_t root = 0;
  while (root < roots && (b.h.is_leaf(root) || b.h.cut_left[root] == kNoNode))
    ++root;
  ASSERT_LT(root, roots);
  VsplitPacket p = db.packet(root);
  // The left face's vt corner again as a moved face, with another wedge;
  // the vs corner made wrong too, which the client must not keep.
  const uint32_t other = (p.wedges.added[1] + 1) % db.widths.wedges;
  p.wedges.added[0] = (p.wedges.added[0] + 1) % db.widths.wedges;
  p.wedges.moved.push_back({{p.vs.tree, p.vs.heap, 0}, other});
  const Bytes bad = encode_vsplit_message({p}, db.widths, roots).value();
  const Bytes base = db.base_message().value();
  Result<StreamClient> client = StreamClient::create(base.data(), base.size());
  ASSERT_TRUE(client.is_ok()) << client.status().message();
  const Status refused = client.value().receive(bad.data(), bad.size());
  EXPECT_EQ(refused.kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(refused.message().find("wedge differs"), std::string::npos) << refused.message();
  EXPECT_TRUE(client.value().received().empty());
  const Bytes good = encode_vsplit_message({db.packet(root)}, db.widths, roots).value();
  EXPECT_TRUE(client.value().receive(good.data(), good.size()).is_ok());
}

INSTANTIATE_TEST_SUITE_P(Assets, StreamWedgesTest,
                         testing::Values("Duck/Duck.glb", "CesiumMilkTruck/CesiumMilkTruck.gltf",
                                         "Fox/Fox.gltf"),
                         [](const testing::TestParamInfo<std::string>& param) {
                           return param.param.substr(0, param.param.find('/'));
                         });

}  // namespace
}  // namespace lodbake
