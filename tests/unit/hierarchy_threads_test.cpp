// The hierarchy step's sections (BASE, VHIE, RFIN, VSPL, DAGE, VTRE) are
// the same bytes for 1, 2 and 7 threads, on a real mesh and on random
// meshes large enough that every parallel step cuts several parts (a
// round's listing splits at 2 x 4096 vertices, its sort at 32768
// candidates).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "lib/bake/hierarchy_step.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

// Every section of the step, tag and bytes, in order.
std::vector<std::pair<std::string, Bytes>> sections(const TriangleMesh& mesh, unsigned threads) {
  HierarchyStepOptions request;
  request.options.threads = threads;
  EXPECT_TRUE(parse_hierarchy_sections(&request).is_ok());
  HierarchyBuilt built = take(build_hierarchy_sections(request, mesh), "hierarchy sections");
  std::vector<std::pair<std::string, Bytes>> out;
  for (HierarchySection& s : built.sections)
    out.emplace_back(s.tag, std::move(s.bytes));
  return out;
}

void expect_same_for_every_thread_count(const TriangleMesh& mesh, const std::string& name) {
  const std::vector<std::pair<std::string, Bytes>> one = sections(mesh, 1);
  ASSERT_EQ(one.size(), 6u) << name;
  for (const auto& [tag, bytes] : one)
    EXPECT_GT(bytes.size(), 0u) << name << " " << tag;
  for (unsigned threads : {2u, 7u}) {
    const std::vector<std::pair<std::string, Bytes>> other = sections(mesh, threads);
    ASSERT_EQ(other.size(), one.size()) << name << ", " << threads << " threads";
    for (size_t i = 0; i < one.size(); ++i) {
      EXPECT_EQ(other[i].first, one[i].first) << name;
      EXPECT_TRUE(other[i].second == one[i].second)
          << name << ": " << one[i].first << " differs with " << threads << " threads";
    }
  }
}

// A height field over a jittered side x side grid (one boundary loop),
// each cell cut along a random diagonal, its vertices in a random order.
TriangleMesh random_terrain(uint32_t side, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
  std::uniform_real_distribution<float> height(0.0f, 2.0f);
  const uint32_t n = side * side;
  std::vector<uint32_t> slot(n);
  std::iota(slot.begin(), slot.end(), 0u);
  std::shuffle(slot.begin(), slot.end(), rng);
  TriangleMesh mesh;
  mesh.positions.resize(n);
  for (uint32_t y = 0; y < side; ++y) {
    for (uint32_t x = 0; x < side; ++x) {
      mesh.positions[slot[y * side + x]] = {static_cast<float>(x) + jitter(rng),
                                            static_cast<float>(y) + jitter(rng), height(rng)};
    }
  }
  for (uint32_t y = 0; y + 1 < side; ++y) {
    for (uint32_t x = 0; x + 1 < side; ++x) {
      const uint32_t a = slot[y * side + x], b = slot[y * side + x + 1];
      const uint32_t c = slot[(y + 1) * side + x], d = slot[(y + 1) * side + x + 1];
      if (rng() % 2 == 0) {
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({a, d, c});
      } else {
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({b, d, c});
      }
    }
  }
  return mesh;
}

TEST(HierarchyThreads, SameSectionsOnTheBunny) {
  TriangleMesh mesh = load_clean_mesh("stanford_bun_zipper.ply");
  mesh.normals = MeshAttribute();
  mesh.texcoords = MeshAttribute();
  ASSERT_GT(mesh.vertex_count(), 7u * 4096u);
  expect_same_for_every_thread_count(mesh, "bunny");
}

TEST(HierarchyThreads, SameSectionsOnRandomMeshes) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const TriangleMesh mesh = random_terrain(180 + 10 * seed, seed);
    expect_same_for_every_thread_count(mesh, "random terrain " + std::to_string(seed));
  }
}

}  // namespace
}  // namespace lodbake
