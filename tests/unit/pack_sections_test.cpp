// Packing every section kind (issue 7: "round trip of every section kind with
// and without Draco"). The containers lodbake-hierarchy (META, BASE, VHIE,
// RFIN, VSPL, DAGE, VTRE), lodbake-fan (META, BASE, FANH) and lodbake-strips
// (META, BASE, VSPL, SETS; --strips-only: META, BASE, STRP) write are built
// in memory from one shared mesh the way those tools build them, then packed
// through lib/pack compact, quantized to 14 bits and with Draco. After
// packing:
// - the sections pack does not recode are copied byte for byte (codec,
//   flags and sizes too) and decode to the same structure; those with a
//   compact codec of their own (VTRE, SETS, VHIE, RFIN; FANH and STRP
//   against BASE) are stored compact, smaller,
//   and decode to the same raw payload byte for byte;
// - BASE and VSPL keep every vertex, triangle and split id, with positions
//   within the stated quantization error (docs/format.md sections 11 and
//   22.2);
// - the checks of `lodbake-inspect --validate` (validate_sections) pass, and
//   each structure's own validator passes on what the packed file decodes to;
// - the copied structures still describe the packed progressive mesh: DAGE
//   and VTRE rebuilt from it are the stored ones (VTRE's copied float32
//   positions within the error of the packed ones), VHIE's own progressive
//   mesh has VSPL's splits, and SETS recovers the packed PM's triangles;
// - packing the packed file with the same options gives the same bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/compact_sections.h"
#include "formats/sections/dage.h"
#include "formats/sections/draco_codec.h"
#include "formats/sections/fanh.h"
#include "formats/sections/meta.h"
#include "formats/sections/rfin.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/section_validation.h"
#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vtre.h"
#include "formats/support/quantization.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/fanmerge/fan_build.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/pack/pack_containers.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "lib/strips/sets_build.h"
#include "lib/strips/sets_recovery.h"
#include "lib/strips/stripify.h"
#include "lib/validate/structure_validation.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

constexpr int kBits = 14;  // --quantize 14, and Draco's default qp

struct Written {
  const char* tag;
  Bytes bytes;
  bool required;
};

Bytes write_container(const char* tool, std::map<std::string, uint64_t> counts,
                      std::vector<Written> sections) {
  MetaSection meta = make_meta(tool);
  meta.input = MetaInput{"elephant.off", std::string(64, 'e'), 173779};
  meta.counts = std::move(counts);
  ContainerWriter writer;
  EXPECT_TRUE(writer.add_section(kMetaTag, take(encode_meta(meta), "META"), false).is_ok());
  for (Written& w : sections)
    EXPECT_TRUE(writer.add_section(w.tag, std::move(w.bytes), w.required).is_ok()) << w.tag;
  return take(writer.finish(), "container");
}

std::map<std::string, uint64_t> pm_counts(const ProgressiveMesh& pm) {
  return {{"vertices", pm.base.vertex_count()},
          {"triangles", pm.base.triangle_count()},
          {"splits", pm.splits.size()},
          {"full_vertices", pm.full_vertex_count()},
          {"full_triangles", full_triangle_count(pm.base.triangle_count(), pm.splits)}};
}

