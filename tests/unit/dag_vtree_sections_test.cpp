// DAGE and VTRE sections: round trips of the structures built from real
// progressive meshes, the fuzz seeds (small hand-made PMs) decode and
// re-encode byte for byte, every truncation and appended byte is refused
// with LBK-E023, single-bit flips never crash, and the validators find
// redundant edges and fans naming vertices that do not exist.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/dage.h"
#include "formats/sections/section_validation.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vtre.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/simplify/simplify.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "split_front_support.h"
#include "test_meshes.h"
#include "test_support.h"

namespace lodbake {
namespace {

ProgressiveMesh record(const TriangleMesh& mesh) {
  SimplifyOptions options;
  options.record_pm = true;
  Result<SimplifyResult> result = simplify(mesh, options);
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  return result.is_ok() ? *std::move(result).value().pm : ProgressiveMesh();
}

// The small PMs the fuzz seeds are made of: a genus-1 torus grid and a
// square with a boundary.
std::vector<std::pair<std::string, ProgressiveMesh>> seed_pms() {
  TriangleMesh square = test_meshes::make(
      {{0, 0, 0},
       {1, 0, 0},
       {2, 0, 0},
       {0, 1, 0},
       {1, 1, 0.2f},
       {2, 1, 0},
       {0, 2, 0},
       {1, 2, 0},
       {2, 2, 0}},
      {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {3, 4, 7}, {3, 7, 6}, {4, 5, 8}, {4, 8, 7}});
  return {{"torus", record(test_meshes::torus(5, 4))}, {"square", record(square)}};
}

void expect_e023(const Status& status, const std::string& what) {
  EXPECT_FALSE(status.is_ok()) << what;
  EXPECT_EQ(status.code(), 23) << what << ": " << status.message();
}

TEST(DageSection, RoundTripsRealDags) {
  for (const char* file : {"npm_bunny.obj", "cgal_elephant-with-holes.off"}) {
    const ProgressiveMesh pm = front_test::record_half_pm(file);
    Result<VsplitDag> dag = build_vsplit_dag(pm);
    ASSERT_TRUE(dag.is_ok()) << dag.status().message();
    Result<Bytes> bytes = encode_dage(dag.value());
    ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
    DageSummary summary;
    Result<VsplitDag> back = decode_dage(bytes.value().data(), bytes.value().size(), &summary);
    ASSERT_TRUE(back.is_ok()) << back.status().message();
    EXPECT_EQ(back.value(), dag.value());
    EXPECT_EQ(summary.node_count, pm.splits.size());
    EXPECT_EQ(summary.base_vertex_count, pm.base.vertex_count());
    EXPECT_EQ(summary.edge_count, dag.value().edge_count());
    EXPECT_GT(summary.root_count, 0u);
    EXPECT_TRUE(validate_dage(back.value()).empty());
    Result<DageSummary> fixed = read_dage_summary(bytes.value().data(), bytes.value().size());
    ASSERT_TRUE(fixed.is_ok());
    EXPECT_EQ(fixed.value().leaf_count, summary.leaf_count);
  }
}

TEST(VtreSection, RoundTripsRealTrees) {
  for (const char* file : {"npm_bunny.obj", "cgal_mushroom.off"}) {
    const ProgressiveMesh pm = front_test::record_half_pm(file);
    Result<VertexTrees> trees = build_vertex_trees(pm);
    ASSERT_TRUE(trees.is_ok()) << trees.status().message();
    EXPECT_TRUE(validate_vtre(trees.value()).empty());
    Result<Bytes> bytes = encode_vtre(trees.value());
    ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
    VtreSummary summary;
    VtreRecordSizes sizes;
    Result<VertexTrees> back =
        decode_vtre(bytes.value().data(), bytes.value().size(), &summary, &sizes);
    ASSERT_TRUE(back.is_ok()) << back.status().message();
    EXPECT_EQ(back.value(), trees.value());
    EXPECT_EQ(summary.node_count(), trees.value().node_count());
    const VtreRecordSizes expected = vtre_record_sizes(trees.value());
    EXPECT_EQ(sizes.base_bits, expected.base_bits);
    EXPECT_EQ(sizes.left_bits, expected.left_bits);
    EXPECT_EQ(sizes.right_bits, expected.right_bits);
    EXPECT_EQ(sizes.left_records, pm.splits.size());
    // The records and the 20 fixed bytes make the payload.
    EXPECT_EQ((sizes.base_bits + sizes.left_bits + sizes.right_bits + 7) / 8 + kVtreFixedBytes,
              bytes.value().size());
    // A right record has no coordinate: smaller than a left one on average.
    EXPECT_LT(sizes.right_bits / sizes.right_records, sizes.left_bits / sizes.left_records);
  }
}

// The seeds in tests/fuzz/corpus/{dage,vtre}_section are these encodings;
// LODBAKE_WRITE_SEEDS=<dir> writes them there instead of comparing.
TEST(DagVtreSections, FuzzSeedsAreTheCurrentEncodings) {
  const std::string write_dir = testing_util::env_or("LODBAKE_WRITE_SEEDS", "");
  const std::string corpus = std::string(LODBAKE_TEST_SOURCE_DIR) + "/tests/fuzz/corpus/";
  for (const auto& [name, pm] : seed_pms()) {
    ASSERT_GT(pm.splits.size(), 0u) << name;
    Result<VsplitDag> dag = build_vsplit_dag(pm);
    Result<VertexTrees> trees = build_vertex_trees(pm);
    ASSERT_TRUE(dag.is_ok() && trees.is_ok()) << name;
    const Bytes dage = encode_dage(dag.value()).value();
    const Bytes vtre = encode_vtre(trees.value()).value();
    EXPECT_LT(dage.size(), 2048u);
    EXPECT_LT(vtre.size(), 2048u);
    if (!write_dir.empty()) {
      ASSERT_TRUE(write_file_atomic(write_dir + "/dage_section/" + name + ".bin", dage).is_ok());
      ASSERT_TRUE(write_file_atomic(write_dir + "/vtre_section/" + name + ".bin", vtre).is_ok());
      continue;
    }
    EXPECT_EQ(testing_util::read_bytes(corpus + "dage_section/" + name + ".bin"), dage) << name;
    EXPECT_EQ(testing_util::read_bytes(corpus + "vtre_section/" + name + ".bin"), vtre) << name;
  }
}

TEST(DagVtreSections, TruncationsAndTrailingBytesAreRefused) {
  for (const auto& [name, pm] : seed_pms()) {
    const Bytes dage = encode_dage(build_vsplit_dag(pm).value()).value();
    const Bytes vtre = encode_vtre(build_vertex_trees(pm).value()).value();
    for (size_t len = 0; len < dage.size(); ++len)
      expect_e023(decode_dage(dage.data(), len).status(),
                  name + " DAGE cut at " + std::to_string(len));
    for (size_t len = 0; len < vtre.size(); ++len)
      expect_e023(decode_vtre(vtre.data(), len).status(),
                  name + " VTRE cut at " + std::to_string(len));
    Bytes longer = dage;
    longer.push_back(0);
    expect_e023(decode_dage(longer.data(), longer.size()).status(), name + " DAGE + 1 byte");
    longer = vtre;
    longer.push_back(0);
    expect_e023(decode_vtre(longer.data(), longer.size()).status(), name + " VTRE + 1 byte");
    // Bit flips: either refused with E023 or a DAG / trees that re-encode.
    for (size_t bit = 0; bit < 8 * dage.size(); ++bit) {
      Bytes flipped = dage;
      flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      Result<VsplitDag> d = decode_dage(flipped.data(), flipped.size());
      if (d.is_ok()) {
        EXPECT_EQ(encode_dage(d.value()).value(), flipped) << name << " bit " << bit;
      } else {
        EXPECT_EQ(d.status().code(), 23);
      }
    }
    for (size_t bit = 0; bit < 8 * vtre.size(); ++bit) {
      Bytes flipped = vtre;
      flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      Result<VertexTrees> t = decode_vtre(flipped.data(), flipped.size());
      if (t.is_ok()) {
        EXPECT_TRUE(validate_vtre(t.value()).empty());
      } else {
        EXPECT_EQ(t.status().code(), 23);
      }
    }
  }
}

TEST(DageSection, TheFormatDocumentsExampleBytes) {
  VsplitDag dag;  // docs/format.md section 15
  dag.base_vertex_count = 3;
  dag.parent_offsets = {0, 0, 1, 2};
  dag.parents = {0, 1};
  const Bytes expected = {3, 0, 0, 0, 3, 0, 0, 0, 2, 0, 0, 0,   1,
                          0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 0, 0x26};
  Result<Bytes> bytes = encode_dage(dag);
  ASSERT_TRUE(bytes.is_ok());
  EXPECT_EQ(bytes.value(), expected);
}

TEST(DageSection, ValidationFindsRedundantEdgesAndEncodeRefusesCycles) {
  VsplitDag dag;
  dag.parent_offsets = {0, 0, 1, 3};
  dag.parents = {0, 0, 1};  // 2 -> 0 is implied by 2 -> 1 -> 0
  const std::vector<std::string> findings = validate_dage(dag);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_NE(findings[0].find("1 edges are implied"), std::string::npos) << findings[0];
  Result<Bytes> bytes = encode_dage(dag);
  ASSERT_TRUE(bytes.is_ok());  // redundancy is a validation finding, not a layout error
  dag.parents = {0, 2, 1};     // node 1's parent 2 is not below it
  dag.parent_offsets = {0, 0, 2, 3};
  EXPECT_FALSE(encode_dage(dag).is_ok());
}

TEST(VtreSection, CountsThePayloadCannotHoldAreRefusedBeforeAllocating) {
  // One vertex (0 id bits), no runs, but 2^32 - 16 fan entries claimed.
  Bytes bytes = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xF0, 0xFF, 0xFF, 0xFF, 0, 0, 0, 0};
  bytes.resize(bytes.size() + 12, 0);
  Result<VertexTrees> trees = decode_vtre(bytes.data(), bytes.size());
  expect_e023(trees.status(), "fan entries without runs");
  // 2^31 base vertices in 44 bytes.
  Bytes huge = {0, 0, 0, 0x80, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 31, 0, 0, 0};
  huge.resize(44, 0);
  expect_e023(decode_vtre(huge.data(), huge.size()).status(), "2^31 vertices");
  // DAGE: 2^32 - 2 nodes in 8 bytes of stream.
  Bytes dage = {0xFE, 0xFF, 0xFF, 0xFF, 3, 0, 0, 0, 0, 0,  0, 0,
                1,    0,    0,    0,    1, 0, 0, 0, 1, 32, 0, 0};
  dage.resize(32, 0);
  expect_e023(decode_dage(dage.data(), dage.size()).status(), "2^32 - 2 nodes");
}

TEST(VtreSection, ValidationFindsFansNamingMissingVertices) {
  const ProgressiveMesh pm = seed_pms()[0].second;
  Result<VertexTrees> trees = build_vertex_trees(pm);
  ASSERT_TRUE(trees.is_ok());
  VertexTrees broken = trees.value();
  broken.fan_vertices[0] = static_cast<uint32_t>(broken.positions.size());  // past the last vertex
  const std::vector<std::string> findings = validate_vtre(broken);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_NE(findings[0].find("do not reference a valid node"), std::string::npos) << findings[0];
  Result<Bytes> refused = encode_vtre(broken);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_NE(refused.status().message().find("cannot encode VTRE"), std::string::npos);
}

// A container with BASE + VSPL + DAGE + VTRE of one PM validates clean; the
// DAGE and VTRE of another PM are reported as not matching its VSPL.
Bytes container_bytes(const ProgressiveMesh& pm, const ProgressiveMesh& structures_from) {
  ContainerWriter writer;
  EXPECT_TRUE(writer.add_section(kBaseTag, encode_base(pm.base, {}).value(), true).is_ok());
  EXPECT_TRUE(writer.add_section(kVsplTag, encode_vspl(pm, {}).value(), true).is_ok());
  EXPECT_TRUE(writer
                  .add_section(kDageTag,
                               encode_dage(build_vsplit_dag(structures_from).value()).value(),
                               false)
                  .is_ok());
  EXPECT_TRUE(writer
                  .add_section(kVtreTag,
                               encode_vtre(build_vertex_trees(structures_from).value()).value(),
                               false)
                  .is_ok());
  return writer.finish().value();
}

std::vector<SectionFinding> container_findings(const ProgressiveMesh& pm,
                                               const ProgressiveMesh& structures_from) {
  const Bytes file = container_bytes(pm, structures_from);
  Result<Container> container = read_container(file.data(), file.size());
  EXPECT_TRUE(container.is_ok()) << container.status().message();
  if (!container.is_ok()) return {};
  return validate_sections(container.value());
}

TEST(DagVtreSections, ContainerValidationChecksThemAgainstVspl) {
  const std::vector<std::pair<std::string, ProgressiveMesh>> pms = seed_pms();
  for (const SectionFinding& f : container_findings(pms[0].second, pms[0].second))
    ADD_FAILURE() << f.tag << ": " << f.message;
  const std::vector<SectionFinding> findings = container_findings(pms[0].second, pms[1].second);
  size_t dage = 0;
  size_t vtre = 0;
  for (const SectionFinding& f : findings) {
    dage += f.tag == kDageTag && f.message.find("but VSPL holds") != std::string::npos;
    vtre += f.tag == kVtreTag && f.message.find("but VSPL holds") != std::string::npos;
  }
  EXPECT_EQ(dage, 1u);
  EXPECT_EQ(vtre, 1u);
}

// The CLI cases' containers (tests/data/containers/README.md) are these;
// LODBAKE_WRITE_CONTAINERS=<dir> writes them there instead of comparing.
TEST(DagVtreSections, CliContainersAreTheCurrentEncodings) {
  const std::vector<std::pair<std::string, ProgressiveMesh>> pms = seed_pms();
  const std::vector<std::pair<std::string, Bytes>> files = {
      {"torus_dag_vtrees.lbk", container_bytes(pms[0].second, pms[0].second)},
      {"torus_dag_vtrees_of_square.lbk", container_bytes(pms[0].second, pms[1].second)}};
  const std::string write_dir = testing_util::env_or("LODBAKE_WRITE_CONTAINERS", "");
  const std::string dir = std::string(LODBAKE_TEST_SOURCE_DIR) + "/tests/data/containers/";
  for (const auto& [name, bytes] : files) {
    EXPECT_LT(bytes.size(), 2048u) << name;
    if (!write_dir.empty()) {
      ASSERT_TRUE(write_file_atomic(write_dir + "/" + name, bytes).is_ok());
    } else {
      EXPECT_EQ(testing_util::read_bytes(dir + name), bytes) << name;
    }
  }
}

}  // namespace
}  // namespace lodbake
