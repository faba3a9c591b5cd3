// VHIE and RFIN codecs: round trip, exact payload sizes, every truncation
// and every single-bit flip of an encoded hierarchy either decodes to a
// valid hierarchy or gives LBK-E023, never a crash (ASan checks), and the
// specific malformations the decoder names.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/hierarchy/selective_refiner.h"

namespace lodbake {
namespace {

// A regular icosahedron: closed, 12 vertices of degree 5.
TriangleMesh icosahedron() {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  TriangleMesh m;
  m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  return m;
}

VertexHierarchy built() {
  Result<BalancedHierarchy> b = build_balanced_hierarchy(icosahedron(), BalancedBuildOptions());
  EXPECT_TRUE(b.is_ok()) << b.status().message();
  return b.is_ok() ? std::move(b).value().hierarchy : VertexHierarchy();
}

TEST(VhieSection, RoundTripAndShape) {
  const VertexHierarchy h = built();
  const HierarchyShape s = hierarchy_shape(h);
  EXPECT_EQ(s.leaves, 12u);
  EXPECT_GT(s.splits, 0u);
  Result<Bytes> bytes = encode_vhie(h);
  ASSERT_TRUE(bytes.is_ok());
  Result<VhieSummary> summary = read_vhie_summary(bytes.value().data(), bytes.value().size());
  ASSERT_TRUE(summary.is_ok()) << summary.status().message();
  EXPECT_EQ(summary.value().node_count, s.nodes);
  EXPECT_EQ(summary.value().depth, s.depth);
  Result<VertexHierarchy> back = decode_vhie(bytes.value().data(), bytes.value().size(), h.base);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  Result<Bytes> again = encode_vhie(back.value());
  ASSERT_TRUE(again.is_ok());
  EXPECT_EQ(again.value(), bytes.value());
}

TEST(VhieSection, TruncationsAndBitFlipsAreRejectedCleanly) {
  const VertexHierarchy h = built();
  const Bytes bytes = encode_vhie(h).value();
  for (size_t len = 0; len < bytes.size(); ++len) {
    Result<VertexHierarchy> r = decode_vhie(bytes.data(), len, h.base);
    ASSERT_FALSE(r.is_ok()) << len;
    EXPECT_EQ(r.status().code(), 23);
    EXPECT_NE(r.status().message().find("section VHIE: "), std::string::npos);
  }
  Bytes longer = bytes;
  longer.push_back(0);
  EXPECT_FALSE(decode_vhie(longer.data(), longer.size(), h.base).is_ok());
  size_t accepted = 0;
  for (size_t bit = 0; bit < bytes.size() * 8; ++bit) {
    Bytes flipped = bytes;
    flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    Result<VertexHierarchy> r = decode_vhie(flipped.data(), flipped.size(), h.base);
    if (r.is_ok()) {
      ++accepted;  // e.g. a position or error bit: still a valid hierarchy
      EXPECT_TRUE(validate_hierarchy(r.value()).empty());
    } else {
      EXPECT_EQ(r.status().code(), 23) << r.status().message();
    }
  }
  EXPECT_GT(accepted, 0u);
}

TEST(VhieSection, NamesTheMalformation) {
  const VertexHierarchy h = built();
  const Bytes bytes = encode_vhie(h).value();
  TriangleMesh other = h.base;
  other.positions.push_back({0, 0, 0});
  Result<VertexHierarchy> r = decode_vhie(bytes.data(), bytes.size(), other);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.status().message().find("root count"), std::string::npos) << r.status().message();
  Bytes flags = bytes;
  flags[9] = 1;
  r = decode_vhie(flags.data(), flags.size(), h.base);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.status().message().find("unknown flags"), std::string::npos);
  Bytes depth = bytes;
  depth[8] = static_cast<uint8_t>(depth[8] + 1);
  r = decode_vhie(depth.data(), depth.size(), h.base);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.status().message().find("stored depth"), std::string::npos) << r.status().message();
}

TEST(VhieSection, ValidationFindsBrokenStructure) {
  VertexHierarchy h = built();
  ASSERT_TRUE(validate_hierarchy(h).empty());
  VertexHierarchy cut = h;
  for (uint32_t i = 0; i < cut.node_count(); ++i) {
    if (!cut.is_leaf(i)) {
      cut.cut_left[i] = i;  // not a leaf
      break;
    }
  }
  ASSERT_FALSE(validate_hierarchy(cut).empty());
  EXPECT_NE(validate_hierarchy(cut).front().find("not leaves"), std::string::npos);
  VertexHierarchy order = h;
  for (uint32_t i = 0; i < order.node_count(); ++i) {
    if (!order.is_leaf(i)) {
      std::swap(order.parent[order.first_child[i]], order.parent[order.first_child[i] + 1]);
      order.first_child[i] += 1;
      break;
    }
  }
  EXPECT_FALSE(validate_hierarchy(order).empty());
  EXPECT_FALSE(encode_vhie(cut).is_ok());
}