// lodbake-hierarchy's container (all of --sections vhie,dage,vtre).
Bytes hierarchy_container() {
  const TriangleMesh& mesh = bare_elephant();
  const BalancedHierarchy built =
      take(build_balanced_hierarchy(mesh, BalancedBuildOptions()), "hierarchy");
  const VertexHierarchy& h = built.hierarchy;
  const std::vector<NodeRefinement> refinement =
      take(compute_refinement_data(h, mesh), "refinement");
  const ProgressiveMesh pm = take(hierarchy_to_progressive_mesh(h), "hierarchy PM");
  const HierarchyShape shape = hierarchy_shape(h);
  std::map<std::string, uint64_t> counts = pm_counts(pm);
  counts["hierarchy_nodes"] = shape.nodes;
  counts["hierarchy_depth"] = shape.depth;
  counts["input_vertices"] = mesh.vertex_count();
  counts["input_triangles"] = mesh.triangle_count();
  std::vector<Written> sections;
  sections.push_back({kBaseTag, take(encode_base(h.base, BaseEncodeOptions()), "BASE"), true});
  sections.push_back({kVhieTag, take(encode_vhie(h), "VHIE"), true});
  sections.push_back({kRfinTag, take(encode_rfin(h, refinement), "RFIN"), false});
  sections.push_back({kVsplTag, take(encode_vspl(pm, VsplEncodeOptions()), "VSPL"), true});
  sections.push_back(
      {kDageTag, take(encode_dage(take(build_vsplit_dag(pm), "DAG")), "DAGE"), false});
  sections.push_back(
      {kVtreTag, take(encode_vtre(take(build_vertex_trees(pm), "trees")), "VTRE"), false});
  return write_container("lodbake-hierarchy", std::move(counts), std::move(sections));
}

// lodbake-fan's container.
Bytes fan_container() {
  const TriangleMesh& mesh = bare_elephant();
  const FanBuildResult built = take(build_fan_hierarchy(mesh, FanBuildOptions()), "fan");
  std::vector<Written> sections;
  sections.push_back({kBaseTag, take(encode_base(mesh, BaseEncodeOptions()), "BASE"), true});
  sections.push_back({kFanhTag, take(encode_fanh(built.hierarchy), "FANH"), true});
  return write_container("lodbake-fan",
                         {{"vertices", mesh.vertex_count()},
                          {"triangles", mesh.triangle_count()},
                          {"fan_internal_nodes", built.hierarchy.internal_count()}},
                         std::move(sections));
}

// lodbake-strips' container: the full PM with half placement, its fully
// refined mesh stripified and the SETS graph over the PM.
Bytes strips_container() {
  SimplifyOptions options;
  options.record_pm = true;
  options.placement = Placement::kHalf;
  SimplifyResult simplified = take(simplify(bare_elephant(), options), "simplify");
  EXPECT_TRUE(simplified.pm.has_value());
  if (!simplified.pm) return {};
  const ProgressiveMesh& pm = *simplified.pm;
  const TriangleMesh full = take(mesh_at_lod(pm, pm.full_vertex_count()), "full mesh");
  const TriangleStrips strips = take(stripify(full), "strips");
  std::vector<Written> sections;
  sections.push_back({kBaseTag, take(encode_base(pm.base, BaseEncodeOptions()), "BASE"), true});
  sections.push_back({kVsplTag, take(encode_vspl(pm, VsplEncodeOptions()), "VSPL"), true});
  sections.push_back(
      {kSetsTag, take(encode_sets(take(build_sets(strips, pm), "SETS")), "SETS"), true});
  return write_container("lodbake-strips", pm_counts(pm), std::move(sections));
}

// lodbake-strips --strips-only's container.
Bytes strips_only_container() {
  const TriangleMesh& mesh = bare_elephant();
  std::vector<Written> sections;
  sections.push_back({kBaseTag, take(encode_base(mesh, BaseEncodeOptions()), "BASE"), true});
  sections.push_back({kStrpTag, take(encode_strp(take(stripify(mesh), "strips")), "STRP"), true});
  return write_container("lodbake-strips",
                         {{"vertices", mesh.vertex_count()}, {"triangles", mesh.triangle_count()}},
                         std::move(sections));
}

enum class Baked { kHierarchy, kFan, kStrips, kStripsOnly };
enum class Variant { kCompact, kQuantized, kDraco };

const Bytes& baked(Baked kind) {
  static std::map<Baked, Bytes> cache;
  auto it = cache.find(kind);
  if (it != cache.end()) return it->second;
  Bytes file;
  switch (kind) {
    case Baked::kHierarchy:
      file = hierarchy_container();
      break;
    case Baked::kFan:
      file = fan_container();
      break;
    case Baked::kStrips:
      file = strips_container();
      break;
    case Baked::kStripsOnly:
      file = strips_only_container();
      break;
  }
  return cache.emplace(kind, std::move(file)).first->second;
}

