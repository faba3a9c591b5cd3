// lodbake-fan's and lodbake-strips' builds (lib/bake's steps, as the tools
// and lodbake-bake run them) give the same bytes for 1, 2 and 7 threads, on
// a real scan and on random meshes large enough that 2 and 7 threads cut
// their work into several parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "lib/bake/fan_step.h"
#include "lib/bake/strips_step.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

// A w x w grid over the unit square with random heights and random quad
// diagonals (which break the rows into many strips), its vertices and
// triangles shuffled (so that index ranges are scattered over the surface).
TriangleMesh random_terrain(uint32_t w, uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> height(0.0f, 0.02f);
  std::vector<uint32_t> slot(w * w);
  for (uint32_t i = 0; i < slot.size(); ++i)
    slot[i] = i;
  std::shuffle(slot.begin(), slot.end(), random);
  TriangleMesh mesh;
  mesh.positions.resize(slot.size());
  for (uint32_t y = 0; y < w; ++y)
    for (uint32_t x = 0; x < w; ++x)
      mesh.positions[slot[y * w + x]] = {static_cast<float>(x) / static_cast<float>(w - 1),
                                         static_cast<float>(y) / static_cast<float>(w - 1),
                                         height(random)};
  for (uint32_t y = 0; y + 1 < w; ++y)
    for (uint32_t x = 0; x + 1 < w; ++x) {
      const uint32_t a = slot[y * w + x], b = slot[y * w + x + 1];
      const uint32_t c = slot[(y + 1) * w + x], d = slot[(y + 1) * w + x + 1];
      if (random() % 2 == 0) {
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({a, d, c});
      } else {
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({b, d, c});
      }
    }
  std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), random);
  return mesh;
}

void expect_same_fan(const TriangleMesh& mesh, const std::string& what) {
  SCOPED_TRACE(what);
  // The fan's parts own 8,192 vertices at least: 2 threads cut 2 parts.
  ASSERT_GE(mesh.vertex_count(), 2u * 8192);
  FanBuildOptions options;
  options.threads = 1;
  const FanBuilt one = take(build_fan(options, mesh), "fan, 1 thread");
  ASSERT_GT(one.result.stats.merges, 0u);
  for (unsigned threads : {2u, 7u}) {
    options.threads = threads;
    const FanBuilt again = take(build_fan(options, mesh), "fan");
    EXPECT_EQ(again.fanh, one.fanh) << threads << " threads";
    EXPECT_EQ(again.base, one.base) << threads << " threads";
    EXPECT_EQ(again.counts, one.counts) << threads << " threads";
    EXPECT_EQ(again.result.stats.refused_flip, one.result.stats.refused_flip);
    EXPECT_EQ(again.result.stats.refused_topology, one.result.stats.refused_topology);
  }
}

StripsBuilt strips_with(const TriangleMesh& mesh, unsigned threads) {
  StripsStepOptions request;
  request.threads = threads;
  StripsInput in;
  in.pm = std::make_shared<const ProgressiveMesh>(
      take(record_pm(mesh, nullptr, threads), "progressive mesh"));
  return take(build_strips(request, in), "strips and SETS");
}

void expect_same_strips(const TriangleMesh& mesh, const std::string& what) {
  SCOPED_TRACE(what);
  const StripsBuilt one = strips_with(mesh, 1);
  // The SETS ranges hold 512 strips at least: 2 threads cut 2 ranges.
  ASSERT_GE(one.strip_stats.strips, 2u * 512);
  ASSERT_EQ(one.sections.size(), 3u);  // BASE, VSPL, SETS
  for (unsigned threads : {2u, 7u}) {
    const StripsBuilt again = strips_with(mesh, threads);
    ASSERT_EQ(again.sections.size(), one.sections.size());
    for (size_t i = 0; i < one.sections.size(); ++i) {
      EXPECT_EQ(again.sections[i].first, one.sections[i].first);
      EXPECT_EQ(again.sections[i].second, one.sections[i].second)
          << one.sections[i].first << ", " << threads << " threads";
    }
    EXPECT_EQ(again.counts, one.counts);
    for (const char* key : {"strip_updates", "removed_indices", "emptied_strips", "nodes", "arcs"})
      EXPECT_EQ(again.report["sets"][key], one.report["sets"][key]) << key;
  }
}

TEST(BuilderThreads, FanIsTheSameForAnyThreadCount) {
  expect_same_fan(load_clean_mesh("stanford_bun_zipper.ply"), "bunny");
  for (uint32_t seed : {1u, 2u})
    expect_same_fan(random_terrain(130 + 10 * seed, seed), "terrain " + std::to_string(seed));
}

TEST(BuilderThreads, StripsAndSetsAreTheSameForAnyThreadCount) {
  expect_same_strips(load_clean_mesh("stanford_bun_zipper.ply"), "bunny");
  for (uint32_t seed : {1u, 2u})
    expect_same_strips(random_terrain(100 + 20 * seed, seed), "terrain " + std::to_string(seed));
}

}  // namespace
}  // namespace lodbake
