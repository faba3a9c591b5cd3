// Mode sets of the replay runtime (lib/replay/sets_replay.h): the recovery
// tests' LoD sequences (counts, order, endpoints, spacing); the runner with
// validation on the sample, a shared mesh with a boundary and a torus (every
// recovered LoD is the PM's with its orientation, coherent equals fresh);
// validation failing on a corrupted graph and against another LoD's mesh.
#include "lib/replay/sets_replay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "lib/simplify/simplify.h"
#include "lib/strips/sets_build.h"
#include "lib/strips/stripify.h"
#include "simplify_test_meshes.h"
#include "test_meshes.h"

namespace lodbake {
namespace {

// The descent of a sequence (up to the coarsest LoD) after checking the
// shape every test shares: LoD 0 first and last, strictly increasing to
// the coarsest LoD, then the same LoDs strictly decreasing.
std::vector<uint32_t> checked_descent(const std::vector<uint32_t>& lods, uint32_t lod_count,
                                      const std::string& what) {
  EXPECT_FALSE(lods.empty()) << what;
  if (lods.empty()) return {};
  EXPECT_EQ(lods.size() % 2, 1u) << what;
  const size_t d = lods.size() / 2 + 1;
  std::vector<uint32_t> down(lods.begin(), lods.begin() + d);
  EXPECT_EQ(lods.front(), 0u) << what;
  EXPECT_EQ(lods.back(), 0u) << what;
  EXPECT_EQ(down.back(), lod_count - 1) << what;
  for (size_t i = 1; i < d; ++i)
    EXPECT_LT(down[i - 1], down[i]) << what << " descent at " << i;
  for (size_t i = 0; i + 1 < d; ++i)
    EXPECT_EQ(lods[lods.size() - 1 - i], down[i]) << what << " ascent mirrors the descent";
  return down;
}

TEST(RecoveryTestLods, SmallExamplesSpacedLinearlyAndExponentially) {
  // 10% of 100 LoDs: 10 positions; linear t * 99, exponential 100^t - 1.
  EXPECT_EQ(recovery_test_lods(100, 10, LodSpacing::kLinear),
            (std::vector<uint32_t>{0, 11, 22, 33, 44, 55, 66, 77, 88, 99, 88, 77, 66, 55, 44, 33,
                                   22, 11, 0}));
  EXPECT_EQ(
      recovery_test_lods(100, 10, LodSpacing::kExponential),
      (std::vector<uint32_t>{0, 1, 2, 4, 7, 12, 21, 35, 59, 99, 59, 35, 21, 12, 7, 4, 2, 1, 0}));
  // Fewer LoDs than 2 positions: both ends anyway; one LoD: just LoD 0.
  EXPECT_EQ(recovery_test_lods(50, 1, LodSpacing::kLinear), (std::vector<uint32_t>{0, 49, 0}));
  EXPECT_EQ(recovery_test_lods(2, 20, LodSpacing::kExponential), (std::vector<uint32_t>{0, 1, 0}));
  EXPECT_EQ(recovery_test_lods(1, 20, LodSpacing::kLinear), (std::vector<uint32_t>{0}));
  // 100% linear: every LoD down and back. Exponential positions crowd at
  // LoD 0 and skip near the base: 7^(5/6) - 1 = 4.05 rounds to the LoD 4
  // already taken, so LoD 5 is never visited.
  EXPECT_EQ(recovery_test_lods(7, 100, LodSpacing::kLinear),
            (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 5, 4, 3, 2, 1, 0}));
  EXPECT_EQ(recovery_test_lods(7, 100, LodSpacing::kExponential),
            (std::vector<uint32_t>{0, 1, 2, 3, 4, 6, 4, 3, 2, 1, 0}));
  EXPECT_EQ(paper_recovery_percents(), (std::vector<double>{1, 3, 6, 10, 15, 20}));
  EXPECT_STREQ(spacing_name(LodSpacing::kLinear), "linear");
  EXPECT_STREQ(spacing_name(LodSpacing::kExponential), "exponential");
}

TEST(RecoveryTestLods, CountsOrderAndEndpointsOfThePapersTests) {
  for (uint32_t lod_count : {3u, 97u, 2758u, 34820u}) {
    for (double percent : {1.0, 3.0, 6.0, 10.0, 15.0, 20.0, 2.5, 100.0}) {
      const std::string what =
          std::to_string(lod_count) + " LoDs, " + std::to_string(percent) + "%";
      const uint32_t n = std::max<uint32_t>(2, static_cast<uint32_t>(lod_count * percent / 100));
      const std::vector<uint32_t> linear = checked_descent(
          recovery_test_lods(lod_count, percent, LodSpacing::kLinear), lod_count, what + " linear");
      const std::vector<uint32_t> exponential =
          checked_descent(recovery_test_lods(lod_count, percent, LodSpacing::kExponential),
                          lod_count, what + " exponential");
      // Linear positions are at least one LoD apart: none is dropped.
      EXPECT_EQ(linear.size(), n) << what;
      EXPECT_LE(exponential.size(), n) << what;
      // Evenly spaced (within rounding) against dense near the full mesh.
      for (size_t i = 1; i < linear.size(); ++i) {
        EXPECT_LE(linear[i] - linear[i - 1], (lod_count - 1) / (n - 1) + 1) << what;
        EXPECT_GE(linear[i] - linear[i - 1], (lod_count - 1) / (n - 1)) << what;
      }
      if (exponential.size() >= 4) {
        EXPECT_LT(exponential[1] - exponential[0],
                  exponential.back() - exponential[exponential.size() - 2])
            << what;
      }
    }
  }
  // The sample's sizes, as lodbake-replay reports them (2758 LoDs).
  EXPECT_EQ(recovery_test_lods(2758, 1, LodSpacing::kLinear).size(), 53u);
  EXPECT_EQ(recovery_test_lods(2758, 1, LodSpacing::kExponential).size(), 49u);
  EXPECT_EQ(recovery_test_lods(2758, 20, LodSpacing::kLinear).size(), 1101u);
}

TEST(SummarizeSetsTest, MeansAndRates) {
  std::vector<SetsStep> steps(2);
  steps[0].indices = 100;
  steps[0].fresh_us = 1;
  steps[0].coherent_us = 0.5;
  steps[1].indices = 300;
  steps[1].fresh_us = 3;
  steps[1].coherent_us = 1.5;
  const SetsTestSummary s = summarize_sets_test(LodSpacing::kExponential, 6, steps);
  EXPECT_EQ(s.spacing, LodSpacing::kExponential);
  EXPECT_EQ(s.percent, 6);
  EXPECT_EQ(s.lods, 2u);
  EXPECT_EQ(s.indices, 400u);
  EXPECT_DOUBLE_EQ(s.fresh_us_per_lod, 2);
  EXPECT_DOUBLE_EQ(s.coherent_us_per_lod, 1);
  EXPECT_DOUBLE_EQ(s.fresh_mindices_per_s, 100);  // 400 indices in 4 us
  EXPECT_DOUBLE_EQ(s.coherent_mindices_per_s, 200);
  const SetsTestSummary empty = summarize_sets_test(LodSpacing::kLinear, 1, {});
  EXPECT_EQ(empty.lods, 0u);
  EXPECT_EQ(empty.fresh_us_per_lod, 0);
  EXPECT_EQ(empty.coherent_mindices_per_s, 0);
}

// What lodbake-strips writes: the PM of the mesh, strips of its full mesh,
// the SETS graph over both, and the graph through its codec.
struct Built {
  ProgressiveMesh pm;
  SetsGraph graph;
};

Built build(const TriangleMesh& input) {
  Built b;
  SimplifyOptions options;
  options.record_pm = true;
  Result<SimplifyResult> simplified = simplify(input, options);
  EXPECT_TRUE(simplified.is_ok()) << simplified.status().message();
  if (!simplified.is_ok()) return b;
  b.pm = *std::move(simplified).value().pm;
  Result<TriangleMesh> full = mesh_at_lod(b.pm, b.pm.full_vertex_count());
  EXPECT_TRUE(full.is_ok());
  Result<TriangleStrips> strips = stripify(full.value());
  EXPECT_TRUE(strips.is_ok());
  Result<SetsGraph> graph = build_sets(strips.value(), b.pm);
  EXPECT_TRUE(graph.is_ok()) << graph.status().message();
  Result<Bytes> bytes = encode_sets(graph.value());
  EXPECT_TRUE(bytes.is_ok());
  Result<SetsGraph> decoded = decode_sets(bytes.value().data(), bytes.value().size());
  EXPECT_TRUE(decoded.is_ok()) << decoded.status().message();
  if (decoded.is_ok()) b.graph = std::move(decoded).value();
  return b;
}

TriangleMesh sample_mesh() {
  LoadedMesh loaded;
  const std::string path = std::string(LODBAKE_TEST_SOURCE_DIR) + "/samples/elephant.off";
  const Status status = load_mesh(path, clean_mesh_options(), &loaded);
  EXPECT_TRUE(status.is_ok()) << path << ": " << status.message();
  return loaded.mesh;
}

void expect_tests_validate(const Built& b, const std::vector<double>& percents,
                           const std::string& what, bool many_strips) {
  Result<SetsReplay> replay = SetsReplay::create(b.pm, b.graph);
  ASSERT_TRUE(replay.is_ok()) << what << ": " << replay.status().message();
  ASSERT_EQ(replay.value().lod_count(), b.pm.splits.size() + 1);
  for (LodSpacing spacing : {LodSpacing::kLinear, LodSpacing::kExponential}) {
    for (double percent : percents) {
      const std::string test = what + " " + spacing_name(spacing) + " " + std::to_string(percent);
      const std::vector<uint32_t> lods =
          recovery_test_lods(replay.value().lod_count(), percent, spacing);
      Result<std::vector<SetsStep>> steps = run_sets_test(&replay.value(), lods, true);
      ASSERT_TRUE(steps.is_ok()) << test << ": " << steps.status().message();
      ASSERT_EQ(steps.value().size(), lods.size()) << test;
      uint64_t walked = 0, strips = 0;
      for (size_t k = 0; k < lods.size(); ++k) {
        const SetsStep& step = steps.value()[k];
        EXPECT_EQ(step.lod, lods[k]) << test;
        EXPECT_GT(step.indices, 0u) << test;
        EXPECT_GE(step.indices, step.triangles + 2 * step.strips) << test;
        EXPECT_GE(step.fresh_us, 0) << test;
        walked += step.coherent_walked_strips;
        strips += step.strips;
      }
      // LoD 0 at both ends: every full-mesh triangle, the same strips.
      EXPECT_EQ(steps.value().front().indices, steps.value().back().indices) << test;
      EXPECT_EQ(steps.value().front().triangles, steps.value().back().triangles) << test;
      // The first coherent recovery of a test walks every strip (restart()).
      EXPECT_EQ(steps.value().front().coherent_walked_strips, steps.value().front().strips) << test;
      // Coherence never walks more than a fresh recovery; on meshes with
      // many strips (not the torus's few) and LoDs close enough together,
      // under half as many.
      EXPECT_LE(walked, strips) << test;
      if (many_strips && percent >= 6) {
        EXPECT_LT(walked, strips / 2) << test;
      }
      const SetsTestSummary summary = summarize_sets_test(spacing, percent, steps.value());
      EXPECT_EQ(summary.lods, lods.size()) << test;
      EXPECT_GT(summary.fresh_us_per_lod, 0) << test;
      EXPECT_GT(summary.fresh_mindices_per_s, 0) << test;
    }
  }
}

TEST(SetsReplay, SampleTestsValidateAtEveryLod) {
  const TriangleMesh input = sample_mesh();
  ASSERT_EQ(input.triangle_count(), 5558u);
  const Built b = build(input);
  ASSERT_EQ(b.graph.lod_count, b.pm.splits.size() + 1);
  expect_tests_validate(b, {1, 3, 6}, "elephant", true);
  // LoD 0's step counts the full mesh's triangles.
  Result<SetsReplay> replay = SetsReplay::create(b.pm, b.graph);
  ASSERT_TRUE(replay.is_ok());
  Result<SetsStep> step = replay.value().step(0);
  ASSERT_TRUE(step.is_ok());
  EXPECT_EQ(step.value().triangles, 5558u);
}

TEST(SetsReplay, MeshWithABoundaryAndATorusValidate) {
  TriangleMesh mushroom = load_clean_mesh("cgal_mushroom.off");
  ASSERT_EQ(mushroom.triangle_count(), 4608u);
  mushroom.normals = MeshAttribute();
  mushroom.texcoords = MeshAttribute();
  expect_tests_validate(build(mushroom), {1, 10}, "mushroom", true);
  expect_tests_validate(build(test_meshes::torus(14, 10)), {1, 20, 100}, "torus", false);
}

TEST(SetsReplay, OutOfRangeLodAndMismatchedGraphAreRefused) {
  const Built torus = build(test_meshes::torus(10, 8));
  const Built other = build(test_meshes::torus(12, 8));
  EXPECT_FALSE(SetsReplay::create(torus.pm, other.graph).is_ok());
  Result<SetsReplay> replay = SetsReplay::create(torus.pm, torus.graph);
  ASSERT_TRUE(replay.is_ok());
  EXPECT_FALSE(replay.value().check().empty());  // nothing recovered yet
  Result<std::vector<SetsStep>> steps =
      run_sets_test(&replay.value(), {0, replay.value().lod_count()}, false);
  ASSERT_FALSE(steps.is_ok());
  EXPECT_EQ(steps.status().message().rfind("step 1, LoD ", 0), 0u) << steps.status().message();
}

TEST(SetsReplay, ValidationFindsAnotherLodsTriangles) {
  const Built b = build(test_meshes::torus(14, 10));
  Result<SetsReplay> replay = SetsReplay::create(b.pm, b.graph);
  ASSERT_TRUE(replay.is_ok());
  const uint32_t lod = replay.value().lod_count() / 2;
  ASSERT_TRUE(replay.value().step(lod).is_ok());
  EXPECT_TRUE(replay.value().check().empty());
  // The strips of `lod` against the PM one contraction further: the
  // triangles around the contracted edge differ.
  const std::vector<std::string> problems = replay.value().check(lod + 1);
  ASSERT_FALSE(problems.empty());
  EXPECT_NE(problems[0].find("PM triangles"), std::string::npos) << problems[0];
  // And back at its own LoD all is well again (the PM refines back).
  EXPECT_TRUE(replay.value().check(lod).empty());
}

TEST(SetsReplay, ValidationFailsOnACorruptedGraphNamingTheStep) {
  Built b = build(test_meshes::torus(14, 10));
  // Two nodes of different vertices swap vertices: every walk still
  // reaches END (the structure holds), but the triangles change.
  const uint32_t a = 0;
  uint32_t c = 1;
  while (b.graph.node_vertex[c] == b.graph.node_vertex[a])
    ++c;
  std::swap(b.graph.node_vertex[a], b.graph.node_vertex[c]);
  ASSERT_TRUE(check_sets_structure(b.graph).is_ok());
  Result<SetsReplay> replay = SetsReplay::create(b.pm, b.graph);
  ASSERT_TRUE(replay.is_ok()) << replay.status().message();
  const std::vector<uint32_t> lods =
      recovery_test_lods(replay.value().lod_count(), 10, LodSpacing::kLinear);
  // Without validation the run completes: only the check sees it.
  EXPECT_TRUE(run_sets_test(&replay.value(), lods, false).is_ok());
  Result<std::vector<SetsStep>> steps = run_sets_test(&replay.value(), lods, true);
  ASSERT_FALSE(steps.is_ok());
  EXPECT_EQ(steps.status().kind(), ErrorKind::kValidation);
  EXPECT_EQ(steps.status().message().rfind("step 0, LoD 0: ", 0), 0u) << steps.status().message();
  EXPECT_NE(steps.status().message().find("PM triangles"), std::string::npos)
      << steps.status().message();
}

}  // namespace
}  // namespace lodbake