// A hand-made forest whose first tree is a chain 40 levels deep (each split
// peels one leaf off), so its ids need more than 32 bits.
VertexHierarchy deep_chain(uint32_t levels) {
  VertexHierarchy h;
  h.base.positions = {{0, 0, 0}, {1, 0, 0}};
  const uint32_t splits = levels - 1;
  const uint32_t n = 2 + 2 * splits;
  h.parent.assign(n, kNoNode);
  h.first_child.assign(n, kNoNode);
  h.position.assign(n, Vec3f{0, 0, 0});
  h.cut_left.assign(n, kNoNode);
  h.cut_right.assign(n, kNoNode);
  h.input_vertex.assign(n, kNoVertex);
  h.error.assign(n, 0.5f);
  h.position[1] = {1, 0, 0};
  uint32_t chain = 0;
  for (uint32_t k = 0; k < splits; ++k) {
    const uint32_t c = 2 + 2 * k;
    h.first_child[chain] = c;
    h.parent[c] = h.parent[c + 1] = chain;
    h.position[c] = h.position[chain];
    h.position[c + 1] = {0, static_cast<float>(k + 1), 0};
    h.cut_left[chain] = 1;  // the other tree's lone root, a leaf
    chain = c;
  }
  uint32_t v = 0;
  for (uint32_t i = 0; i < n; ++i) {
    if (h.first_child[i] == kNoNode) h.input_vertex[i] = v++;
    if (h.first_child[i] == kNoNode) h.error[i] = 0;
  }
  return h;
}

TEST(VhieSection, DeepTreesUse64BitIds) {
  const VertexHierarchy h = deep_chain(40);
  ASSERT_TRUE(validate_hierarchy(h).empty()) << validate_hierarchy(h).front();
  const HierarchyShape s = hierarchy_shape(h);
  EXPECT_EQ(s.depth, 40u);
  EXPECT_EQ(s.tree_bits, 1);
  EXPECT_EQ(s.id_bits, 41);
  EXPECT_EQ(s.id_bytes, 8);
  const std::vector<HierarchyNodeId> ids = hierarchy_node_ids(h);
  // The deepest left child: heap id 2^39.
  EXPECT_EQ(ids[h.node_count() - 2].heap, uint64_t{1} << 39);
  EXPECT_EQ(ids[h.node_count() - 1].heap, (uint64_t{1} << 39) + 1);
  Result<Bytes> bytes = encode_vhie(h);
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  Result<VertexHierarchy> back = decode_vhie(bytes.value().data(), bytes.value().size(), h.base);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(back.value().parent, h.parent);
  EXPECT_EQ(hierarchy_shape(back.value()).depth, 40u);
  Result<SelectiveRefiner> r = SelectiveRefiner::create(h);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  const uint32_t deepest = static_cast<uint32_t>(h.node_count() - 1);
  EXPECT_EQ(r.value().active_ancestor_id(r.value().id_of(deepest)), (HierarchyNodeId{0, 1}));
  EXPECT_EQ(r.value().active_ancestor(deepest), 0u);
  // 65 levels do not fit 64-bit heap ids.
  EXPECT_FALSE(validate_hierarchy(deep_chain(65)).empty());
}

TEST(RfinSection, RoundTripTruncationAndRanges) {
  const VertexHierarchy h = built();
  Result<std::vector<NodeRefinement>> data = compute_refinement_data(h, icosahedron());
  ASSERT_TRUE(data.is_ok()) << data.status().message();
  for (uint32_t i = 0; i < h.node_count(); ++i) {
    if (h.is_leaf(i)) continue;
    EXPECT_GT(data.value()[i].radius, 0);
    EXPECT_GE(data.value()[i].cone_half_angle, 0);
  }
  Result<Bytes> bytes = encode_rfin(h, data.value());
  ASSERT_TRUE(bytes.is_ok());
  Result<std::vector<NodeRefinement>> back =
      decode_rfin(bytes.value().data(), bytes.value().size(), h);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  for (size_t len = 0; len < bytes.value().size(); ++len)
    EXPECT_FALSE(decode_rfin(bytes.value().data(), len, h).is_ok()) << len;
  Bytes negative = bytes.value();
  const float minus = -1.0f;
  std::memcpy(&negative[kRfinFixedBytes], &minus, 4);
  Result<std::vector<NodeRefinement>> bad = decode_rfin(negative.data(), negative.size(), h);
  ASSERT_FALSE(bad.is_ok());
  EXPECT_NE(bad.status().message().find("section RFIN: "), std::string::npos);
}

}  // namespace
}  // namespace lodbake