RepackOptions options_of(Variant variant) {
  RepackOptions options;
  if (variant == Variant::kQuantized) options.quantize_bits = kBits;
  if (variant == Variant::kDraco) {
    options.draco = true;
    options.draco_options.quantization_bits = kBits;
  }
  return options;
}

Bytes repack_one(const Bytes& file, const RepackOptions& options) {
  Result<PackResult> packed =
      repack_containers({{"in.lbk", file}}, options, nlohmann::json::object(), nullptr);
  EXPECT_TRUE(packed.is_ok()) << packed.status().message();
  return packed.is_ok() ? std::move(packed).value().file : Bytes{};
}

// A file read twice: as stored (codecs as in the table) and decoded (every
// section its raw payload, as every tool reads it). Not movable: the
// sections point into `bytes` and `storage`.
struct Opened {
  explicit Opened(Bytes file) : bytes(std::move(file)) {
    stored = take(read_container(bytes.data(), bytes.size()), "container");
    decoded = take(read_container(bytes.data(), bytes.size()), "container");
    const Status codecs = decode_section_codecs(&decoded, &storage);
    EXPECT_TRUE(codecs.is_ok()) << codecs.message();
  }
  Opened(const Opened&) = delete;
  Opened& operator=(const Opened&) = delete;

  // The raw payload of `tag` (fails the test when there is none).
  std::pair<const uint8_t*, size_t> raw(const char* tag) const {
    const Section* s = decoded.find(tag);
    EXPECT_NE(s, nullptr) << tag;
    return s != nullptr ? std::make_pair(s->data, s->size) : std::make_pair(nullptr, size_t{0});
  }
  TriangleMesh base() const {
    auto [data, size] = raw(kBaseTag);
    return take(decode_base(data, size), "BASE");
  }
  ProgressiveMesh pm() const {
    auto [base_data, base_size] = raw(kBaseTag);
    auto [vspl_data, vspl_size] = raw(kVsplTag);
    return take(decode_progressive_mesh(base_data, base_size, vspl_data, vspl_size), "PM");
  }

  Bytes bytes;
  Container stored;
  Container decoded;
  std::vector<Bytes> storage;
};

Bytes stored_bytes(const Section& s) {
  return Bytes(s.data, s.data + s.size);
}

double max_distance(const std::vector<Vec3f>& a, const std::vector<Vec3f>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0;
  for (size_t v = 0; v < a.size() && v < b.size(); ++v) {
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::fabs(static_cast<double>(a[v][k]) - b[v][k]));
  }
  return worst;
}

std::vector<Vec3f> full_positions(const ProgressiveMesh& pm) {
  return take(mesh_at_lod(pm, pm.full_vertex_count()), "full mesh").positions;
}

// The stated error of BASE's positions after packing with `variant`:
// none (copied), section 11's bound for --quantize, one Draco step of the
// box's largest side for --draco (docs/format.md 22.2).
double base_error_bound(Variant variant, const std::vector<Vec3f>& positions) {
  Vec3f lo{}, hi{};
  bounding_box(positions, &lo, &hi);
  switch (variant) {
    case Variant::kCompact:
      return 0;
    case Variant::kQuantized:
      return quantization_error_bound(lo, hi, kBits);
    case Variant::kDraco:
      return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) / ((1 << kBits) - 1);
  }
  return 0;
}

