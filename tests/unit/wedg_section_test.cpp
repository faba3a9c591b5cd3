// The WEDG section: a recorded asset PM's wedges round-trip, and damaged
// payloads are refused with a message naming what is wrong.
#include "formats/sections/wedg.h"

#include <gtest/gtest.h>

#include "lib/scene/scene_io.h"
#include "lib/scene/scene_lods.h"
#include "tests/unit/asset_test_support.h"

namespace lodbake {
namespace {

MeshPm duck_pm() {
  const Scene scene = test::read_asset(test::kAssets + "Duck/Duck.glb");
  const SceneLodOptions options;
  Result<std::vector<MeshPm>> pms = scene_progressive_meshes(scene, options);
  EXPECT_TRUE(pms.is_ok());
  return pms.value().at(0);
}

TEST(WedgSection, RoundTripsARecordedProgressiveMesh) {
  const MeshPm m = duck_pm();
  Result<Bytes> bytes = encode_wedg(m.wedges);
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  EXPECT_EQ(bytes.value().size(), kWedgFixedBytes + 12 * m.wedges.wedge_count() +
                                      12 * m.wedges.base.size() + 28 * m.wedges.added.size() +
                                      4 * m.wedges.moved.size());
  Result<PmWedges> back = decode_wedg(bytes.value().data(), bytes.value().size());
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_TRUE(back.value() == m.wedges);
  EXPECT_TRUE(validate_wedg(back.value(), m.pm).empty());
}

TEST(WedgSection, RefusesDamagedPayloads) {
  const MeshPm m = duck_pm();
  const Bytes good = encode_wedg(m.wedges).value();
  auto refused = [](Bytes b, const std::string& why) {
    Result<PmWedges> r = decode_wedg(b.data(), b.size());
    EXPECT_FALSE(r.is_ok()) << why;
    if (!r.is_ok()) {
      EXPECT_NE(r.status().message().find("section WEDG"), std::string::npos) << why;
    }
  };
  refused(Bytes(good.begin(), good.begin() + 10), "short header");
  refused(Bytes(good.begin(), good.end() - 4), "truncated");
  Bytes longer = good;
  longer.push_back(0);
  refused(longer, "a byte too many");
  Bytes flags = good;
  flags[0] = 1;
  refused(flags, "unknown flags");
  Bytes huge = good;
  huge[4] = huge[5] = huge[6] = huge[7] = 0xff;  // 4 billion wedges in a small payload
  refused(huge, "a count the payload cannot hold");
  Bytes wedge = good;
  const size_t first_base = kWedgFixedBytes + 12 * m.wedges.wedge_count();
  wedge[first_base] = wedge[first_base + 1] = wedge[first_base + 2] = wedge[first_base + 3] = 0xff;
  refused(wedge, "a base wedge out of range");
}

TEST(WedgSection, DisagreesWithAnotherProgressiveMesh) {
  const MeshPm m = duck_pm();
  PmWedges fewer = m.wedges;
  fewer.base.pop_back();
  EXPECT_FALSE(validate_wedg(fewer, m.pm).empty());
  PmWedges home = m.wedges;
  home.wedge_home[0] = static_cast<uint32_t>(m.pm.full_vertex_count());
  EXPECT_FALSE(validate_wedg(home, m.pm).empty());
  PmWedges wings = m.wedges;
  size_t split = 0;
  while (m.pm.splits[split].vr == kNoVertex)
    ++split;
  wings.added[split][3] = wings.added[split][4] = wings.added[split][5] = kNoVertex;
  EXPECT_FALSE(validate_wedg(wings, m.pm).empty());
  // And the encoder refuses what it could not decode.
  PmWedges partial = m.wedges;
  partial.added[split][4] = kNoVertex;
  EXPECT_FALSE(encode_wedg(partial).is_ok());
}

}  // namespace
}  // namespace lodbake
