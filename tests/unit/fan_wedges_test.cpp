// The wedges of the fan hierarchy's fronts on real assets: the finest front
// is the input corner by corner, every front reached by random fan-merges,
// fan-splits and partial fine paths has a wedge at every corner and one
// primitive per face, the construction path follows the partner rule
// (checked here against the runtime's own triangles, step by step), and
// wedges that are not the structure's own are refused.
#include "lib/fanmerge/fan_wedges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/fanh.h"
#include "formats/sections/open_container.h"
#include "formats/sections/wedg.h"
#include "lib/bake/fan_step.h"
#include "lib/fanmerge/fan_build.h"
#include "lib/replay/structure_loading.h"
#include "lib/scene/scene_lods.h"
#include "lib/validate/structure_validation.h"
#include "tests/unit/asset_test_support.h"

namespace lodbake {
namespace {

using test::kAssets;
using test::read_asset;
using Corners = std::vector<std::array<uint32_t, 3>>;

struct Built {
  TriangleMesh mesh;
  FanHierarchy h;
  PmWedges wedges;
  SceneMesh scene_mesh;  // whose primitives the wedges name
};

std::vector<Built> build_all(const std::string& asset) {
  const Scene scene = read_asset(kAssets + asset);
  std::vector<Built> out;
  Result<std::vector<MeshCornerWedges>> corners = scene_corner_wedges(scene, LoadOptions());
  EXPECT_TRUE(corners.is_ok()) << corners.status().message();
  if (!corners.is_ok()) return out;
  for (const MeshCornerWedges& c : corners.value()) {
    Result<FanBuildResult> r = build_fan_hierarchy(c.topology, FanBuildOptions());
    EXPECT_TRUE(r.is_ok()) << r.status().message();
    if (!r.is_ok()) return {};
    out.push_back(
        {c.topology, std::move(r).value().hierarchy, fan_input_wedges(c), scene.meshes[c.mesh]});
  }
  EXPECT_FALSE(out.empty());
  return out;
}

// Every corner of the runtime's mesh has a wedge and a face's three one
// primitive; returns the corners.
Corners expect_textured(const FanWedges& fronts, const FanRuntime& rt, const PmWedges& w) {
  Result<Corners> corners = fronts.corners(rt);
  EXPECT_TRUE(corners.is_ok()) << corners.status().message();
  if (!corners.is_ok()) return {};
  EXPECT_EQ(corners.value().size(), rt.triangle_count());
  for (const std::array<uint32_t, 3>& c : corners.value()) {
    for (uint32_t wedge : c)
      EXPECT_LT(wedge, w.wedge_count());
    EXPECT_EQ(w.wedge_primitive[c[0]], w.wedge_primitive[c[1]]);
    EXPECT_EQ(w.wedge_primitive[c[0]], w.wedge_primitive[c[2]]);
  }
  return corners.value();
}

class FanWedgesTest : public testing::TestWithParam<std::string> {};

TEST_P(FanWedgesTest, RandomFrontsAreTexturedAndTheFinestIsTheInput) {
  for (const Built& b : build_all(GetParam())) {
    ASSERT_GT(b.h.internal_count(), 0u);
    Result<FanWedges> fronts = FanWedges::create(b.mesh, b.h, b.wedges);
    ASSERT_TRUE(fronts.is_ok()) << fronts.status().message();
    EXPECT_GT(fronts.value().move_count(), 0u);
    FanRuntimeOptions options;
    options.construction_dependencies = true;
    Result<FanRuntime> created = FanRuntime::create(b.mesh, b.h, options);
    ASSERT_TRUE(created.is_ok());
    FanRuntime& rt = created.value();
    EXPECT_EQ(expect_textured(fronts.value(), rt, b.wedges), b.wedges.base);
    ASSERT_TRUE(rt.merge_all());
    // Most corners of the coarsest front take a wedge of their own vertex
    // (a partner across each collapsed edge); the others keep a wedge of
    // a vertex merged into theirs, where a seam met it away from the edge.
    const Corners coarsest = expect_textured(fronts.value(), rt, b.wedges);
    size_t own = 0, f = 0;
    for (uint32_t t = 0; t < rt.input_triangle_count(); ++t) {
      if (!rt.alive(t)) continue;
      for (int k = 0; k < 3; ++k)
        own += b.wedges.wedge_home[coarsest[f][k]] == rt.corners(t)[k];
      ++f;
    }
    std::cout << GetParam() << ": " << own << " of " << 3 * coarsest.size()
              << " coarsest corners on a wedge of their own vertex\n";
    EXPECT_GT(own * 10, 3 * coarsest.size() * 8);
    // The coarsest front as the asset's primitives (what an extracted
    // level is made of): every index checked, no triangle lost.
    Result<std::vector<ScenePrimitive>> primitives =
        primitives_at_level(b.scene_mesh, rt.mesh(), coarsest, b.wedges);
    ASSERT_TRUE(primitives.is_ok()) << primitives.status().message();
    size_t assembled = 0;
    for (const ScenePrimitive& p : primitives.value())
      if (p.mode == PrimitiveMode::kTriangles && p.indices) assembled += p.indices->size() / 3;
    EXPECT_EQ(assembled, rt.triangle_count());
    // Coarsen at an active node's parent or refine an active node, by one
    // step or a whole fan, as a traversal of the active list would.
    std::mt19937 rng(2028);
    uint64_t accepted = 0;
    for (int round = 0; round < 8; ++round) {
      for (int op = 0; op < 300; ++op) {
        const std::vector<uint32_t> active = rt.active().nodes();
        const uint32_t picked = active[rng() % active.size()];
        const uint32_t parent = rt.parent(picked);
        switch (rng() % 4) {
          case 0:
            accepted += parent != kNoNode && rt.advance(parent);
            break;
          case 1:
            accepted += rt.retreat(picked);
            break;
          case 2:
            accepted += parent != kNoNode && rt.fan_merge(parent);
            break;
          default:
            accepted += rt.fan_split(picked);
            break;
        }
      }
      expect_textured(fronts.value(), rt, b.wedges);
    }
    EXPECT_GT(accepted, 0u);
    ASSERT_TRUE(rt.split_all());
    EXPECT_EQ(expect_textured(fronts.value(), rt, b.wedges), b.wedges.base);
  }
}

// The construction path, one collapse at a time: a corner moved from u to
// the centre v takes v's wedge in a removed triangle where u has its wedge,
// else keeps its own. Read off the runtime's triangles before and after
// each step, independently of FanWedges' replay of the lists.
TEST_P(FanWedgesTest, ConstructionStepsFollowThePartnerRule) {
  for (const Built& b : build_all(GetParam())) {
    Result<FanWedges> fronts = FanWedges::create(b.mesh, b.h, b.wedges);
    ASSERT_TRUE(fronts.is_ok()) << fronts.status().message();
    Result<FanRuntime> created = FanRuntime::create(b.mesh, b.h);
    ASSERT_TRUE(created.is_ok());
    FanRuntime& rt = created.value();
    const uint32_t triangles = rt.input_triangle_count();
    Corners expected = b.wedges.base;
    uint64_t partnered = 0, kept = 0;
    for (size_t i = 0; i < rt.internal_count(); ++i) {
      const uint32_t node = static_cast<uint32_t>(rt.leaf_count() + i);
      const uint32_t v = rt.vertex(node);
      for (uint32_t k = 1; k <= rt.collapsible_children(node); ++k) {
        const uint32_t u = rt.vertex(rt.child(node, k));
        std::vector<Triangle> before(triangles);
        std::vector<uint8_t> was_alive(triangles);
        for (uint32_t t = 0; t < triangles; ++t) {
          before[t] = rt.corners(t);
          was_alive[t] = rt.alive(t);
        }
        ASSERT_TRUE(rt.advance(node));
        std::vector<std::pair<uint32_t, uint32_t>> partner;
        for (uint32_t t = 0; t < triangles; ++t) {
          if (!was_alive[t] || rt.alive(t)) continue;
          std::pair<uint32_t, uint32_t> p{kNoVertex, kNoVertex};
          for (int c = 0; c < 3; ++c) {
            if (before[t][c] == u) p.first = expected[t][c];
            if (before[t][c] == v) p.second = expected[t][c];
          }
          partner.push_back(p);
        }
        Result<Corners> corners = fronts.value().corners(rt);
        ASSERT_TRUE(corners.is_ok()) << corners.status().message();
        size_t f = 0;
        for (uint32_t t = 0; t < triangles; ++t) {
          if (!rt.alive(t)) continue;
          const std::array<uint32_t, 3>& actual = corners.value()[f++];
          for (int c = 0; c < 3; ++c) {
            if (before[t][c] != u) continue;
            ASSERT_EQ(rt.corners(t)[c], v);
            uint32_t& w = expected[t][c];
            std::vector<uint32_t> candidates;
            for (const auto& [at_u, at_v] : partner)
              if (at_u == w) candidates.push_back(at_v);
            if (candidates.empty()) {
              ++kept;
              continue;
            }
            ++partnered;
            // Partners that disagree (a seam edge whose ends differ at v
            // only): the first in FANH's removed list, which the runtime's
            // triangles do not show; any of them is the rule's.
            const bool agree = std::all_of(candidates.begin(), candidates.end(),
                                           [&](uint32_t x) { return x == candidates.front(); });
            if (!agree &&
                std::find(candidates.begin(), candidates.end(), actual[c]) != candidates.end()) {
              w = actual[c];
            } else {
              w = candidates.front();
            }
          }
        }
        Corners alive;
        for (uint32_t t = 0; t < triangles; ++t)
          if (rt.alive(t)) alive.push_back(expected[t]);
        ASSERT_EQ(corners.value(), alive) << "node " << node << " child " << k;
      }
    }
    EXPECT_GT(partnered, 0u);
    // The seams the collapses cross away from their edge.
    RecordProperty("kept_" + std::to_string(b.mesh.triangle_count()), std::to_string(kept));
  }
}

INSTANTIATE_TEST_SUITE_P(Assets, FanWedgesTest,
                         testing::Values("Duck/Duck.gltf", "CesiumMilkTruck/CesiumMilkTruck.gltf",
                                         "Fox/Fox.gltf"),
                         [](const testing::TestParamInfo<std::string>& param) {
                           return param.param.substr(0, param.param.find('/'));
                         });

// Wedges that are not the structure's own are refused, naming the problem.
TEST(FanWedges, RefusesWedgesThatAreNotTheStructuresOwn) {
  std::vector<Built> all = build_all("Duck/Duck.gltf");
  ASSERT_FALSE(all.empty());
  const Built& b = all.front();
  auto refused = [&](const TriangleMesh& mesh, const FanHierarchy& h, const PmWedges& w) {
    Result<FanWedges> r = FanWedges::create(mesh, h, w);
    EXPECT_FALSE(r.is_ok());
    return r.is_ok() ? std::string() : r.status().message();
  };
  PmWedges split = b.wedges;
  split.added.push_back({0, 0, 0, 0, 0, 0});
  split.moved_offset.push_back(0);
  EXPECT_NE(refused(b.mesh, b.h, split).find("splits"), std::string::npos);
  PmWedges fewer = b.wedges;
  fewer.base.pop_back();
  EXPECT_NE(refused(b.mesh, b.h, fewer).find("triangles, BASE has"), std::string::npos);
  // Two corners of a triangle swapped: each wedge at another vertex.
  PmWedges swapped = b.wedges;
  std::swap(swapped.base[7][0], swapped.base[7][1]);
  EXPECT_NE(refused(b.mesh, b.h, swapped).find("triangle 7's corner"), std::string::npos);
  PmWedges out_of_range = b.wedges;
  out_of_range.base[3][2] = static_cast<uint32_t>(b.wedges.wedge_count());
  EXPECT_NE(refused(b.mesh, b.h, out_of_range).find("out of range"), std::string::npos);
  // A hierarchy whose steps do not fit the mesh's triangles.
  TriangleMesh rotated = b.mesh;
  PmWedges rotated_wedges = b.wedges;
  for (size_t t = 0; t < rotated.triangles.size(); ++t) {
    std::swap(rotated.triangles[t][0], rotated.triangles[t][1]);
    std::swap(rotated_wedges.base[t][0], rotated_wedges.base[t][1]);
  }
  std::swap(rotated.triangles[0], rotated.triangles.back());
  std::swap(rotated_wedges.base[0], rotated_wedges.base.back());
  EXPECT_NE(refused(rotated, b.h, rotated_wedges).find("does not replay"), std::string::npos);
  // Another mesh's hierarchy.
  std::vector<Built> other = build_all("Fox/Fox.gltf");
  ASSERT_FALSE(other.empty());
  EXPECT_NE(refused(b.mesh, other.front().h, b.wedges).find("fan hierarchy over"),
            std::string::npos);
}

// BASE + FANH + `wedges` as WEDG, raw, in one group, opened.
OpenedContainer fan_container(const Built& b, const PmWedges& wedges) {
  ContainerWriter writer;
  Result<Bytes> base = encode_base(b.mesh, BaseEncodeOptions());
  Result<Bytes> fanh = encode_fanh(b.h);
  Result<Bytes> wedg = encode_wedg(wedges);
  EXPECT_TRUE(base.is_ok() && fanh.is_ok() && wedg.is_ok());
  EXPECT_TRUE(writer.add_known_section(kBaseTag, base.value()).is_ok());
  EXPECT_TRUE(writer.add_known_section(kFanhTag, fanh.value()).is_ok());
  EXPECT_TRUE(writer.add_known_section(kWedgTag, wedg.value()).is_ok());
  Result<Bytes> file = writer.finish();
  EXPECT_TRUE(file.is_ok());
  Result<OpenedContainer> opened = open_container(std::move(file).value());
  EXPECT_TRUE(opened.is_ok()) << opened.status().message();
  return std::move(opened).value();
}

std::string findings_of(const OpenedContainer& file) {
  std::string out;
  for (const SectionFinding& f : validate_container(file.decoded()))
    out += f.tag + ": " + f.message + "\n";
  return out;
}

// What replay and --validate load: the group's own WEDG gives every front
// its wedges; another's is refused at load (kInvalidInput: exit 3) and
// named by --validate.
TEST(FanWedges, ContainersLoadTheirOwnWedgesOnly) {
  std::vector<Built> all = build_all("Duck/Duck.gltf");
  ASSERT_FALSE(all.empty());
  const Built& b = all.front();
  {
    const OpenedContainer own = fan_container(b, b.wedges);
    Result<FanStructure> loaded = load_fan_structure(own.decoded(), 0);
    ASSERT_TRUE(loaded.is_ok()) << loaded.status().message();
    ASSERT_TRUE(loaded.value().fronts.has_value());
    EXPECT_EQ(*loaded.value().wedges, b.wedges);
    EXPECT_EQ(findings_of(own), "");
  }
  PmWedges swapped = b.wedges;
  std::swap(swapped.base[7][0], swapped.base[7][1]);
  PmWedges split = b.wedges;
  split.added.push_back({kNoVertex, kNoVertex, kNoVertex, kNoVertex, kNoVertex, kNoVertex});
  split.moved_offset.push_back(0);
  PmWedges fewer = b.wedges;
  fewer.base.pop_back();
  for (const PmWedges* foreign : {&swapped, &split, &fewer}) {
    const OpenedContainer file = fan_container(b, *foreign);
    Result<FanStructure> loaded = load_fan_structure(file.decoded(), 0);
    ASSERT_FALSE(loaded.is_ok());
    EXPECT_EQ(loaded.status().kind(), ErrorKind::kInvalidInput);
    EXPECT_EQ(loaded.status().message().rfind("section WEDG: ", 0), 0u)
        << loaded.status().message();
    const std::string findings = findings_of(file);
    EXPECT_NE(findings.find("WEDG: "), std::string::npos) << findings;
  }
}

}  // namespace
}  // namespace lodbake