// Topology and ids of two progressive meshes: every split's vs, vl, vr,
// error, the permutation to the input, the fully refined triangles.
void expect_same_ids(const ProgressiveMesh& a, const ProgressiveMesh& b) {
  ASSERT_EQ(a.splits.size(), b.splits.size());
  EXPECT_EQ(a.base.vertex_count(), b.base.vertex_count());
  EXPECT_EQ(a.base.triangles, b.base.triangles);
  for (size_t i = 0; i < a.splits.size(); ++i) {
    ASSERT_EQ(a.splits[i].vs, b.splits[i].vs) << i;
    ASSERT_EQ(a.splits[i].vl, b.splits[i].vl) << i;
    ASSERT_EQ(a.splits[i].vr, b.splits[i].vr) << i;
    ASSERT_EQ(a.splits[i].error, b.splits[i].error) << i;
  }
  EXPECT_EQ(a.input_vertex, b.input_vertex);
  EXPECT_EQ(take(mesh_at_lod(a, a.full_vertex_count()), "full a").triangles,
            take(mesh_at_lod(b, b.full_vertex_count()), "full b").triangles);
}

void expect_no_findings(const std::vector<std::string>& findings, const char* what) {
  for (const std::string& f : findings)
    ADD_FAILURE() << what << ": " << f;
}

class PackEverySection : public ::testing::TestWithParam<std::tuple<Baked, Variant>> {};

