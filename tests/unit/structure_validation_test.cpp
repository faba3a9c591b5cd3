// validate_container(): the deep checks find damage that each section's own
// validation lets through, and name the damaged section. The containers are
// the consumer fuzz target's seeds (tests/fuzz/corpus/consumers), each
// damaged in one structure field, re-encoded, with every CRC recomputed.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/dage.h"
#include "formats/sections/fanh.h"
#include "formats/sections/open_container.h"
#include "formats/sections/section_validation.h"
#include "formats/sections/sets.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vtre.h"
#include "formats/support/file_io.h"
#include "lib/replay/structure_loading.h"
#include "lib/validate/structure_validation.h"

namespace lodbake {
namespace {

std::string source(const std::string& relative) {
  return std::string(LODBAKE_TEST_SOURCE_DIR) + "/" + relative;
}

OpenedContainer open_file(const std::string& relative) {
  Result<OpenedContainer> opened = open_container_file(source(relative));
  EXPECT_TRUE(opened.is_ok()) << opened.status().message();
  return std::move(opened).value();
}

OpenedContainer seed(const std::string& name) {
  return open_file("tests/fuzz/corpus/consumers/" + name);
}

// The container with `tag` (group 0) replaced by `payload`, stored raw.
OpenedContainer replaced(const OpenedContainer& file, const char* tag, const Bytes& payload) {
  ContainerWriter writer;
  for (const Section& s : file.decoded().sections) {
    const bool target = s.tag() == tag && s.group() == 0;
    const Bytes bytes = target ? payload : Bytes(s.data, s.data + s.size);
    EXPECT_TRUE(writer.add_section(s.tag(), bytes, s.required(), s.group()).is_ok());
  }
  Result<Bytes> out = writer.finish();
  EXPECT_TRUE(out.is_ok());
  Result<OpenedContainer> opened = open_container(std::move(out).value());
  EXPECT_TRUE(opened.is_ok()) << opened.status().message();
  return std::move(opened).value();
}

bool names(const std::vector<SectionFinding>& findings, const std::string& tag) {
  for (const SectionFinding& f : findings) {
    if (f.tag == tag) return true;
  }
  return false;
}

std::string listed(const std::vector<SectionFinding>& findings) {
  std::string out;
  for (const SectionFinding& f : findings)
    out += f.tag + ": " + f.message + "\n";
  return out;
}

TEST(StructureValidation, EverySeedPasses) {
  for (const char* name :
       {"hier_ico.lbk", "hier_ico_compact.lbk", "hier_grid.lbk", "fan_ico.lbk", "fan_grid.lbk",
        "sets_ico.lbk", "sets_grid.lbk", "strp_ico.lbk", "pm_ico.lbk", "merged_ico.lbk",
        "merged_grid.lbk", "torus_dag_vtrees.lbk"}) {
    const OpenedContainer file = seed(name);
    const std::vector<SectionFinding> findings = validate_container(file.decoded());
    EXPECT_TRUE(findings.empty()) << name << "\n" << listed(findings);
  }
}

// The example: both cut vertices of a split on one leaf of another
// tree; VHIE's own checks pass it, mode stream refuses it.
TEST(StructureValidation, DamagedCutVerticesAreFound) {
  const OpenedContainer file = open_file("tests/data/containers/torus_vhie_damaged_cuts.lbk");
  EXPECT_TRUE(validate_sections(file.decoded()).empty());
  const std::vector<SectionFinding> findings = validate_container(file.decoded());
  ASSERT_FALSE(findings.empty());
  EXPECT_EQ(findings.front().tag, kVhieTag);
  EXPECT_NE(findings.front().message.find("mode vhier"), std::string::npos);
}

// Found by the consumers fuzz target: a VHIE cut vertex that works when
// every node is split in index order but not on the fronts mode stream
// reaches; the cut vertices are checked against the wing faces.
TEST(StructureValidation, CutVertexThatWorksInOneOrderIsFound) {
  const OpenedContainer file = seed("found_vhie_cut_order.lbk");
  EXPECT_TRUE(validate_sections(file.decoded()).empty());
  const std::vector<SectionFinding> findings = validate_container(file.decoded());
  ASSERT_FALSE(findings.empty());
  EXPECT_EQ(findings.front().tag, kVhieTag);
  EXPECT_NE(findings.front().message.find("wing faces"), std::string::npos)
      << findings.front().message;
}

// Damages `tag` of `name` through `edit` on its decoded structure and
// returns the findings; `deep_only`: the sections' own checks pass it.
template <typename T>
std::vector<SectionFinding> damaged(const std::string& name, const char* tag,
                                    const std::function<Result<T>(const Section&)>& decode,
                                    const std::function<void(T*)>& edit,
                                    const std::function<Result<Bytes>(const T&)>& encode,
                                    bool deep_only) {
  const OpenedContainer file = seed(name);
  const Section* section = file.find(tag, 0);
  EXPECT_NE(section, nullptr);
  Result<T> value = decode(*section);
  EXPECT_TRUE(value.is_ok());
  edit(&value.value());
  Result<Bytes> bytes = encode(value.value());
  EXPECT_TRUE(bytes.is_ok()) << bytes.status().message();
  const OpenedContainer broken = replaced(file, tag, bytes.value());
  // Damage that only the use of the structure shows passes the sections'
  // own checks.
  if (deep_only) {
    EXPECT_TRUE(validate_sections(broken.decoded()).empty()) << tag;
  }
  return validate_container(broken.decoded());
}

TEST(StructureValidation, VhieCutVerticesSwapped) {
  const OpenedContainer file = seed("hier_ico.lbk");
  Result<VhierStructure> loaded = load_vhier_structure(file.decoded(), 0);
  ASSERT_TRUE(loaded.is_ok());
  // Every internal node's two cut vertices exchanged.
  VertexHierarchy bad = *loaded.value().h;
  size_t changed = 0;
  for (uint32_t s = 0; s < bad.node_count(); ++s) {
    if (bad.is_leaf(s) || bad.cut_left[s] == kNoNode) continue;
    std::swap(bad.cut_left[s], bad.cut_right[s]);
    ++changed;
  }
  ASSERT_GT(changed, 0u);
  Result<Bytes> bytes = encode_vhie(bad);
  ASSERT_TRUE(bytes.is_ok());
  const OpenedContainer broken = replaced(file, kVhieTag, bytes.value());
  EXPECT_TRUE(validate_sections(broken.decoded()).empty());
  const std::vector<SectionFinding> findings = validate_container(broken.decoded());
  EXPECT_TRUE(names(findings, kVhieTag)) << listed(findings);
}

TEST(StructureValidation, DageMissingDependencyIsFound) {
  std::vector<SectionFinding> findings = damaged<VsplitDag>(
      "hier_ico.lbk", kDageTag, [](const Section& s) { return decode_dage(s.data, s.size); },
      [](VsplitDag* dag) {
        // The last node with parents loses them all (still a well-formed DAG).
        for (size_t k = dag->node_count(); k-- > 0;) {
          const uint32_t first = dag->parent_offsets[k], last = dag->parent_offsets[k + 1];
          if (first == last) continue;
          dag->parents.erase(dag->parents.begin() + first, dag->parents.begin() + last);
          for (size_t j = k + 1; j < dag->parent_offsets.size(); ++j)
            dag->parent_offsets[j] -= last - first;
          break;
        }
      },
      [](const VsplitDag& dag) { return encode_dage(dag); }, true);
  EXPECT_TRUE(names(findings, kDageTag)) << listed(findings);
}

TEST(StructureValidation, FanhChildListIsFound) {
  std::vector<SectionFinding> findings = damaged<FanHierarchy>(
      "fan_ico.lbk", kFanhTag, [](const Section& s) { return decode_fanh(s.data, s.size); },
      [](FanHierarchy* h) {
        // The first internal node's first two children exchanged.
        ASSERT_GE(h->child_start.size(), 2u);
        ASSERT_GE(h->child_start[1] - h->child_start[0], 2u);
        std::swap(h->children[h->child_start[0]], h->children[h->child_start[0] + 1]);
      },
      [](const FanHierarchy& h) { return encode_fanh(h); }, false);
  EXPECT_TRUE(names(findings, kFanhTag)) << listed(findings);
}

TEST(StructureValidation, SetsLabelIsFound) {
  std::vector<SectionFinding> findings = damaged<SetsGraph>(
      "sets_ico.lbk", kSetsTag, [](const Section& s) { return decode_sets(s.data, s.size); },
      [](SetsGraph* g) {
        // An arc's label moved to the next LoD.
        for (uint32_t& lod : g->arc_lod) {
          if (lod + 1 < g->lod_count) {
            ++lod;
            break;
          }
        }
      },
      [](const SetsGraph& g) { return encode_sets(g); }, false);
  EXPECT_TRUE(names(findings, kSetsTag)) << listed(findings);
}

TEST(StructureValidation, VtreFanIsFound) {
  std::vector<SectionFinding> findings = damaged<VertexTrees>(
      "hier_ico.lbk", kVtreTag, [](const Section& s) { return decode_vtre(s.data, s.size); },
      [](VertexTrees* t) {
        // A fan vertex replaced by another vertex of the trees.
        ASSERT_GE(t->fan_vertices.size(), 2u);
        std::swap(t->fan_vertices[0], t->fan_vertices[1]);
      },
      [](const VertexTrees& t) { return encode_vtre(t); }, true);
  EXPECT_TRUE(names(findings, kVtreTag)) << listed(findings);
}

// A group other than 0 is named in the finding.
TEST(StructureValidation, FindingsNameTheirGroup) {
  const OpenedContainer file = seed("merged_ico.lbk");
  ASSERT_GT(file.group_count(), 1u);
  const Container& c = file.decoded();
  // Group 1 holds the fan hierarchy: swap two children there.
  ContainerWriter writer;
  for (const Section& s : c.sections) {
    Bytes bytes(s.data, s.data + s.size);
    if (s.tag() == kFanhTag) {
      Result<FanHierarchy> h = decode_fanh(s.data, s.size);
      ASSERT_TRUE(h.is_ok());
      std::swap(h.value().children[0], h.value().children[1]);
      bytes = encode_fanh(h.value()).value();
    }
    ASSERT_TRUE(writer.add_section(s.tag(), bytes, s.required(), s.group()).is_ok());
  }
  Result<OpenedContainer> broken = open_container(writer.finish().value());
  ASSERT_TRUE(broken.is_ok());
  const std::vector<SectionFinding> findings = validate_container(broken.value().decoded());
  ASSERT_TRUE(names(findings, kFanhTag)) << listed(findings);
  for (const SectionFinding& f : findings) {
    if (f.tag == kFanhTag) {
      EXPECT_EQ(f.message.rfind("group ", 0), 0u) << f.message;
    }
  }
}

}  // namespace
}  // namespace lodbake
