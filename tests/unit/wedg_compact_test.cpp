// Compact WEDG (codec 1): the wedges recorded on real assets round-trip
// byte for byte and shrink; corners away from their home take the escape;
// damaged payloads are refused with LBK-E023 and never crash.
#include "formats/sections/wedg_compact.h"

#include <gtest/gtest.h>

#include <iostream>

#include "formats/sections/wedg.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_lods.h"

namespace lodbake {
namespace {

const std::string kAssets = std::string(LODBAKE_TEST_SHARED_DATA) + "/assets/";

// `keep_seams`: no seam release, so that every corner stays at its
// wedge's home.
std::vector<MeshPm> asset_pms(const std::string& name, bool keep_seams = false) {
  ImportReport report;
  Result<Scene> scene = read_scene_file(kAssets + name, {}, &report);
  EXPECT_TRUE(scene.is_ok()) << name;
  if (!scene.is_ok()) return {};
  SceneLodOptions options;
  if (keep_seams) options.simplify.seam_release.reset();
  Result<std::vector<MeshPm>> pms = scene_progressive_meshes(scene.value(), options);
  EXPECT_TRUE(pms.is_ok()) << name;
  return pms.is_ok() ? pms.value() : std::vector<MeshPm>{};
}

// Encodes `wedges` compact against `base` and checks the round trip.
Bytes round_trip(const PmWedges& wedges, const TriangleMesh& base, const std::string& what) {
  const Bytes raw = encode_wedg(wedges).value();
  Result<Bytes> compact = encode_wedg_compact(raw.data(), raw.size(), base);
  EXPECT_TRUE(compact.is_ok()) << what << ": " << compact.status().message();
  if (!compact.is_ok()) return {};
  Result<Bytes> back = decode_wedg_compact(compact.value().data(), compact.value().size(), base);
  EXPECT_TRUE(back.is_ok()) << what << ": " << back.status().message();
  EXPECT_TRUE(back.is_ok() && back.value() == raw) << what << ": not byte for byte";
  return compact.value();
}

TEST(WedgCompact, RoundTripsRecordedWedgesSmaller) {
  for (const char* asset :
       {"Duck/Duck.glb", "CesiumMilkTruck/CesiumMilkTruck.gltf", "SheenCloth/SheenCloth.glb"}) {
    const std::vector<MeshPm> pms = asset_pms(asset);
    ASSERT_FALSE(pms.empty()) << asset;
    for (const MeshPm& m : pms) {
      const std::string what = std::string(asset) + " mesh " + std::to_string(m.mesh);
      const size_t raw = encode_wedg(m.wedges).value().size();
      const Bytes compact = round_trip(m.wedges, m.pm.base, what);
      std::cout << what << ": raw " << raw << " bytes, compact " << compact.size() << "\n";
      // At least 5 times smaller (measured 8 to 12 times).
      EXPECT_LT(compact.size() * 5, raw) << what;
    }
  }
}

TEST(WedgCompact, CornersAwayFromTheirHomeTakeTheEscape) {
  const MeshPm m = asset_pms("Duck/Duck.glb", true).at(0);
  PmWedges moved = m.wedges;
  // A seam moved by a permissive collapse: corners use wedges of other
  // vertices.
  moved.base[0][0] = moved.base[1][2];
  moved.moved.front() = 0;
  for (std::array<uint32_t, 6>& a : moved.added) {
    if (a[0] != kNoVertex && a[3] != kNoVertex) {
      a[4] = a[2];
      break;
    }
  }
  const Bytes plain = round_trip(m.wedges, m.pm.base, "at home");
  const Bytes escaped = round_trip(moved, m.pm.base, "escapes");
  ASSERT_FALSE(escaped.empty());
  EXPECT_EQ(plain[1 + kWedgFixedBytes], 0);
  EXPECT_EQ(escaped[1 + kWedgFixedBytes], 1);  // the mode says escapes are coded
}

TEST(WedgCompact, RefusesWhatDoesNotFollowBase) {
  const MeshPm m = asset_pms("Duck/Duck.glb").at(0);
  const Bytes raw = encode_wedg(m.wedges).value();
  TriangleMesh fewer = m.pm.base;
  fewer.triangles.pop_back();
  Result<Bytes> r = encode_wedg_compact(raw.data(), raw.size(), fewer);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kUnsupported);
  PmWedges far = m.wedges;
  far.wedge_home[0] = static_cast<uint32_t>(m.pm.full_vertex_count());
  const Bytes far_raw = encode_wedg(far).value();
  r = encode_wedg_compact(far_raw.data(), far_raw.size(), m.pm.base);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kUnsupported);
  r = encode_wedg_compact(raw.data(), raw.size() - 1, m.pm.base);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
}

TEST(WedgCompact, RefusesDamagedPayloads) {
  const MeshPm m = asset_pms("CesiumMilkTruck/CesiumMilkTruck.gltf").at(0);
  const TriangleMesh& base = m.pm.base;
  const Bytes good = round_trip(m.wedges, base, "truck");
  ASSERT_FALSE(good.empty());
  auto refused = [&](const Bytes& b, const TriangleMesh& against, const std::string& why) {
    Result<Bytes> r = decode_wedg_compact(b.data(), b.size(), against);
    EXPECT_FALSE(r.is_ok()) << why;
    if (!r.is_ok()) {
      EXPECT_NE(r.status().message().find("LBK-E023"), std::string::npos) << why;
      EXPECT_NE(r.status().message().find("section WEDG: compact"), std::string::npos)
          << why << ": " << r.status().message();
    }
  };
  refused(Bytes(good.begin(), good.begin() + 10), base, "short header");
  refused(Bytes(good.begin(), good.end() - 1), base, "truncated");
  Bytes longer = good;
  longer.push_back(0);
  refused(longer, base, "a byte too many");
  Bytes version = good;
  version[0] = 9;
  refused(version, base, "unknown version");
  Bytes mode = good;
  mode[1 + kWedgFixedBytes] = 4;
  refused(mode, base, "unknown mode");
  Bytes flags = good;
  flags[1] = 1;
  refused(flags, base, "raw flags");
  for (size_t count_at : {5u, 13u, 17u}) {  // wedges, splits, moved: 4 billion
    Bytes huge = good;
    huge[count_at] = huge[count_at + 1] = huge[count_at + 2] = huge[count_at + 3] = 0xff;
    refused(huge, base, "a count the stream cannot hold at byte " + std::to_string(count_at));
  }
  TriangleMesh other = base;
  other.triangles.pop_back();
  refused(good, other, "another BASE");
  // Every byte flipped: refused with LBK-E023, or a valid raw payload.
  for (size_t i = 0; i < good.size(); i += 1 + good.size() / 500) {
    Bytes damaged = good;
    damaged[i] ^= 0x5a;
    Result<Bytes> r = decode_wedg_compact(damaged.data(), damaged.size(), base);
    if (r.is_ok()) {
      EXPECT_TRUE(decode_wedg(r.value().data(), r.value().size()).is_ok()) << "byte " << i;
    } else {
      EXPECT_NE(r.status().message().find("section WEDG"), std::string::npos)
          << "byte " << i << ": " << r.status().message();
    }
  }
}

}  // namespace
}  // namespace lodbake
