// simplify() gives the same bytes for any thread count: the engine's parts
// are cut by the thread count (lib/core/parallel.h) and every step's result
// must not depend on where. Compared with 1, 2 and 7 threads (7 cuts parts
// that are neither halves nor powers of two) on real meshes and on random
// ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "lib/ingest/load_mesh.h"
#include "lib/simplify/simplify.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

// A mesh the tools would repair (the Stanford dragon decimations have
// duplicate faces and non-manifold edges), repaired as `--repair` does.
TriangleMesh load_repaired_mesh(const std::string& file) {
  LoadOptions options = clean_mesh_options();
  options.repair = true;
  options.strict = false;
  LoadedMesh loaded;
  const Status status = load_mesh(shared_mesh_path(file), options, &loaded);
  EXPECT_TRUE(status.is_ok()) << file << ": " << status.message();
  return loaded.mesh;
}

// A w x h grid of quads on a randomly displaced height field, each quad
// cut along a random diagonal, the vertices numbered in a random order:
// random costs and ties, random vertex order, an open border.
TriangleMesh random_grid(uint32_t w, uint32_t h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> height(0.0f, 0.2f);
  std::vector<uint32_t> id(size_t{w} * h);
  for (uint32_t i = 0; i < id.size(); ++i)
    id[i] = i;
  std::shuffle(id.begin(), id.end(), rng);
  TriangleMesh mesh;
  mesh.positions.resize(id.size());
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      // Whole heights in steps of 1/64 on a third of the vertices: exact
      // cost ties.
      const float z = rng() % 3 == 0 ? static_cast<float>(rng() % 4) / 64 : height(rng);
      mesh.positions[id[size_t{y} * w + x]] = {static_cast<float>(x), static_cast<float>(y), z};
    }
  }
  auto v = [&](uint32_t x, uint32_t y) { return id[size_t{y} * w + x]; };
  for (uint32_t y = 0; y + 1 < h; ++y) {
    for (uint32_t x = 0; x + 1 < w; ++x) {
      if (rng() % 2) {
        mesh.triangles.push_back({v(x, y), v(x + 1, y), v(x + 1, y + 1)});
        mesh.triangles.push_back({v(x, y), v(x + 1, y + 1), v(x, y + 1)});
      } else {
        mesh.triangles.push_back({v(x, y), v(x + 1, y), v(x, y + 1)});
        mesh.triangles.push_back({v(x + 1, y), v(x + 1, y + 1), v(x, y + 1)});
      }
    }
  }
  std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), rng);
  return mesh;
}

SimplifyResult run(const TriangleMesh& mesh, SimplifyOptions options, unsigned threads) {
  options.threads = threads;
  Result<SimplifyResult> result = simplify(mesh, options);
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  if (!result.is_ok()) return SimplifyResult();
  return std::move(result).value();
}

// Runs `options` with 1, 2 and 7 threads and expects the same mesh, PM
// and statistics.
void expect_same_for_every_thread_count(const TriangleMesh& mesh, const SimplifyOptions& options) {
  const SimplifyResult one = run(mesh, options, 1);
  ASSERT_LT(one.mesh.triangles.size(), mesh.triangles.size());
  ASSERT_GT(one.stats.passes, 1u);
  if (options.record_pm) {
    ASSERT_TRUE(one.pm.has_value());
  }
  for (unsigned threads : {2u, 7u}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    const SimplifyResult other = run(mesh, options, threads);
    EXPECT_EQ(one.mesh, other.mesh);
    EXPECT_EQ(one.pm, other.pm);
    EXPECT_EQ(one.stats.collapses, other.stats.collapses);
    EXPECT_EQ(one.stats.passes, other.stats.passes);
    EXPECT_EQ(one.stats.refused_link, other.stats.refused_link);
    EXPECT_EQ(one.stats.refused_flip, other.stats.refused_flip);
    EXPECT_EQ(one.stats.max_collapse_error, other.stats.max_collapse_error);
  }
}

TEST(SimplifyThreads, BunnySameForOneTwoAndSeven) {
  const TriangleMesh bunny = load_clean_mesh("stanford_bun_zipper.ply");
  for (Placement placement : {Placement::kHalf, Placement::kOptimal}) {
    SimplifyOptions options;
    options.placement = placement;
    options.record_pm = placement == Placement::kHalf;
    options.target_ratio = 0.02;
    SCOPED_TRACE(placement == Placement::kHalf ? "half" : "optimal");
    expect_same_for_every_thread_count(bunny, options);
  }
}

TEST(SimplifyThreads, DragonsSameForOneTwoAndSeven) {
  for (const char* file :
       {"stanford_dragon_vrip_res3.ply.gz", "stanford_dragon_vrip_res2.ply.gz"}) {
    SCOPED_TRACE(file);
    const TriangleMesh dragon = load_repaired_mesh(file);
    ASSERT_GT(dragon.triangles.size(), 40000u);
    SimplifyOptions options;
    options.record_pm = true;
    options.target_ratio = 0.01;
    options.height_guard = true;
    expect_same_for_every_thread_count(dragon, options);
  }
}

TEST(SimplifyThreads, RandomMeshesSameForOneTwoAndSeven) {
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    // 2 * 139 * 121 = 33,360 triangles: above the sizes from which every
    // step runs in parts.
    const TriangleMesh mesh = random_grid(140, 122, seed);
    SimplifyOptions options;
    options.record_pm = seed % 2 == 1;
    options.placement = seed <= 2 ? Placement::kHalf : Placement::kOptimal;
    options.target_ratio = seed % 2 == 1 ? 0.05 : 0.3;
    expect_same_for_every_thread_count(mesh, options);
  }
}

}  // namespace
}  // namespace lodbake
