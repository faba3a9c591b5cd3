// lib/strips: the stripifier covers every triangle once with its
// orientation; compaction follows the paper's Figure 1; the SETS graph gives,
// at every LoD of small meshes and sampled LoDs of the bunny, exactly the
// progressive mesh's oriented triangles; coherent recovery equals fresh
// recovery along any LoD sequence; validation catches a broken graph.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "lib/strips/chunked_array.h"
#include "lib/strips/sets_build.h"
#include "lib/strips/sets_recovery.h"
#include "lib/strips/strip_compaction.h"
#include "lib/strips/stripify.h"
#include "simplify_test_meshes.h"
#include "test_meshes.h"

namespace lodbake {
namespace {

ProgressiveMesh record(const TriangleMesh& mesh) {
  SimplifyOptions options;
  options.record_pm = true;
  options.placement = Placement::kHalf;
  Result<SimplifyResult> result = simplify(mesh, options);
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  if (!result.is_ok()) return ProgressiveMesh();
  return *std::move(result).value().pm;
}

TriangleMesh with_triangles(size_t vertices, std::vector<Triangle> triangles) {
  TriangleMesh mesh;
  mesh.positions.assign(vertices, Vec3f{0, 0, 0});
  mesh.triangles = std::move(triangles);
  return mesh;
}

void expect_covers(const TriangleMesh& mesh, const TriangleStrips& strips,
                   const std::string& what) {
  EXPECT_TRUE(same_oriented_triangles(with_triangles(mesh.vertex_count(), mesh.triangles),
                                      with_triangles(mesh.vertex_count(), strip_triangles(strips))))
      << what;
}

std::vector<uint32_t> compacted(std::vector<uint32_t> s) {
  compact_strip(&s);
  return s;
}

TEST(StripCompaction, FollowsThePapersFigureOne) {
  // a..h = 0..7. LoD 2: [b,b,d,d,e,f,g,h] -> [d,d,e,f,g,h].
  EXPECT_EQ(compacted({1, 1, 3, 3, 4, 5, 6, 7}), (std::vector<uint32_t>{3, 3, 4, 5, 6, 7}));
  // LoD 3: [d,d,e,d,g,h] -> [e,d,g,h].
  EXPECT_EQ(compacted({3, 3, 4, 3, 6, 7}), (std::vector<uint32_t>{4, 3, 6, 7}));
  // LoD 4: [e,d,h,h] -> [e,d,h] (the tail after the last triangle goes).
  EXPECT_EQ(compacted({4, 3, 7, 7}), (std::vector<uint32_t>{4, 3, 7}));
  // LoD 1 cannot be shortened: removing "d d" would create (a, b, e).
  EXPECT_EQ(compacted({0, 1, 3, 3, 4, 5, 6, 7}), (std::vector<uint32_t>{0, 1, 3, 3, 4, 5, 6, 7}));
  // No triangle left: empty.
  EXPECT_TRUE(compacted({2, 2, 3, 3, 2}).empty());
}

TEST(StripCompaction, KeepsTheTrianglesOfRandomSequences) {
  std::mt19937 rng(7);
  for (int round = 0; round < 20000; ++round) {
    std::vector<uint32_t> s(3 + rng() % 14);
    for (uint32_t& v : s)
      v = rng() % 5;
    std::vector<uint32_t> c = compacted(s);
    std::vector<Triangle> before, after;
    append_strip_triangles(s.data(), s.size(), &before);
    append_strip_triangles(c.data(), c.size(), &after);
    EXPECT_TRUE(same_oriented_triangles(with_triangles(5, before), with_triangles(5, after)))
        << "round " << round;
    EXPECT_LE(c.size(), s.size());
    // What is left is a contiguous-pairs reduction: no removable pair stays.
    EXPECT_EQ(compacted(c), c) << "round " << round;
  }
}

// Each id's successors at its occurrences, in order (kNone after the last).
std::vector<std::vector<uint32_t>> successor_runs(const std::vector<uint32_t>& s, uint32_t ids) {
  std::vector<std::vector<uint32_t>> runs(ids);
  for (size_t i = 0; i < s.size(); ++i)
    runs[s[i]].push_back(i + 1 < s.size() ? s[i + 1] : 0xFFFFFFFFu);
  return runs;
}

TEST(StripCompaction, NotesEveryIdWhoseSuccessorsChange) {
  // The SETS build re-records only the noted ids: any other id still present
  // must keep its successor run exactly.
  std::mt19937 rng(11);
  size_t noted_some = 0;
  for (int round = 0; round < 20000; ++round) {
    std::vector<uint32_t> s(3 + rng() % 14);
    for (uint32_t& v : s)
      v = rng() % 5;
    std::vector<uint32_t> c = s, changed;
    compact_strip(&c, &changed);
    EXPECT_EQ(c, compacted(s)) << "round " << round;
    noted_some += !changed.empty();
    const auto before = successor_runs(s, 5), after = successor_runs(c, 5);
    for (uint32_t id = 0; id < 5; ++id) {
      if (after[id].empty() || std::find(changed.begin(), changed.end(), id) != changed.end())
        continue;
      EXPECT_EQ(after[id], before[id]) << "round " << round << ", id " << id;
    }
  }
  EXPECT_GT(noted_some, 1000u);  // the property was exercised
}

TEST(Stripify, CoversSmallMeshesWithTheirOrientation) {
  for (const auto& [name, mesh] : std::vector<std::pair<std::string, TriangleMesh>>{
           {"tetrahedron", test_meshes::tetrahedron()},
           {"open_square", test_meshes::open_square()},
           {"torus", test_meshes::torus(12, 9)},
           {"klein_bottle", test_meshes::klein_bottle(8, 6)},
           {"moebius", test_meshes::moebius_band(9)},
           {"bowtie", test_meshes::bowtie()}}) {
    StripifyStats stats;
    Result<TriangleStrips> strips = stripify(mesh, &stats);
    ASSERT_TRUE(strips.is_ok()) << name;
    expect_covers(mesh, strips.value(), name);
    EXPECT_EQ(stats.triangles, mesh.triangle_count()) << name;
    EXPECT_EQ(stats.indices, strips.value().indices.size()) << name;
  }
}

TEST(Stripify, SkipsDegenerateTrianglesAndRejectsBadIndices) {
  TriangleMesh mesh = test_meshes::open_square();
  mesh.triangles.push_back({1, 1, 2});
  StripifyStats stats;
  Result<TriangleStrips> strips = stripify(mesh, &stats);
  ASSERT_TRUE(strips.is_ok());
  EXPECT_EQ(stats.skipped_degenerate, 1u);
  EXPECT_EQ(strip_triangles(strips.value()).size(), 2u);
  mesh.triangles.push_back({0, 1, 9});
  EXPECT_FALSE(stripify(mesh).is_ok());
}

TEST(Stripify, BunnyStripsAreLongAndExact) {
  const TriangleMesh mesh = load_clean_mesh("stanford_bun_zipper.ply");
  StripifyStats stats;
  Result<TriangleStrips> strips = stripify(mesh, &stats);
  ASSERT_TRUE(strips.is_ok());
  expect_covers(mesh, strips.value(), "bunny");
  // A triangle list takes 3; long strips approach 1.
  EXPECT_LT(stats.indices_per_triangle(), 1.6);
  EXPECT_LT(stats.swaps, stats.triangles / 10);
}

struct Sets {
  ProgressiveMesh pm;
  TriangleStrips strips;
  SetsGraph graph;
};

Sets build(const TriangleMesh& input) {
  Sets sets;
  sets.pm = record(input);
  Result<TriangleMesh> full = mesh_at_lod(sets.pm, sets.pm.full_vertex_count());
  EXPECT_TRUE(full.is_ok());
  Result<TriangleStrips> strips = stripify(full.value());
  EXPECT_TRUE(strips.is_ok());
  sets.strips = strips.value();
  Result<SetsGraph> graph = build_sets(sets.strips, sets.pm);
  EXPECT_TRUE(graph.is_ok()) << graph.status().message();
  if (graph.is_ok()) sets.graph = graph.value();
  return sets;
}

// Recovers every LoD in `lods` with a fresh and a coherent recovery and
// compares both with the progressive mesh at that LoD.
void expect_lods_match(const Sets& sets, const std::vector<uint32_t>& lods,
                       const std::string& what) {
  Result<StripRecovery> fresh = StripRecovery::create(sets.graph);
  Result<StripRecovery> coherent = StripRecovery::create(sets.graph);
  ASSERT_TRUE(fresh.is_ok() && coherent.is_ok()) << fresh.status().message();
  Result<PmRefiner> refiner = PmRefiner::create(sets.pm);
  ASSERT_TRUE(refiner.is_ok());
  const size_t full = sets.pm.full_vertex_count();
  for (uint32_t lod : lods) {
    ASSERT_TRUE(fresh.value().recover(lod).is_ok()) << what << " LoD " << lod;
    ASSERT_TRUE(coherent.value().recover_coherent(lod).is_ok()) << what << " LoD " << lod;
    ASSERT_TRUE(refiner.value().refine_to(full - lod).is_ok());
    const TriangleMesh& pm_mesh = refiner.value().mesh();
    // The checks lodbake-replay --mode sets --validate runs.
    const std::vector<std::string> problems =
        check_recovered_triangles(fresh.value(), pm_mesh.triangles);
    ASSERT_TRUE(problems.empty()) << what << " LoD " << lod << ": " << problems[0];
    ASSERT_EQ(compare_recoveries(coherent.value(), fresh.value()), "") << what << " LoD " << lod;
    ASSERT_EQ(coherent.value().to_strips(), fresh.value().to_strips()) << what << " LoD " << lod;
    // The walk in formats/ (validation's reference) agrees strip by strip.
    for (size_t s = 0; s < sets.graph.strip_count(); s += 1 + sets.graph.strip_count() / 16) {
      Result<std::vector<uint32_t>> walked = walk_strip(sets.graph, s, lod);
      ASSERT_TRUE(walked.is_ok());
      const auto& idx = fresh.value().indices();
      ASSERT_EQ(walked.value(), std::vector<uint32_t>(
                                    idx.begin() + fresh.value().first(s),
                                    idx.begin() + fresh.value().first(s) + fresh.value().count(s)));
    }
  }
}

std::vector<uint32_t> all_lods(uint32_t count) {
  std::vector<uint32_t> lods(count);
  for (uint32_t l = 0; l < count; ++l)
    lods[l] = l;
  return lods;
}

class SetsOnSmallMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(SetsOnSmallMesh, EveryLodHasThePmTrianglesWithOrientation) {
  TriangleMesh input;
  const std::string name = GetParam();
  if (name == "torus") {
    input = test_meshes::torus(14, 10);
  } else {
    input = load_clean_mesh(name);
    input.normals = MeshAttribute();
    input.texcoords = MeshAttribute();
  }
  const Sets sets = build(input);
  ASSERT_EQ(sets.graph.lod_count, sets.pm.splits.size() + 1);
  EXPECT_TRUE(validate_sets(sets.graph).empty());
  std::vector<uint32_t> lods = all_lods(sets.graph.lod_count);
  expect_lods_match(sets, lods, name + " coarsening");
  std::reverse(lods.begin(), lods.end());
  expect_lods_match(sets, lods, name + " refining");
  // Random jumps: coherent recovery must forget nothing.
  std::mt19937 rng(11);
  std::vector<uint32_t> jumps(200);
  for (uint32_t& l : jumps)
    l = rng() % sets.graph.lod_count;
  expect_lods_match(sets, jumps, name + " random");
}

INSTANTIATE_TEST_SUITE_P(Meshes, SetsOnSmallMesh,
                         ::testing::Values("torus", "cgal_tetrahedron.off", "cgal_mpi.off",
                                           "cgal_mushroom.off"));

TEST(SetsOnBunny, SampledLodsMatchAndCoherentEqualsFresh) {
  TriangleMesh input = load_clean_mesh("stanford_bun_zipper.ply");
  const Sets sets = build(input);
  const uint32_t count = sets.graph.lod_count;
  std::vector<uint32_t> lods;
  for (uint32_t i = 0; i <= 40; ++i)
    lods.push_back(static_cast<uint32_t>(uint64_t{count - 1} * i / 40));
  for (uint32_t i = 0; i <= 40; ++i)
    lods.push_back(lods[40 - i]);
  std::mt19937 rng(5);
  for (int i = 0; i < 40; ++i)
    lods.push_back(rng() % count);
  expect_lods_match(sets, lods, "bunny");
  EXPECT_TRUE(validate_sets(sets.graph).empty());
}

TEST(SetsGraph, CodecRoundTripsAndValidationFindsBrokenWalks) {
  const Sets sets = build(test_meshes::torus(10, 8));
  Result<Bytes> bytes = encode_sets(sets.graph);
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  Result<SetsGraph> decoded = decode_sets(bytes.value().data(), bytes.value().size());
  ASSERT_TRUE(decoded.is_ok()) << decoded.status().message();
  EXPECT_EQ(decoded.value(), sets.graph);
  Result<Bytes> again = encode_sets(decoded.value());
  ASSERT_TRUE(again.is_ok());
  EXPECT_EQ(again.value(), bytes.value());
  // Every truncation is refused, and so is a trailing byte.
  for (size_t n = 0; n < bytes.value().size(); ++n)
    EXPECT_FALSE(decode_sets(bytes.value().data(), n).is_ok()) << n;
  Bytes longer = bytes.value();
  longer.push_back(0);
  EXPECT_FALSE(decode_sets(longer.data(), longer.size()).is_ok());
  // A successor that ends a strip too early leaves nodes unvisited but is
  // structurally fine; one that loops makes a node run out of successors.
  SetsGraph broken = sets.graph;
  const uint32_t n0 = broken.node_first[0];
  broken.successors[broken.successor_first[broken.arc_first[n0]]] = n0;
  std::vector<std::string> findings = validate_sets(broken);
  ASSERT_FALSE(findings.empty());
  EXPECT_NE(findings[0].find("do not reach END"), std::string::npos) << findings[0];
  Result<StripRecovery> recovery = StripRecovery::create(broken);
  EXPECT_FALSE(recovery.is_ok());
  // Unsorted labels are a structure error.
  SetsGraph unsorted = sets.graph;
  for (size_t n = 0; n < unsorted.node_count(); ++n) {
    if (unsorted.arc_first[n + 1] - unsorted.arc_first[n] >= 2) {
      std::swap(unsorted.arc_lod[unsorted.arc_first[n]],
                unsorted.arc_lod[unsorted.arc_first[n] + 1]);
      break;
    }
  }
  EXPECT_FALSE(check_sets_structure(unsorted).is_ok());
  EXPECT_FALSE(encode_sets(unsorted).is_ok());
}

// A loop that only a coarser LoD's walk takes: create() (whose node layout
// walks sampled LoDs) still succeeds, recover() at LoD 0 works, and the
// broken LoD gives a Status naming the strip, fresh and coherent, while
// other strips are walked interleaved with it.
TEST(SetsGraph, RecoveryReportsAWalkThatBreaksOnlyAtACoarseLod) {
  const Sets sets = build(test_meshes::torus(10, 8));
  const SetsGraph& g = sets.graph;
  bool found = false;
  for (size_t s = 0; s < g.strip_count() && !found; ++s) {
    for (uint32_t n = g.node_first[s]; n < g.node_first[s + 1] && !found; ++n) {
      for (uint32_t a = g.arc_first[n]; a + 1 < g.arc_first[n + 1] && !found; ++a) {
        if (a == g.arc_first[n]) continue;  // keep the LoD-0 run intact
        SetsGraph broken = g;
        broken.successors[broken.successor_first[a]] = n;
        const uint32_t lod = g.arc_lod[a];
        if (walk_strip(broken, s, lod).is_ok() || !walk_strip(broken, s, 0).is_ok()) continue;
        found = true;
        Result<StripRecovery> fresh = StripRecovery::create(broken);
        ASSERT_TRUE(fresh.is_ok()) << fresh.status().message();
        EXPECT_TRUE(fresh.value().recover(0).is_ok());
        const Status status = fresh.value().recover(lod);
        ASSERT_FALSE(status.is_ok());
        EXPECT_NE(status.message().find("strip " + std::to_string(s) + " at LoD"),
                  std::string::npos)
            << status.message();
        Result<StripRecovery> coherent = StripRecovery::create(broken);
        ASSERT_TRUE(coherent.is_ok());
        ASSERT_TRUE(coherent.value().recover_coherent(0).is_ok());
        EXPECT_FALSE(coherent.value().recover_coherent(lod).is_ok());
      }
    }
  }
  EXPECT_TRUE(found) << "no arc of the torus graph breaks only a coarse walk";
}

TEST(StripsSection, CodecRoundTripsAndRefusesDamage) {
  const TriangleMesh mesh = test_meshes::torus(9, 7);
  Result<TriangleStrips> strips = stripify(mesh);
  ASSERT_TRUE(strips.is_ok());
  Result<Bytes> bytes = encode_strp(strips.value());
  ASSERT_TRUE(bytes.is_ok());
  Result<TriangleStrips> decoded = decode_strp(bytes.value().data(), bytes.value().size());
  ASSERT_TRUE(decoded.is_ok()) << decoded.status().message();
  EXPECT_EQ(decoded.value(), strips.value());
  EXPECT_TRUE(validate_strp(decoded.value(), mesh).empty());
  for (size_t n = 0; n < bytes.value().size(); ++n)
    EXPECT_FALSE(decode_strp(bytes.value().data(), n).is_ok()) << n;
  TriangleMesh other = mesh;
  std::swap(other.triangles[0][1], other.triangles[0][2]);
  EXPECT_EQ(validate_strp(decoded.value(), other).size(), 2u);
  Result<TriangleMesh> extracted = mesh_from_strips(decoded.value(), mesh);
  ASSERT_TRUE(extracted.is_ok());
  EXPECT_TRUE(same_oriented_triangles(extracted.value(), mesh));
}

// No strips over 0 vertices makes the index width 0 bits, so the payload
// size cannot bound N; N must then be 0 (fuzz_strp_section: N = 0xfff60000
// in 13 bytes reserved 16 GiB of indices).
TEST(StripsSection, RefusesIndicesWithoutStrips) {
  const Bytes strp = {0, 0, 0, 0, 0, 0, 0, 0, 0x00, 0x00, 0xf6, 0xff, 0};
  Result<TriangleStrips> decoded = decode_strp(strp.data(), strp.size());
  ASSERT_FALSE(decoded.is_ok());
  EXPECT_EQ(decoded.status().message(),
            "LBK-E023: section STRP: no strips, the header has 4294311936 indices");
  EXPECT_FALSE(read_strp_summary(strp.data(), strp.size()).is_ok());
}

// The worked examples of docs/format.md decode to what the text says.
TEST(FormatExamples, StrpAndSetsBytesOfTheSpecification) {
  const Bytes strp = {0x06, 0, 0, 0, 0x01, 0, 0, 0, 0x06, 0, 0, 0, 0x02, 0x0f, 0x4a, 0x09};
  Result<TriangleStrips> strips = decode_strp(strp.data(), strp.size());
  ASSERT_TRUE(strips.is_ok()) << strips.status().message();
  EXPECT_EQ(strips.value().indices, (std::vector<uint32_t>{3, 0, 2, 1, 5, 4}));
  EXPECT_EQ(encode_strp(strips.value()).value(), strp);

  const Bytes sets = {4, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0,    0,    0,    4,    0,   0,
                      0, 4, 0, 0, 0, 6, 0, 0, 0, 0, 2, 0, 1, 0x83, 0x7c, 0x12, 0x71, 0x00};
  Result<SetsGraph> graph = decode_sets(sets.data(), sets.size());
  ASSERT_TRUE(graph.is_ok()) << graph.status().message();
  Result<std::vector<uint32_t>> walked = walk_strip(graph.value(), 0, 0);
  ASSERT_TRUE(walked.is_ok());
  EXPECT_EQ(walked.value(), (std::vector<uint32_t>{0, 1, 2, 3, 0, 1}));
  EXPECT_EQ(encode_sets(graph.value()).value(), sets);
}

}  // namespace

// The SETS builder's record arrays: values written across chunk boundaries
// read back, and an array refills after release().
TEST(ChunkedArray, KeepsValuesAcrossChunksAndAfterRelease) {
  using strips_internal::ChunkedArray;
  ChunkedArray<uint32_t> a;
  const size_t n = 3 * ChunkedArray<uint32_t>::kChunk + 7;
  for (size_t i = 0; i < n; ++i)
    a.push_back(static_cast<uint32_t>(i * 2654435761u));
  ASSERT_EQ(a.size(), n);
  for (size_t i = 0; i < n; ++i)
    ASSERT_EQ(a[i], static_cast<uint32_t>(i * 2654435761u)) << i;
  a[ChunkedArray<uint32_t>::kChunk] = 5;
  EXPECT_EQ(a[ChunkedArray<uint32_t>::kChunk], 5u);
  EXPECT_EQ(a.back(), static_cast<uint32_t>((n - 1) * 2654435761u));
  a.release();
  EXPECT_TRUE(a.empty());
  a.push_back(9);
  EXPECT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0], 9u);
}

}  // namespace lodbake