TEST_P(PackEverySection, KeepsIdsCopiesByteForByteValidatesAndIsIdempotent) {
  const auto [kind, variant] = GetParam();
  if (variant == Variant::kDraco && !draco_codec_built())
    GTEST_SKIP() << "built without the Draco codec";
  const RepackOptions options = options_of(variant);
  const Bytes& original = baked(kind);
  ASSERT_FALSE(original.empty());
  const Opened before(original);
  const Opened after(repack_one(original, options));
  ASSERT_FALSE(after.bytes.empty());

  // The checks lodbake-inspect --validate runs, on the written and the packed file.
  for (const SectionFinding& f : validate_container(before.decoded))
    ADD_FAILURE() << "as written: " << f.tag << ": " << f.message;
  for (const SectionFinding& f : validate_container(after.decoded))
    ADD_FAILURE() << "packed: " << f.tag << ": " << f.message;

  // The same sections in pack's order (META, BASE, VSPL, then the others
  // as written); those pack does not recode copied.
  std::vector<std::string> tags_expected = {kMetaTag, kBaseTag}, tags_after;
  if (before.stored.find(kVsplTag) != nullptr) tags_expected.push_back(kVsplTag);
  for (const Section& s : before.stored.sections) {
    if (s.tag() != kMetaTag && s.tag() != kBaseTag && s.tag() != kVsplTag)
      tags_expected.push_back(s.tag());
  }
  for (const Section& s : after.stored.sections)
    tags_after.push_back(s.tag());
  EXPECT_EQ(tags_after, tags_expected);
  for (const Section& s : before.stored.sections) {
    const Section* packed = after.stored.find(s.tag());
    ASSERT_NE(packed, nullptr) << s.tag();
    if (s.tag() == kMetaTag || s.tag() == kBaseTag || s.tag() == kVsplTag) continue;
    if (has_standalone_compact_codec(s.tag()) || has_base_compact_codec(s.tag())) {
      // Recoded compact: the raw payload every reader sees is the same bytes.
      EXPECT_EQ(packed->entry.codec, static_cast<uint16_t>(SectionCodec::kCompact)) << s.tag();
      EXPECT_LT(packed->entry.stored_size, s.entry.stored_size) << s.tag();
      auto [b_data, b_size] = before.raw(s.tag().c_str());
      auto [a_data, a_size] = after.raw(s.tag().c_str());
      // VTRE's copy of the base positions follows a recoded BASE (below).
      if (s.tag() != kVtreTag) {
        EXPECT_EQ(Bytes(a_data, a_data + a_size), Bytes(b_data, b_data + b_size)) << s.tag();
      }
      EXPECT_EQ(packed->entry.decoded_size, s.entry.decoded_size) << s.tag();
      // The inputs flag VHIE, VSPL, FANH, STRP and SETS required (as the
      // tools once did); pack writes the registry's flags.
      EXPECT_EQ(packed->required(), section_required(s.tag())) << s.tag();
      continue;
    }
    EXPECT_EQ(stored_bytes(*packed), stored_bytes(s)) << s.tag();
    EXPECT_EQ(packed->entry.codec, s.entry.codec) << s.tag();
    EXPECT_EQ(packed->entry.decoded_size, s.entry.decoded_size) << s.tag();
    EXPECT_EQ(packed->required(), section_required(s.tag())) << s.tag();
  }

  // META: pack's, with the input and the counts of the file it packed.
  {
    auto [b_data, b_size] = before.raw(kMetaTag);
    auto [a_data, a_size] = after.raw(kMetaTag);
    const MetaSection meta_before = take(decode_meta(b_data, b_size), "META");
    const MetaSection meta_after = take(decode_meta(a_data, a_size), "META");
    EXPECT_EQ(meta_after.tool, "lodbake-pack");
    EXPECT_EQ(meta_after.input, meta_before.input);
    EXPECT_EQ(meta_after.counts, meta_before.counts);
  }

  // BASE: same vertices and triangles, positions within the stated error.
  const TriangleMesh base_before = before.base();
  const TriangleMesh base_after = after.base();
  ASSERT_EQ(base_after.vertex_count(), base_before.vertex_count());
  EXPECT_EQ(base_after.triangles, base_before.triangles);
  EXPECT_EQ(base_after.normals, base_before.normals);
  EXPECT_EQ(base_after.texcoords, base_before.texcoords);
  const double base_bound = base_error_bound(variant, base_before.positions);
  EXPECT_LE(max_distance(base_after.positions, base_before.positions), base_bound);
  const Section* stored_base = after.stored.find(kBaseTag);
  ASSERT_NE(stored_base, nullptr);
  if (variant == Variant::kCompact) {
    EXPECT_EQ(stored_bytes(*stored_base), stored_bytes(*before.stored.find(kBaseTag)));
  }
  EXPECT_EQ(stored_base->entry.codec,
            static_cast<uint16_t>(variant == Variant::kDraco ? SectionCodec::kDraco
                                                             : SectionCodec::kRaw));

  // VSPL: compact and lossless, or quantized: same ids, positions within
  // BASE's error plus VSPL's quantization bound.
  ProgressiveMesh pm_before, pm_after;
  double full_bound = 0;
  if (before.decoded.find(kVsplTag) != nullptr) {
    pm_before = before.pm();
    pm_after = after.pm();
    EXPECT_EQ(after.stored.find(kVsplTag)->entry.codec,
              static_cast<uint16_t>(SectionCodec::kCompact));
    const std::vector<Vec3f> exact = full_positions(pm_before);
    if (variant == Variant::kCompact) {
      EXPECT_EQ(pm_after, pm_before);
    } else {
      expect_same_ids(pm_after, pm_before);
      Vec3f lo{}, hi{};
      bounding_box(exact, &lo, &hi);
      full_bound = base_bound + quantization_error_bound(lo, hi, kBits);
    }
    EXPECT_LE(max_distance(full_positions(pm_after), exact), full_bound);
  }

  // VHIE and RFIN: the same hierarchy over the packed BASE (roots, and the
  // left children at their parents' positions, moved with it), valid, whose
  // own progressive mesh has the packed VSPL's splits.
  if (before.decoded.find(kVhieTag) != nullptr) {
    auto [b_data, b_size] = before.raw(kVhieTag);
    auto [a_data, a_size] = after.raw(kVhieTag);
    const VertexHierarchy h_before = take(decode_vhie(b_data, b_size, base_before), "VHIE");
    const VertexHierarchy h_after = take(decode_vhie(a_data, a_size, base_after), "VHIE");
    expect_no_findings(validate_hierarchy(h_after), "VHIE");
    EXPECT_EQ(h_after.parent, h_before.parent);
    EXPECT_EQ(h_after.first_child, h_before.first_child);
    EXPECT_EQ(h_after.cut_left, h_before.cut_left);
    EXPECT_EQ(h_after.cut_right, h_before.cut_right);
    EXPECT_EQ(h_after.input_vertex, h_before.input_vertex);
    EXPECT_EQ(h_after.error, h_before.error);
    EXPECT_EQ(hierarchy_node_ids(h_after), hierarchy_node_ids(h_before));
    EXPECT_LE(max_distance(h_after.position, h_before.position), base_bound);
    if (!pm_after.splits.empty()) {
      expect_same_ids(take(hierarchy_to_progressive_mesh(h_after), "VHIE's PM"), pm_after);
    }
    auto [rb_data, rb_size] = before.raw(kRfinTag);
    auto [ra_data, ra_size] = after.raw(kRfinTag);
    const std::vector<NodeRefinement> r_before =
        take(decode_rfin(rb_data, rb_size, h_before), "RFIN");
    const std::vector<NodeRefinement> r_after =
        take(decode_rfin(ra_data, ra_size, h_after), "RFIN");
    ASSERT_EQ(r_after.size(), r_before.size());
    for (size_t i = 0; i < r_after.size(); ++i) {
      ASSERT_EQ(r_after[i].radius, r_before[i].radius) << i;
      ASSERT_EQ(r_after[i].cone_axis, r_before[i].cone_axis) << i;
      ASSERT_EQ(r_after[i].cone_half_angle, r_before[i].cone_half_angle) << i;
      ASSERT_EQ(r_after[i].mu2, r_before[i].mu2) << i;
      ASSERT_EQ(r_after[i].delta2, r_before[i].delta2) << i;
    }
  }

  // DAGE: the same DAG, valid, and the DAG of the packed progressive mesh.
  if (before.decoded.find(kDageTag) != nullptr) {
    auto [b_data, b_size] = before.raw(kDageTag);
    auto [a_data, a_size] = after.raw(kDageTag);
    const VsplitDag dag_after = take(decode_dage(a_data, a_size), "DAGE");
    EXPECT_EQ(dag_after, take(decode_dage(b_data, b_size), "DAGE"));
    expect_no_findings(validate_dage(dag_after), "DAGE");
    EXPECT_EQ(take(build_vsplit_dag(pm_after), "DAG of the packed PM"), dag_after);
  }

  // VTRE: the same trees, valid, their base positions those of the packed
  // BASE, and the trees of the packed progressive mesh but for their
  // float32 split positions, which are within its error.
  if (before.decoded.find(kVtreTag) != nullptr) {
    auto [b_data, b_size] = before.raw(kVtreTag);
    auto [a_data, a_size] = after.raw(kVtreTag);
    const VertexTrees trees_after = take(decode_vtre(a_data, a_size), "VTRE");
    VertexTrees expected = take(decode_vtre(b_data, b_size), "VTRE");
    ASSERT_EQ(pm_after.base.vertex_count(), expected.base_vertex_count);
    for (uint32_t v = 0; v < expected.base_vertex_count; ++v)
      expected.positions[v] = pm_after.base.positions[v];
    EXPECT_EQ(trees_after, expected);
    expect_no_findings(validate_vtre(trees_after), "VTRE");
    VertexTrees rebuilt = take(build_vertex_trees(pm_after), "trees of the packed PM");
    EXPECT_LE(max_distance(rebuilt.positions, trees_after.positions), full_bound);
    rebuilt.positions = trees_after.positions;
    EXPECT_TRUE(rebuilt == trees_after);
  }

  // FANH: the same forest and lists, which replay over the packed BASE.
  if (before.decoded.find(kFanhTag) != nullptr) {
    auto [b_data, b_size] = before.raw(kFanhTag);
    auto [a_data, a_size] = after.raw(kFanhTag);
    const FanHierarchy fan_after = take(decode_fanh(a_data, a_size), "FANH");
    const FanHierarchy fan_before = take(decode_fanh(b_data, b_size), "FANH");
    EXPECT_EQ(fan_after.vertex_count, fan_before.vertex_count);
    EXPECT_EQ(fan_after.triangle_count, fan_before.triangle_count);
    EXPECT_EQ(fan_after.child_start, fan_before.child_start);
    EXPECT_EQ(fan_after.children, fan_before.children);
    EXPECT_EQ(fan_after.error, fan_before.error);
    EXPECT_EQ(fan_after.removed_start, fan_before.removed_start);
    EXPECT_EQ(fan_after.removed, fan_before.removed);
    EXPECT_EQ(fan_after.modified_start, fan_before.modified_start);
    EXPECT_EQ(fan_after.modified, fan_before.modified);
    expect_no_findings(validate_fanh(fan_after, base_after), "FANH");
  }

  // STRP: the same strips, which describe the packed BASE's triangles.
  if (before.decoded.find(kStrpTag) != nullptr) {
    auto [b_data, b_size] = before.raw(kStrpTag);
    auto [a_data, a_size] = after.raw(kStrpTag);
    const TriangleStrips strips_after = take(decode_strp(a_data, a_size), "STRP");
    EXPECT_EQ(strips_after, take(decode_strp(b_data, b_size), "STRP"));
    expect_no_findings(validate_strp(strips_after, base_after), "STRP");
  }

  // SETS: the same graph, valid, over the packed progressive mesh: every
  // sampled LoD recovers that mesh's triangles with their orientation.
  if (before.decoded.find(kSetsTag) != nullptr) {
    auto [b_data, b_size] = before.raw(kSetsTag);
    auto [a_data, a_size] = after.raw(kSetsTag);
    const SetsGraph graph = take(decode_sets(a_data, a_size), "SETS");
    EXPECT_EQ(graph, take(decode_sets(b_data, b_size), "SETS"));
    expect_no_findings(validate_sets(graph), "SETS");
    ASSERT_EQ(graph.lod_count, pm_after.splits.size() + 1);
    ASSERT_EQ(graph.vertex_count, pm_after.full_vertex_count());
    Result<StripRecovery> recovery = StripRecovery::create(graph);
    Result<PmRefiner> refiner = PmRefiner::create(pm_after);
    ASSERT_TRUE(recovery.is_ok() && refiner.is_ok());
    const size_t full = pm_after.full_vertex_count();
    std::vector<uint32_t> lods;  // about 24 from the full mesh (0) to the base
    for (uint32_t lod = 0; lod + 1 < graph.lod_count; lod += 1 + graph.lod_count / 24)
      lods.push_back(lod);
    lods.push_back(graph.lod_count - 1);
    for (uint32_t lod : lods) {
      ASSERT_TRUE(recovery.value().recover(lod).is_ok()) << "LoD " << lod;
      ASSERT_TRUE(refiner.value().refine_to(full - lod).is_ok()) << "LoD " << lod;
      const std::vector<std::string> problems =
          check_recovered_triangles(recovery.value(), refiner.value().mesh().triangles);
      ASSERT_TRUE(problems.empty()) << "LoD " << lod << ": " << problems[0];
    }
  }

  // Idempotent: the packed file packed again with the same options.
  EXPECT_EQ(repack_one(after.bytes, options), after.bytes);
}

std::string variant_name(const ::testing::TestParamInfo<std::tuple<Baked, Variant>>& info) {
  static const char* kinds[] = {"Hierarchy", "Fan", "Strips", "StripsOnly"};
  static const char* variants[] = {"Compact", "Quantized14", "Draco"};
  return std::string(kinds[static_cast<int>(std::get<0>(info.param))]) +
         variants[static_cast<int>(std::get<1>(info.param))];
}

INSTANTIATE_TEST_SUITE_P(
    Containers, PackEverySection,
    ::testing::Combine(::testing::Values(Baked::kHierarchy, Baked::kFan, Baked::kStrips,
                                         Baked::kStripsOnly),
                       ::testing::Values(Variant::kCompact, Variant::kQuantized, Variant::kDraco)),
    variant_name);

}  // namespace
}  // namespace lodbake
