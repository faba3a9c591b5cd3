// The compact codecs of formats/sections/compact_sections.h (VTRE, SETS,
// VHIE, RFIN, DAGE alone; FANH and STRP against BASE), each on
// real payloads written the way the tools write them: the round trip gives
// the raw payload byte for byte, re-encoding is idempotent, the compact
// bytes are smaller, and every truncation, trailing byte and bit flip is
// either refused with LBK-E023 or (a flip inside the stream) decodes to a
// valid raw payload that round-trips again, without crashing or reading
// out of bounds (the sanitizer build checks that).
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/compact_sections.h"
#include "formats/sections/dage.h"
#include "formats/sections/fanh.h"
#include "formats/sections/rfin.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vtre.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/fanmerge/fan_build.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "lib/strips/sets_build.h"
#include "lib/strips/stripify.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "simplify_test_meshes.h"
#include "test_meshes.h"

namespace lodbake {
namespace {

// lodbake-hierarchy's progressive mesh: the balanced hierarchy's.
ProgressiveMesh hierarchy_pm(const TriangleMesh& mesh) {
  const BalancedHierarchy built =
      take(build_balanced_hierarchy(mesh, BalancedBuildOptions()), "hierarchy");
  return take(hierarchy_to_progressive_mesh(built.hierarchy), "hierarchy PM");
}

// The engine's greedy progressive mesh (lodbake-simplify --pm).
ProgressiveMesh greedy_pm(const TriangleMesh& mesh) {
  SimplifyOptions options;
  options.record_pm = true;
  SimplifyResult result = take(simplify(mesh, options), "simplify");
  return result.pm ? *result.pm : ProgressiveMesh{};
}

// lodbake-hierarchy's VHIE.
Bytes vhie_of(const TriangleMesh& mesh) {
  const BalancedHierarchy built =
      take(build_balanced_hierarchy(mesh, BalancedBuildOptions()), "hierarchy");
  return take(encode_vhie(built.hierarchy), "VHIE");
}

// lodbake-hierarchy's RFIN.
Bytes rfin_of(const TriangleMesh& mesh) {
  const BalancedHierarchy built =
      take(build_balanced_hierarchy(mesh, BalancedBuildOptions()), "hierarchy");
  const std::vector<NodeRefinement> refinement =
      take(compute_refinement_data(built.hierarchy, mesh), "refinement");
  return take(encode_rfin(built.hierarchy, refinement), "RFIN");
}

// lodbake-fan's FANH (over the full mesh, which is its BASE).
Bytes fanh_of(const TriangleMesh& mesh) {
  return take(encode_fanh(take(build_fan_hierarchy(mesh, FanBuildOptions()), "fan").hierarchy),
              "FANH");
}

// lodbake-strips --strips-only's STRP (over the full mesh, its BASE).
Bytes strp_of(const TriangleMesh& mesh) {
  return take(encode_strp(take(stripify(mesh), "strips")), "STRP");
}

// lodbake-strips' SETS: the half-placement PM, its full mesh stripified.
Bytes sets_of(const TriangleMesh& mesh) {
  SimplifyOptions options;
  options.record_pm = true;
  options.placement = Placement::kHalf;
  SimplifyResult simplified = take(simplify(mesh, options), "simplify");
  if (!simplified.pm) return {};
  const ProgressiveMesh& pm = *simplified.pm;
  const TriangleMesh full = take(mesh_at_lod(pm, pm.full_vertex_count()), "full mesh");
  const TriangleStrips strips = take(stripify(full), "strips");
  return take(encode_sets(take(build_sets(strips, pm), "SETS")), "SETS");
}

struct Sample {
  std::string name;
  const char* tag;
  std::function<Bytes()> raw;
  bool small = false;  // the exhaustive corruption checks run on these
  // The BASE mesh, for the codecs that need one (FANH).
  std::function<TriangleMesh()> base = nullptr;
};

void PrintTo(const Sample& sample, std::ostream* out) {
  *out << sample.name;
}

std::vector<Sample> samples() {
  std::vector<Sample> s;
  s.push_back({"VtreHierarchyElephant", kVtreTag, [] {
                 return take(
                     encode_vtre(take(build_vertex_trees(hierarchy_pm(bare_elephant())), "trees")),
                     "VTRE");
               }});
  s.push_back(
      {"VtreGreedyTorus", kVtreTag,
       [] {
         return take(
             encode_vtre(take(build_vertex_trees(greedy_pm(test_meshes::torus(10, 7))), "trees")),
             "VTRE");
       },
       true});
  s.push_back({"VtreNoSplits", kVtreTag,
               [] {
                 ProgressiveMesh pm;
                 pm.base = test_meshes::tetrahedron();
                 return take(encode_vtre(take(build_vertex_trees(pm), "trees")), "VTRE");
               },
               true});
  s.push_back({"VhieElephant", kVhieTag, [] { return vhie_of(bare_elephant()); }});
  s.push_back({"VhieTorus", kVhieTag, [] { return vhie_of(test_meshes::torus(8, 6)); }, true});
  s.push_back(
      {"VhieTetrahedron", kVhieTag, [] { return vhie_of(test_meshes::tetrahedron()); }, true});
  s.push_back({"RfinElephant", kRfinTag, [] { return rfin_of(bare_elephant()); }});
  s.push_back({"RfinTorus", kRfinTag, [] { return rfin_of(test_meshes::torus(8, 6)); }, true});
  s.push_back(
      {"RfinTetrahedron", kRfinTag, [] { return rfin_of(test_meshes::tetrahedron()); }, true});
  s.push_back({"FanhElephant", kFanhTag, [] { return fanh_of(bare_elephant()); }, false,
               [] { return bare_elephant(); }});
  s.push_back({"FanhTorus", kFanhTag, [] { return fanh_of(test_meshes::torus(8, 6)); }, true,
               [] { return test_meshes::torus(8, 6); }});
  s.push_back({"StrpElephant", kStrpTag, [] { return strp_of(bare_elephant()); }, false,
               [] { return bare_elephant(); }});
  s.push_back({"StrpTorus", kStrpTag, [] { return strp_of(test_meshes::torus(8, 6)); }, true,
               [] { return test_meshes::torus(8, 6); }});
  s.push_back({"StrpMoebius", kStrpTag, [] { return strp_of(test_meshes::moebius_band(12)); }, true,
               [] { return test_meshes::moebius_band(12); }});
  s.push_back({"DageHierarchyElephant", kDageTag, [] {
                 return take(
                     encode_dage(take(build_vsplit_dag(hierarchy_pm(bare_elephant())), "DAG")),
                     "DAGE");
               }});
  s.push_back({"DageGreedyTorus", kDageTag,
               [] {
                 return take(encode_dage(take(
                                 build_vsplit_dag(greedy_pm(test_meshes::torus(10, 7))), "DAG")),
                             "DAGE");
               },
               true});
  s.push_back({"SetsElephant", kSetsTag, [] { return sets_of(bare_elephant()); }});
  s.push_back({"SetsTorus", kSetsTag, [] { return sets_of(test_meshes::torus(9, 6)); }, true});
  s.push_back(
      {"SetsTetrahedron", kSetsTag, [] { return sets_of(test_meshes::tetrahedron()); }, true});
  return s;
}

const Bytes& raw_of(const Sample& sample) {
  static std::map<std::string, Bytes> cache;
  auto it = cache.find(sample.name);
  if (it == cache.end()) it = cache.emplace(sample.name, sample.raw()).first;
  return it->second;
}

const TriangleMesh& base_of(const Sample& sample) {
  static std::map<std::string, TriangleMesh> cache;
  auto it = cache.find(sample.name);
  if (it == cache.end()) it = cache.emplace(sample.name, sample.base()).first;
  return it->second;
}

// The codec of `sample`'s kind: with its BASE for FANH and STRP, alone otherwise.
Result<Bytes> encode_sample(const Sample& sample, const uint8_t* data, size_t size) {
  if (sample.base) {
    EXPECT_TRUE(has_base_compact_codec(sample.tag));
    return encode_section_compact(sample.tag, data, size, base_of(sample));
  }
  EXPECT_TRUE(has_standalone_compact_codec(sample.tag));
  return encode_section_compact(sample.tag, data, size);
}
Result<Bytes> decode_sample(const Sample& sample, const uint8_t* data, size_t size) {
  if (sample.base) return decode_section_compact(sample.tag, data, size, base_of(sample));
  return decode_section_compact(sample.tag, data, size);
}

class SectionCompact : public ::testing::TestWithParam<Sample> {};

TEST_P(SectionCompact, RoundTripsByteForByteAndIsIdempotent) {
  const Sample& sample = GetParam();
  const Bytes& raw = raw_of(sample);
  ASSERT_FALSE(raw.empty());
  const Bytes compact = take(encode_sample(sample, raw.data(), raw.size()), "encode");
  const Bytes back = take(decode_sample(sample, compact.data(), compact.size()), "decode");
  EXPECT_EQ(back, raw);
  EXPECT_EQ(take(encode_sample(sample, back.data(), back.size()), "again"), compact);
  if (raw.size() > 200) {
    EXPECT_LT(compact.size(), raw.size());
  }
}

// Exhaustive, so on the small samples only (each check decodes the payload).
class SectionCompactCorruption : public SectionCompact {};

TEST_P(SectionCompactCorruption, RefusesEveryTruncationAndTrailingBytes) {
  const Sample& sample = GetParam();
  const Bytes& raw = raw_of(sample);
  const Bytes compact = take(encode_sample(sample, raw.data(), raw.size()), "encode");
  for (size_t n = 0; n < compact.size(); ++n) {
    Result<Bytes> r = decode_sample(sample, compact.data(), n);
    ASSERT_FALSE(r.is_ok()) << "accepted " << n << " of " << compact.size() << " bytes";
    EXPECT_EQ(r.status().code(), static_cast<int>(ContainerError::kMalformedSection))
        << r.status().message();
  }
  for (uint8_t extra : {0, 1, 255}) {
    Bytes longer = compact;
    longer.push_back(extra);
    EXPECT_FALSE(decode_sample(sample, longer.data(), longer.size()).is_ok());
  }
  Bytes versioned = compact;
  versioned[0] = static_cast<uint8_t>(versioned[0] + 1);
  EXPECT_FALSE(decode_sample(sample, versioned.data(), versioned.size()).is_ok());
}

TEST_P(SectionCompactCorruption, BitFlipsAreRefusedOrDecodeToAValidPayload) {
  const Sample& sample = GetParam();
  const Bytes& raw = raw_of(sample);
  const Bytes compact = take(encode_sample(sample, raw.data(), raw.size()), "encode");
  size_t refused = 0;
  for (size_t bit = 0; bit < compact.size() * 8; ++bit) {
    Bytes flipped = compact;
    flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    Result<Bytes> r = decode_sample(sample, flipped.data(), flipped.size());
    if (!r.is_ok()) {
      ++refused;
      EXPECT_EQ(r.status().code(), static_cast<int>(ContainerError::kMalformedSection))
          << "bit " << bit << ": " << r.status().message();
      continue;
    }
    // Another valid payload: it must re-encode and decode to itself.
    Result<Bytes> again = encode_sample(sample, r.value().data(), r.value().size());
    ASSERT_TRUE(again.is_ok()) << "bit " << bit << ": " << again.status().message();
    Result<Bytes> back = decode_sample(sample, again.value().data(), again.value().size());
    ASSERT_TRUE(back.is_ok() && back.value() == r.value()) << "bit " << bit;
  }
  EXPECT_GT(refused, 0u);
}

TEST(SectionCompactCodecs, KeepRawPayloadsTheyCannotReproduceOrRead) {
  // One base vertex without faces, stored with a 1-bit run count where the
  // reference writer uses 0 bits: valid, but the codec cannot store the
  // width, so it refuses (lodbake-pack then keeps the section raw).
  Bytes wide(33, 0);
  wide[0] = 1;   // B
  wide[17] = 1;  // run count bits
  ASSERT_TRUE(decode_vtre(wide.data(), wide.size()).is_ok());
  Result<Bytes> compact = encode_section_compact(kVtreTag, wide.data(), wide.size());
  ASSERT_FALSE(compact.is_ok());
  EXPECT_EQ(compact.status().kind(), ErrorKind::kUnsupported);
  wide[17] = 0;
  EXPECT_TRUE(encode_section_compact(kVtreTag, wide.data(), wide.size()).is_ok());
  wide[19] = 1;  // reserved: malformed
  Result<Bytes> bad = encode_section_compact(kVtreTag, wide.data(), wide.size());
  ASSERT_FALSE(bad.is_ok());
  EXPECT_EQ(bad.status().kind(), ErrorKind::kInvalidInput);
}

// The container paths: a compact section decodes to its raw payload where
// it sits; its entry's decoded size must match (E021); a codec the kind
// does not define is E020; a codec against BASE without BASE is E024.
TEST(SectionCompactContainers, DecodeInPlaceAndRefuseWhatTheyCannot) {
  const TriangleMesh mesh = test_meshes::torus(8, 6);
  const Bytes base = take(encode_base(mesh, BaseEncodeOptions()), "BASE");
  const Bytes strp = strp_of(mesh);
  const Bytes strp_compact =
      take(encode_section_compact(kStrpTag, strp.data(), strp.size(), mesh), "compact STRP");
  const std::vector<Sample> all = samples();
  const Sample* torus_trees = nullptr;
  for (const Sample& sample : all) {
    if (sample.name == "VtreGreedyTorus") torus_trees = &sample;
  }
  ASSERT_NE(torus_trees, nullptr);
  const Bytes vtre = raw_of(*torus_trees);
  const Bytes vtre_compact =
      take(encode_section_compact(kVtreTag, vtre.data(), vtre.size()), "compact VTRE");
  auto decode = [](const Bytes& file, std::vector<Bytes>* storage, Container* out) {
    Result<Container> c = read_container(file.data(), file.size());
    EXPECT_TRUE(c.is_ok()) << c.status().message();
    if (!c.is_ok()) return c.status();
    *out = std::move(c).value();
    return decode_section_codecs(out, storage);
  };
  {
    ContainerWriter w;
    ASSERT_TRUE(w.add_section(kBaseTag, base, true).is_ok());
    ASSERT_TRUE(
        w.add_stored_section(kStrpTag, strp_compact, SectionCodec::kCompact, strp.size(), true)
            .is_ok());
    ASSERT_TRUE(
        w.add_stored_section(kVtreTag, vtre_compact, SectionCodec::kCompact, vtre.size(), false)
            .is_ok());
    const Bytes file = take(w.finish(), "container");
    std::vector<Bytes> storage;
    Container c;
    ASSERT_TRUE(decode(file, &storage, &c).is_ok());
    const Section* s = c.find(kStrpTag);
    const Section* t = c.find(kVtreTag);
    ASSERT_TRUE(s != nullptr && t != nullptr);
    EXPECT_EQ(Bytes(s->data, s->data + s->size), strp);
    EXPECT_EQ(Bytes(t->data, t->data + t->size), vtre);
    EXPECT_EQ(t->entry.stored_size, vtre_compact.size());
  }
  {
    ContainerWriter w;
    ASSERT_TRUE(
        w.add_stored_section(kVtreTag, vtre_compact, SectionCodec::kCompact, vtre.size() + 1, false)
            .is_ok());
    std::vector<Bytes> storage;
    Container c;
    EXPECT_EQ(decode(take(w.finish(), "container"), &storage, &c).code(), 21);
  }
  if (draco_codec_built()) {
    ContainerWriter w;
    ASSERT_TRUE(
        w.add_stored_section(kVtreTag, vtre_compact, SectionCodec::kDraco, vtre.size(), false)
            .is_ok());
    std::vector<Bytes> storage;
    Container c;
    const Status status = decode(take(w.finish(), "container"), &storage, &c);
    EXPECT_EQ(status.code(), 20);
    EXPECT_EQ(status.kind(), ErrorKind::kUnsupported);
  }
  {
    ContainerWriter w;
    ASSERT_TRUE(
        w.add_stored_section(kStrpTag, strp_compact, SectionCodec::kCompact, strp.size(), true)
            .is_ok());
    std::vector<Bytes> storage;
    Container c;
    EXPECT_EQ(decode(take(w.finish(), "container"), &storage, &c).code(), 24);
  }
}

std::string sample_name(const ::testing::TestParamInfo<Sample>& param) {
  return param.param.name;
}

std::vector<Sample> small_samples() {
  std::vector<Sample> all = samples(), small;
  for (Sample& sample : all) {
    if (sample.small) small.push_back(std::move(sample));
  }
  return small;
}

INSTANTIATE_TEST_SUITE_P(Kinds, SectionCompact, ::testing::ValuesIn(samples()), sample_name);
INSTANTIATE_TEST_SUITE_P(Kinds, SectionCompactCorruption, ::testing::ValuesIn(small_samples()),
                         sample_name);

}  // namespace
}  // namespace lodbake
