// Compact and Draco section codecs and container repacking (issue 7), on
// progressive meshes the QEM engine records from real meshes: the compact
// VSPL decodes to the raw payload byte for byte, Draco keeps every vertex
// and triangle id with positions within its quantization step, packing is
// deterministic and idempotent, merge / drop / keep follow the rules of
// lib/pack/pack_containers.h, and a reader without the Draco codec refuses
// with LBK-E020 (exit code 5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/mesh/split_connectivity.h"
#include "formats/sections/base.h"
#include "formats/sections/draco_codec.h"
#include "formats/sections/meta.h"
#include "formats/sections/open_container.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/section_validation.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vspl_compact.h"
#include "lib/pack/pack_containers.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

// An open height-field grid with per-vertex normals and texture coordinates.
TriangleMesh attributed_grid(int cells) {
  TriangleMesh mesh;
  mesh.normals = {AttributeBinding::kPerVertex, 3, {}, {}};
  mesh.texcoords = {AttributeBinding::kPerVertex, 2, {}, {}};
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const float u = static_cast<float>(i) / cells;
      const float v = static_cast<float>(j) / cells;
      mesh.positions.push_back({u, v, 0.1f * std::sin(6 * u) * std::cos(9 * v)});
      mesh.normals.values.insert(mesh.normals.values.end(), {0, 0, 1});
      mesh.texcoords.values.insert(mesh.texcoords.values.end(), {u, v});
    }
  }
  const auto id = [cells](int i, int j) { return static_cast<uint32_t>(j * (cells + 1) + i); };
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh;
}

// The engine's PM of `mesh` down to 8 triangles; per-corner attributes (which
// a PM cannot record) are left out.
ProgressiveMesh record_pm(TriangleMesh mesh, bool optimal = false) {
  for (MeshAttribute* attr : {&mesh.normals, &mesh.texcoords}) {
    if (attr->binding == AttributeBinding::kPerCorner) *attr = {};
  }
  SimplifyOptions options;
  options.target_triangles = 8;
  options.record_pm = true;
  if (optimal) options.placement = Placement::kOptimal;
  Result<SimplifyResult> result = simplify(mesh, options);  // NOLINT
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  if (!result.is_ok() || !result.value().pm) return {};
  return *result.value().pm;
}

// A container with META (input hash `sha`) + BASE + VSPL of `pm`.
Bytes pm_container(const ProgressiveMesh& pm, int quantize_bits = 0,
                   const std::string& sha = std::string(64, 'a')) {
  MetaSection meta = make_meta("lodbake-simplify");
  meta.input = MetaInput{"mesh.off", sha, 123};
  meta.counts = {{"splits", pm.splits.size()}};
  BaseEncodeOptions base_options;
  VsplEncodeOptions vspl_options;
  if (quantize_bits != 0) {
    base_options.quantize = vspl_options.quantize = true;
    base_options.bits = vspl_options.bits = quantize_bits;
  }
  ContainerWriter writer;
  EXPECT_TRUE(writer.add_section(kMetaTag, encode_meta(meta).value(), false).is_ok());
  EXPECT_TRUE(
      writer.add_section(kBaseTag, encode_base(pm.base, base_options).value(), true).is_ok());
  EXPECT_TRUE(writer.add_section(kVsplTag, encode_vspl(pm, vspl_options).value(), false).is_ok());
  return writer.finish().value();
}

// The progressive mesh a packed file holds, read the way every tool reads it.
ProgressiveMesh read_pm(const Bytes& file) {
  Result<Container> container = read_container(file.data(), file.size());
  EXPECT_TRUE(container.is_ok()) << container.status().message();
  if (!container.is_ok()) return {};
  std::vector<Bytes> storage;
  Status decoded = decode_section_codecs(&container.value(), &storage);
  EXPECT_TRUE(decoded.is_ok()) << decoded.message();
  EXPECT_TRUE(validate_sections(container.value()).empty());
  const Section* base = container.value().find(kBaseTag);
  const Section* vspl = container.value().find(kVsplTag);
  if (base == nullptr || vspl == nullptr) return {};
  Result<ProgressiveMesh> pm =
      decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size);
  EXPECT_TRUE(pm.is_ok()) << pm.status().message();
  return pm.is_ok() ? std::move(pm).value() : ProgressiveMesh{};
}

PackResult repack(const std::vector<Bytes>& files, const RepackOptions& options) {
  std::vector<PackInput> inputs;
  for (size_t i = 0; i < files.size(); ++i)
    inputs.push_back({"in" + std::to_string(i) + ".lbk", files[i]});
  Result<PackResult> result = repack_containers(inputs, options, nlohmann::json::object(), nullptr);
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  return result.is_ok() ? std::move(result).value() : PackResult{};
}

double max_position_error(const std::vector<Vec3f>& a, const std::vector<Vec3f>& b) {
  double worst = 0;
  for (size_t v = 0; v < a.size() && v < b.size(); ++v) {
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::fabs(static_cast<double>(a[v][k]) - b[v][k]));
  }
  return worst;
}

// Same ids: every split's vs, vl, vr and the permutation, and the fully
// refined meshes have identical triangle lists.
void expect_same_ids(const ProgressiveMesh& a, const ProgressiveMesh& b) {
  ASSERT_EQ(a.splits.size(), b.splits.size());
  ASSERT_EQ(a.base.triangles, b.base.triangles);
  for (size_t i = 0; i < a.splits.size(); ++i) {
    ASSERT_EQ(a.splits[i].vs, b.splits[i].vs) << i;
    ASSERT_EQ(a.splits[i].vl, b.splits[i].vl) << i;
    ASSERT_EQ(a.splits[i].vr, b.splits[i].vr) << i;
    ASSERT_EQ(a.splits[i].error, b.splits[i].error) << i;
  }
  EXPECT_EQ(a.input_vertex, b.input_vertex);
  Result<TriangleMesh> full_a = mesh_at_lod(a, a.full_vertex_count());
  Result<TriangleMesh> full_b = mesh_at_lod(b, b.full_vertex_count());
  ASSERT_TRUE(full_a.is_ok() && full_b.is_ok());
  EXPECT_EQ(full_a.value().triangles, full_b.value().triangles);
}

std::vector<Vec3f> full_positions(const ProgressiveMesh& pm) {
  Result<TriangleMesh> full = mesh_at_lod(pm, pm.full_vertex_count());
  EXPECT_TRUE(full.is_ok());
  return full.is_ok() ? full.value().positions : std::vector<Vec3f>{};
}

double extent(const std::vector<Vec3f>& positions) {
  Vec3f lo{}, hi{};
  bounding_box(positions, &lo, &hi);
  return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}

class CompactVspl : public ::testing::TestWithParam<int> {};

// Compact coding is lossless: the raw payload comes back byte for byte, for
// float32 and quantized positions, half and optimal placement (stored vs
// positions), attributes and boundary splits, in every layout version (1
// and 2 still read and written on request). Encoding is deterministic, and
// re-encoding what was decoded gives the same bytes.
TEST_P(CompactVspl, DecodesToTheRawPayloadByteForByte) {
  const int bits = GetParam();
  std::vector<ProgressiveMesh> pms = {record_pm(load_clean_mesh("cgal_elephant-with-holes.off")),
                                      record_pm(load_clean_mesh("c3d_spot.obj"), true),
                                      record_pm(attributed_grid(12))};
  for (const ProgressiveMesh& pm : pms) {
    ASSERT_FALSE(pm.splits.empty());
    VsplEncodeOptions options;
    options.quantize = bits != 0;
    options.bits = bits == 0 ? 16 : bits;
    Bytes raw = encode_vspl(pm, options).value();
    for (uint8_t version : {1, 2, 3, 4}) {
      VsplCompactOptions compact_options;
      compact_options.version = version;
      Result<Bytes> compact = encode_vspl_compact(raw.data(), raw.size(), pm.base, compact_options);
      ASSERT_TRUE(compact.is_ok()) << compact.status().message();
      EXPECT_EQ(compact.value()[0], version);
      // Given the caller's own decoding of the payload, the same bytes.
      const VsplSection decoded = decode_vspl(raw.data(), raw.size(), pm.base.positions).value();
      VsplCompactOptions given = compact_options;
      given.decoded = &decoded;
      EXPECT_EQ(encode_vspl_compact(raw.data(), raw.size(), pm.base, given).value(),
                compact.value());
      Result<Bytes> back =
          decode_vspl_compact(compact.value().data(), compact.value().size(), pm.base);
      ASSERT_TRUE(back.is_ok()) << back.status().message();
      EXPECT_EQ(back.value(), raw);
      EXPECT_LT(compact.value().size(), raw.size());
      EXPECT_EQ(
          encode_vspl_compact(back.value().data(), back.value().size(), pm.base, compact_options)
              .value(),
          compact.value());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bits, CompactVspl, ::testing::Values(0, 8, 14, 30));

// Version 3 (the default) on a real mesh: ids identical, positions within the stated
// quantization, and the codec's own connectivity replay ends with exactly
// the triangles of lib/simplify's replay (so every wing was found in its fan).
TEST(CompactVsplVersion3, RealMeshKeepsIdsAndPositionsAndFindsEveryWing) {
  const ProgressiveMesh pm = record_pm(load_clean_mesh("cgal_elephant-with-holes.off"));
  ASSERT_FALSE(pm.splits.empty());
  VsplEncodeOptions options;
  options.quantize = true;
  options.bits = 14;
  const Bytes raw = encode_vspl(pm, options).value();
  VsplCompactStats stats;
  VsplCompactOptions compact_options;
  compact_options.stats = &stats;
  const Bytes compact =
      encode_vspl_compact(raw.data(), raw.size(), pm.base, compact_options).value();
  const Bytes back = decode_vspl_compact(compact.data(), compact.size(), pm.base).value();
  const VsplSection section = decode_vspl(back.data(), back.size(), pm.base.positions).value();
  ASSERT_EQ(section.splits.size(), pm.splits.size());
  Vec3f lo{}, hi{};
  std::vector<Vec3f> vt_positions;
  for (const VertexSplit& s : pm.splits)
    vt_positions.push_back(s.vt_position);
  bounding_box(vt_positions, &lo, &hi);
  const double step = extent(vt_positions) / ((1u << 14) - 1);
  for (size_t i = 0; i < pm.splits.size(); ++i) {
    EXPECT_EQ(section.splits[i].vs, pm.splits[i].vs);
    EXPECT_EQ(section.splits[i].vl, pm.splits[i].vl);
    EXPECT_EQ(section.splits[i].vr, pm.splits[i].vr);
    for (int a = 0; a < 3; ++a)
      EXPECT_LE(std::fabs(section.splits[i].vt_position[a] - pm.splits[i].vt_position[a]), step);
  }
  EXPECT_EQ(section.input_vertex, pm.input_vertex);
  // A wing outside its fan would cost an escape of ~log2(n) = 11 bits.
  EXPECT_LT(stats.wing_bits / static_cast<double>(pm.splits.size()), 8.0);
  EXPECT_GT(stats.vs_bits, 0);
  EXPECT_GT(stats.position_bits, 0);
  EXPECT_GT(stats.error_bits, 0);

  Result<PmRefiner> refiner = PmRefiner::create(pm);
  ASSERT_TRUE(refiner.is_ok());
  ASSERT_TRUE(refiner.value().refine_to(pm.full_vertex_count()).is_ok());
  SplitConnectivity replay(static_cast<uint32_t>(pm.base.vertex_count()), pm.base.triangles);
  for (const VertexSplit& s : pm.splits)
    replay.split(s.vs, s.vl, s.vr);
  EXPECT_EQ(replay.triangles(), refiner.value().mesh().triangles);
}

// Every truncation and flipped bits fail cleanly (ASan and UBSan check the
// decoder's reads) or decode to something else, in every version.
TEST(CompactVsplHostile, TruncatedAndFlippedPayloads) {
  const ProgressiveMesh pm = record_pm(attributed_grid(5));
  VsplEncodeOptions options;
  options.quantize = true;
  options.bits = 12;
  Bytes raw = encode_vspl(pm, options).value();
  // Version 4 with errors rounded to 6 bits, so that its shift is not 0.
  const Bytes rounded = round_vspl_errors(raw.data(), raw.size(), 6).value();
  for (uint8_t version : {1, 2, 3, 4}) {
    if (version == 4) raw = rounded;
    VsplCompactOptions compact_options;
    compact_options.version = version;
    Bytes compact = encode_vspl_compact(raw.data(), raw.size(), pm.base, compact_options).value();
    if (version == 4) {
      ASSERT_GT(compact[1 + kVsplFixedBytes + 24], 0);  // the shift, after the box
    }
    for (size_t n = 0; n < compact.size(); ++n) {
      Result<Bytes> cut = decode_vspl_compact(compact.data(), n, pm.base);
      EXPECT_FALSE(cut.is_ok()) << n;
    }
    Bytes longer = compact;
    longer.push_back(0);
    EXPECT_FALSE(decode_vspl_compact(longer.data(), longer.size(), pm.base).is_ok());
    for (size_t i = 1; i < compact.size(); ++i) {
      for (int bit = 0; bit < 8; ++bit) {
        if (version == 1 && bit != 4) continue;
        Bytes flipped = compact;
        flipped[i] ^= static_cast<uint8_t>(1u << bit);
        Result<Bytes> decoded = decode_vspl_compact(flipped.data(), flipped.size(), pm.base);
        if (decoded.is_ok()) {
          EXPECT_NE(decoded.value(), raw) << i;
        }
      }
    }
  }
  Bytes wrong_version = encode_vspl_compact(raw.data(), raw.size(), pm.base).value();
  wrong_version[0] = 5;
  Result<Bytes> refused = decode_vspl_compact(wrong_version.data(), wrong_version.size(), pm.base);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_NE(refused.status().message().find("layout version 5 is unknown"), std::string::npos);
}

// Hostile records that the format accepts but that do not fit the mesh
// (wings that are not vs's neighbours, splits of a vertex without faces)
// are escapes: they still code and decode exactly.
TEST(CompactVsplHostile, RecordsThatDoNotFitTheMeshStillRoundTrip) {
  ProgressiveMesh pm = record_pm(attributed_grid(6));
  ASSERT_GT(pm.splits.size(), 4u);
  std::swap(pm.splits[1].vl, pm.splits[3].vr);
  for (VertexSplit& s : pm.splits) {
    if (s.vl == s.vr || s.vl == s.vs || s.vr == s.vs) s.vr = kNoVertex;
    if (s.vl == kNoVertex && s.vr == kNoVertex) s.vl = s.vs == 0 ? 1 : 0;
  }
  pm.splits[2].vs = 0;
  pm.splits[2].vl = 1;
  pm.splits[2].vr = 2;
  for (bool quantize : {false, true}) {
    VsplEncodeOptions options;
    options.quantize = quantize;
    const Result<Bytes> raw = encode_vspl(pm, options);
    ASSERT_TRUE(raw.is_ok()) << raw.status().message();
    for (uint8_t version : {2, 3, 4}) {
      VsplCompactOptions compact_options;
      compact_options.version = version;
      const Bytes compact =
          encode_vspl_compact(raw.value().data(), raw.value().size(), pm.base, compact_options)
              .value();
      EXPECT_EQ(decode_vspl_compact(compact.data(), compact.size(), pm.base).value(), raw.value());
    }
  }
}

// By default the writer keeps the smaller layout: version 1 for a tiny PM,
// whose adaptive models have no time to learn, version 3 for a real mesh.
TEST(CompactVspl, DefaultKeepsTheSmallerLayout) {
  for (const ProgressiveMesh& pm : {record_pm(attributed_grid(3)),
                                    record_pm(load_clean_mesh("cgal_elephant-with-holes.off"))}) {
    VsplEncodeOptions options;
    options.quantize = true;
    options.bits = 14;
    const Bytes raw = encode_vspl(pm, options).value();
    size_t sizes[4] = {};
    for (uint8_t version : {0, 1, 2, 3}) {
      VsplCompactOptions compact_options;
      compact_options.version = version;
      sizes[version] =
          encode_vspl_compact(raw.data(), raw.size(), pm.base, compact_options).value().size();
    }
    EXPECT_EQ(sizes[0], std::min(sizes[1], sizes[3]));
    // Version 3's class and weight models pay off on a real mesh.
    if (pm.splits.size() > 1000) {
      EXPECT_LT(sizes[3], sizes[2]);
    }
  }
}

// Errors rounded up to fewer significant bits (lodbake-pack --error-bits):
// nothing else in the payload changes, every error stays a bound within a
// relative 2^(1 - bits), rounding again changes nothing, and the default
// writer then takes version 4, which leaves the errors' zero low bits out.
TEST(CompactVsplVersion4, RoundedErrorsCostFewerBitsAndDecodeExactly) {
  const ProgressiveMesh pm = record_pm(load_clean_mesh("cgal_elephant-with-holes.off"));
  VsplEncodeOptions options;
  options.quantize = true;
  options.bits = 14;
  const Bytes raw = encode_vspl(pm, options).value();
  const VsplParts parts = locate_vspl_parts(raw.data(), raw.size()).value();
  size_t v3_size = 0;
  double v3_error_bits = 0;
  for (int bits : {24, 12, 8, 1}) {
    const Bytes rounded = round_vspl_errors(raw.data(), raw.size(), bits).value();
    EXPECT_EQ(round_vspl_errors(rounded.data(), rounded.size(), bits).value(), rounded);
    // Only the error range and the errors differ.
    const size_t errors_end = parts.errors_offset + 4 * pm.splits.size();
    EXPECT_TRUE(std::equal(raw.begin() + kVsplErrorRangeOffset + 8,
                           raw.begin() + static_cast<std::ptrdiff_t>(parts.errors_offset),
                           rounded.begin() + kVsplErrorRangeOffset + 8));
    EXPECT_TRUE(std::equal(raw.begin() + static_cast<std::ptrdiff_t>(errors_end), raw.end(),
                           rounded.begin() + static_cast<std::ptrdiff_t>(errors_end)));
    const VsplSection section =
        decode_vspl(rounded.data(), rounded.size(), pm.base.positions).value();
    for (size_t i = 0; i < pm.splits.size(); ++i) {
      const float exact = pm.splits[i].error;
      const float e = section.splits[i].error;
      EXPECT_GE(e, exact);
      EXPECT_LE(e - exact, std::ldexp(std::fabs(exact), 1 - bits)) << i;
    }
    VsplCompactStats stats;
    VsplCompactOptions compact_options;
    compact_options.stats = &stats;
    const Bytes compact =
        encode_vspl_compact(rounded.data(), rounded.size(), pm.base, compact_options).value();
    EXPECT_EQ(compact[0], bits == 24 ? 3 : 4);
    EXPECT_EQ(decode_vspl_compact(compact.data(), compact.size(), pm.base).value(), rounded);
    if (bits == 24) {
      v3_size = compact.size();
      v3_error_bits = stats.error_bits;
    } else {
      EXPECT_LT(compact.size(), v3_size);
      EXPECT_LT(stats.error_bits, v3_error_bits / 2);
    }
  }
  EXPECT_FALSE(round_vspl_errors(raw.data(), raw.size(), 0).is_ok());
  EXPECT_FALSE(round_vspl_errors(raw.data(), raw.size(), 25).is_ok());
}

// A version-4 payload whose shift is not the errors' largest is refused:
// version 3's stream of rounded errors behind a shift of 0 decodes to the
// same raw payload as the canonical version 4.
TEST(CompactVsplVersion4, RefusesAShiftSmallerThanTheErrorsAllow) {
  const ProgressiveMesh pm = record_pm(attributed_grid(8));
  VsplEncodeOptions options;
  options.quantize = false;
  const Bytes raw = encode_vspl(pm, options).value();
  const Bytes rounded = round_vspl_errors(raw.data(), raw.size(), 4).value();
  VsplCompactOptions v3;
  v3.version = 3;
  Bytes forged = encode_vspl_compact(rounded.data(), rounded.size(), pm.base, v3).value();
  forged[0] = 4;
  forged.insert(forged.begin() + 1 + kVsplFixedBytes, uint8_t{0});
  Result<Bytes> refused = decode_vspl_compact(forged.data(), forged.size(), pm.base);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_NE(refused.status().message().find("error shift 0 is not the errors' largest"),
            std::string::npos)
      << refused.status().message();
  forged[1 + kVsplFixedBytes] = 32;
  refused = decode_vspl_compact(forged.data(), forged.size(), pm.base);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_NE(refused.status().message().find("error shift 32 outside 0..31"), std::string::npos);
}

TEST(DracoBase, KeepsVertexAndTriangleIdsWithinTheQuantizationStep) {
  if (!draco_codec_built()) GTEST_SKIP() << "built without the Draco codec";
  for (const TriangleMesh& mesh : {load_clean_mesh("c3d_spot.obj"), attributed_grid(9)}) {
    TriangleMesh per_vertex = mesh;
    if (per_vertex.texcoords.binding == AttributeBinding::kPerCorner) per_vertex.texcoords = {};
    if (per_vertex.normals.binding == AttributeBinding::kPerCorner) per_vertex.normals = {};
    for (int qp : {11, 14}) {
      DracoOptions options;
      options.quantization_bits = qp;
      Result<Bytes> stored = encode_base_draco(per_vertex, options);
      ASSERT_TRUE(stored.is_ok()) << stored.status().message();
      Result<TriangleMesh> back = decode_base_draco(stored.value().data(), stored.value().size());
      ASSERT_TRUE(back.is_ok()) << back.status().message();
      EXPECT_EQ(back.value().triangles, per_vertex.triangles);
      ASSERT_EQ(back.value().vertex_count(), per_vertex.vertex_count());
      const double step = extent(per_vertex.positions) / ((1 << qp) - 1);
      EXPECT_LE(max_position_error(back.value().positions, per_vertex.positions), step);
      EXPECT_EQ(back.value().normals, per_vertex.normals);
      EXPECT_EQ(back.value().texcoords, per_vertex.texcoords);
    }
  }
}

TEST(DracoBase, RefusesPerCornerAttributesAndForeignBitstreams) {
  if (!draco_codec_built()) GTEST_SKIP() << "built without the Draco codec";
  TriangleMesh mesh = attributed_grid(2);
  mesh.texcoords.binding = AttributeBinding::kPerCorner;
  mesh.texcoords.corners.assign(mesh.triangles.size(), Triangle{0, 0, 0});
  Result<Bytes> refused = encode_base_draco(mesh, DracoOptions{});
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kUnsupported);
  const Bytes not_draco = {kDracoBaseVersion, 14, 7, 'D', 'R', 'A', 'C', 'O', 1, 0, 1, 0};
  Result<TriangleMesh> bad = decode_base_draco(not_draco.data(), not_draco.size());
  ASSERT_FALSE(bad.is_ok());
  EXPECT_NE(bad.status().message().find("section BASE: draco: bitstream version 1.0"),
            std::string::npos);
}

// Past about 22 bits Draco 1.5.5's encoder doubles its memory with each bit
// (4.2 GB for the bunny's base mesh at 30; fuzz_draco_base re-encoding a
// payload that named 30): encoding stops at 24, reading still takes the
// 30 bits that earlier versions of lodbake-pack could write.
TEST(DracoBase, EncodesUpTo24BitsAndReadsPayloadsNamingUpTo30) {
  if (!draco_codec_built()) GTEST_SKIP() << "built without the Draco codec";
  const TriangleMesh mesh = attributed_grid(3);
  DracoOptions options;
  options.quantization_bits = kMaxDracoQuantizationBits;
  Result<Bytes> stored = encode_base_draco(mesh, options);
  ASSERT_TRUE(stored.is_ok()) << stored.status().message();
  Result<DracoOptions> read = read_draco_base_options(stored.value().data(), stored.value().size());
  ASSERT_TRUE(read.is_ok());
  EXPECT_EQ(read.value().quantization_bits, 24);
  options.quantization_bits = 25;
  Result<Bytes> refused = encode_base_draco(mesh, options);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(refused.status().message(), "Draco quantization takes 1 to 24 bits, not 25");
  const Bytes named_30 = {kDracoBaseVersion, 30, 7};
  Result<DracoOptions> old = read_draco_base_options(named_30.data(), named_30.size());
  ASSERT_TRUE(old.is_ok()) << old.status().message();
  EXPECT_EQ(old.value().quantization_bits, 30);
  const Bytes named_31 = {kDracoBaseVersion, 31, 7};
  EXPECT_FALSE(read_draco_base_options(named_31.data(), named_31.size()).is_ok());
}

// Draco quantizes over the float extent max - min; an axis from -2e38 to
// 2e38 overflows it and Draco 1.5.5's encoder then crashed (fuzz_draco_base).
TEST(DracoBase, RefusesPositionsWhoseExtentOverflowsFloat) {
  if (!draco_codec_built()) GTEST_SKIP() << "built without the Draco codec";
  TriangleMesh mesh;
  mesh.positions = {Vec3f{0, 0, -2e38f}, Vec3f{1, 0, 2e38f}, Vec3f{0, 1, 0}};
  mesh.triangles = {Triangle{0, 1, 2}};
  Result<Bytes> refused = encode_base_draco(mesh, DracoOptions{});
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kUnsupported);
  EXPECT_EQ(refused.status().message(),
            "the Draco codec cannot quantize positions spanning -2e+38 to 2e+38 on axis 2 "
            "(beyond float)");
  mesh.positions[2][0] = std::numeric_limits<float>::quiet_NaN();
  refused = encode_base_draco(mesh, DracoOptions{});
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().message(), "the Draco codec takes finite positions only");
}

// Round trip of a whole container, compact and with Draco: same ids, the
// positions within the stated quantization, validation passes.
TEST(Repack, RoundTripKeepsIdsAndPositionsWithinQuantization) {
  const ProgressiveMesh pm = record_pm(load_clean_mesh("cgal_elephant-with-holes.off"));
  const Bytes original = pm_container(pm);
  const std::vector<Vec3f> exact = full_positions(pm);

  RepackOptions compact;
  PackResult lossless = repack({original}, compact);
  ProgressiveMesh same = read_pm(lossless.file);
  EXPECT_EQ(same, pm);  // float32 + compact: exact
  EXPECT_LT(lossless.file.size(), original.size());

  RepackOptions quantized;
  quantized.quantize_bits = 14;
  ProgressiveMesh q = read_pm(repack({original}, quantized).file);
  expect_same_ids(q, pm);
  Vec3f lo{}, hi{};
  bounding_box(exact, &lo, &hi);
  EXPECT_LE(max_position_error(full_positions(q), exact), quantization_error_bound(lo, hi, 14));

  // Errors rounded up to 8 significant bits: the same PM but for the
  // errors, each within a relative 2^-7 above its exact value.
  RepackOptions rounded = quantized;
  rounded.error_bits = 8;
  const PackResult packed_rounded = repack({original}, rounded);
  ProgressiveMesh r = read_pm(packed_rounded.file);
  ASSERT_EQ(r.splits.size(), q.splits.size());
  for (size_t i = 0; i < r.splits.size(); ++i) {
    EXPECT_GE(r.splits[i].error, q.splits[i].error);
    EXPECT_LE(r.splits[i].error - q.splits[i].error, std::ldexp(q.splits[i].error, -7));
    r.splits[i].error = q.splits[i].error;
  }
  EXPECT_EQ(r, q);
  EXPECT_LT(packed_rounded.file.size(), repack({original}, quantized).file.size());

  if (draco_codec_built()) {
    RepackOptions draco;
    draco.draco = true;
    PackResult packed = repack({original}, draco);
    ProgressiveMesh d = read_pm(packed.file);
    expect_same_ids(d, pm);
    // Draco's step on BASE (its own box) and VSPL's on the split vertices.
    const double bound =
        extent(pm.base.positions) / ((1 << 14) - 1) + quantization_error_bound(lo, hi, 14);
    EXPECT_LE(max_position_error(full_positions(d), exact), bound);
    Result<Container> c = read_container(packed.file.data(), packed.file.size());
    ASSERT_TRUE(c.is_ok());
    EXPECT_EQ(c.value().find(kBaseTag)->entry.codec, static_cast<uint16_t>(SectionCodec::kDraco));
    EXPECT_EQ(c.value().find(kVsplTag)->entry.codec, static_cast<uint16_t>(SectionCodec::kCompact));
  }
}

TEST(Repack, PackingAPackedFileGivesTheSameBytes) {
  const ProgressiveMesh pm = record_pm(load_clean_mesh("c3d_spot.obj"), true);
  const Bytes original = pm_container(pm);
  std::vector<RepackOptions> variants(6);
  variants[1].quantize_bits = 12;
  variants[2].compact = false;
  variants[3].draco = draco_codec_built();
  variants[3].draco_options.compression_level = 10;
  variants[4].error_bits = 8;
  variants[5].quantize_bits = 14;
  variants[5].error_bits = 5;
  for (const RepackOptions& options : variants) {
    const Bytes once = repack({original}, options).file;
    const Bytes twice = repack({once}, options).file;
    EXPECT_EQ(once, twice);
    EXPECT_EQ(repack({original}, options).file, once);  // deterministic
  }
}

TEST(Repack, MergesFilesOfOneInputAndCopiesUnknownSectionsByteForByte) {
  const ProgressiveMesh pm = record_pm(attributed_grid(8));
  const Bytes pm_file = pm_container(pm, 16);
  // A second file of the same input with BASE and a section pack does not know.
  const Bytes unknown_payload = {1, 2, 3, 4, 5};
  ContainerWriter writer;
  MetaSection meta = make_meta("lodbake-hierarchy");
  meta.input = MetaInput{"mesh.off", std::string(64, 'a'), 123};
  meta.counts = {{"nodes", 7}};
  ASSERT_TRUE(writer.add_section(kMetaTag, encode_meta(meta).value(), false).is_ok());
  BaseEncodeOptions q16;
  q16.quantize = true;
  ASSERT_TRUE(writer.add_section(kBaseTag, encode_base(pm.base, q16).value(), true).is_ok());
  ASSERT_TRUE(writer.add_section("xTRA", unknown_payload, false).is_ok());
  const Bytes other = writer.finish().value();

  PackResult merged = repack({pm_file, other}, RepackOptions{});
  Result<Container> c = read_container(merged.file.data(), merged.file.size());
  ASSERT_TRUE(c.is_ok()) << c.status().message();
  std::vector<std::string> tags;
  for (const Section& s : c.value().sections)
    tags.push_back(s.tag());
  EXPECT_EQ(tags, (std::vector<std::string>{"META", "BASE", "VSPL", "xTRA"}));
  const Section* extra = c.value().find("xTRA");
  EXPECT_EQ(Bytes(extra->data, extra->data + extra->size), unknown_payload);
  EXPECT_FALSE(extra->required());
  Result<MetaSection> out_meta =
      decode_meta(c.value().find(kMetaTag)->data, c.value().find(kMetaTag)->size);
  ASSERT_TRUE(out_meta.is_ok());
  EXPECT_EQ(out_meta.value().tool, "lodbake-pack");
  EXPECT_EQ(out_meta.value().counts.at("nodes"), 7u);
  EXPECT_EQ(out_meta.value().counts.at("splits"), pm.splits.size());
  EXPECT_EQ(out_meta.value().extra.at("sources").size(), 2u);
  EXPECT_EQ(read_pm(merged.file).splits.size(), pm.splits.size());

  RepackOptions keep;
  keep.keep = {"BASE"};
  PackResult only_base = repack({merged.file}, keep);
  Result<Container> k = read_container(only_base.file.data(), only_base.file.size());
  ASSERT_TRUE(k.is_ok());
  EXPECT_EQ(k.value().sections.size(), 2u);  // META and BASE
  EXPECT_EQ(k.value().find(kVsplTag), nullptr);
  EXPECT_TRUE(validate_sections(k.value()).empty());  // counts of VSPL left out with it
  RepackOptions drop;
  drop.drop = {"xTRA", "META"};
  PackResult dropped = repack({merged.file}, drop);
  Result<Container> d = read_container(dropped.file.data(), dropped.file.size());
  ASSERT_TRUE(d.is_ok());
  EXPECT_EQ(d.value().find("xTRA"), nullptr);
  EXPECT_EQ(d.value().find(kMetaTag), nullptr);
  EXPECT_NE(d.value().find(kVsplTag), nullptr);
}

TEST(Repack, RefusesOtherInputsConflictsAndVsplWithoutBase) {
  const ProgressiveMesh pm = record_pm(attributed_grid(6));
  const Bytes a = pm_container(pm);
  const Bytes b = pm_container(pm, 0, std::string(64, 'b'));
  std::vector<PackInput> inputs = {{"a.lbk", a}, {"b.lbk", b}};
  size_t failed = 9;
  Result<PackResult> other = repack_containers(inputs, RepackOptions{}, {}, &failed);
  ASSERT_FALSE(other.is_ok());
  EXPECT_EQ(failed, 1u);
  EXPECT_NE(other.status().message().find("was baked from another input"), std::string::npos);

  // Same input, another BASE: a group of its own (format 1.1), which a
  // consumer finds by its sections and which validates.
  inputs[1] = {"c.lbk", pm_container(pm, 12)};
  Result<PackResult> grouped = repack_containers(inputs, RepackOptions{}, {}, &failed);
  ASSERT_TRUE(grouped.is_ok()) << grouped.status().message();
  const Bytes& file = grouped.value().file;
  Result<OpenedContainer> opened = open_container(file);
  ASSERT_TRUE(opened.is_ok()) << opened.status().message();
  EXPECT_EQ(opened.value().header().minor, 1);
  ASSERT_EQ(opened.value().group_count(), 2u);
  for (uint32_t g = 0; g < 2; ++g) {
    EXPECT_NE(opened.value().find(kBaseTag, g), nullptr);
    EXPECT_NE(opened.value().find(kVsplTag, g), nullptr);
  }
  EXPECT_EQ(opened.value().find(kMetaTag, 1), nullptr);
  EXPECT_TRUE(validate_sections(opened.value().decoded()).empty());
  // Packing the result again changes nothing.
  EXPECT_EQ(repack({file}, RepackOptions{}).file, file);

  RepackOptions drop_base;
  drop_base.drop = {"BASE"};
  Result<PackResult> orphan = repack_containers({{"a.lbk", a}}, drop_base, {}, nullptr);
  ASSERT_FALSE(orphan.is_ok());
  EXPECT_EQ(orphan.status().kind(), ErrorKind::kInvalidInput);
}

// A reader without the Draco codec refuses a Draco section with LBK-E020,
// kind unsupported (the tools' exit code 5); with it back, the file reads.
TEST(Repack, ReaderWithoutDracoRefusesWithUnsupported) {
  if (!draco_codec_built()) GTEST_SKIP() << "built without the Draco codec";
  RepackOptions draco;
  draco.draco = true;
  const Bytes file = repack({pm_container(record_pm(attributed_grid(6)))}, draco).file;
  set_codec_disabled_for_testing(SectionCodec::kDraco, true);
  Result<Container> refused = read_container(file.data(), file.size());
  set_codec_disabled_for_testing(SectionCodec::kDraco, false);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kUnsupported);
  EXPECT_EQ(refused.status().code(), 20);
  EXPECT_NE(refused.status().message().find("codec 2 (draco), which this build cannot decode"),
            std::string::npos);
  EXPECT_TRUE(read_container(file.data(), file.size()).is_ok());
}

// The container-level rules of docs/format.md section 22: a codec a kind
// does not define is E020, a decoded size other than the entry's is E021, a
// compact VSPL without its BASE is E024.
TEST(SectionCodecs, UndefinedCodecWrongDecodedSizeAndMissingBase) {
  const ProgressiveMesh pm = record_pm(attributed_grid(4));
  const Bytes meta = encode_meta(make_meta("test")).value();
  const Bytes base = encode_base(pm.base, BaseEncodeOptions{}).value();
  const Bytes raw_vspl = encode_vspl(pm, VsplEncodeOptions{}).value();
  const Bytes compact = encode_vspl_compact(raw_vspl.data(), raw_vspl.size(), pm.base).value();
  auto decode = [](const Bytes& file) {
    Result<Container> c = read_container(file.data(), file.size());
    EXPECT_TRUE(c.is_ok()) << c.status().message();
    std::vector<Bytes> storage;
    return c.is_ok() ? decode_section_codecs(&c.value(), &storage) : c.status();
  };
  {
    ContainerWriter w;
    ASSERT_TRUE(
        w.add_stored_section(kMetaTag, meta, SectionCodec::kCompact, meta.size(), false).is_ok());
    Status s = decode(w.finish().value());
    EXPECT_EQ(s.code(), 20);
    EXPECT_EQ(s.kind(), ErrorKind::kUnsupported);
    EXPECT_NE(s.message().find("not defined for this section kind"), std::string::npos);
  }
  {
    ContainerWriter w;
    ASSERT_TRUE(w.add_section(kBaseTag, base, true).is_ok());
    ASSERT_TRUE(
        w.add_stored_section(kVsplTag, compact, SectionCodec::kCompact, raw_vspl.size() + 1, false)
            .is_ok());
    Status s = decode(w.finish().value());
    EXPECT_EQ(s.code(), 21);
    EXPECT_NE(s.message().find("section VSPL decodes to"), std::string::npos);
  }
  {
    ContainerWriter w;
    ASSERT_TRUE(
        w.add_stored_section(kVsplTag, compact, SectionCodec::kCompact, raw_vspl.size(), false)
            .is_ok());
    EXPECT_EQ(decode(w.finish().value()).code(), 24);
  }
  {
    ContainerWriter w;
    ASSERT_TRUE(w.add_section(kBaseTag, base, true).is_ok());
    ASSERT_TRUE(
        w.add_stored_section(kVsplTag, compact, SectionCodec::kCompact, raw_vspl.size(), false)
            .is_ok());
    Bytes file = w.finish().value();
    Result<Container> c = read_container(file.data(), file.size());
    ASSERT_TRUE(c.is_ok());
    std::vector<Bytes> storage;
    ASSERT_TRUE(decode_section_codecs(&c.value(), &storage).is_ok());
    const Section* vspl = c.value().find(kVsplTag);
    EXPECT_EQ(Bytes(vspl->data, vspl->data + vspl->size), raw_vspl);
    EXPECT_EQ(vspl->entry.stored_size, compact.size());  // the entry keeps what was stored
  }
  ContainerWriter w;
  EXPECT_FALSE(
      w.add_stored_section(kBaseTag, base, SectionCodec::kRaw, base.size() + 1, true).is_ok());
}

// Two progressive meshes of one input over different BASEs merge into two
// groups; packed compact, each group's VSPL decodes against its own BASE,
// and consumers find groups by the sections they need.
TEST(Repack, GroupsDecodeEachAgainstItsOwnBase) {
  const ProgressiveMesh pm = record_pm(attributed_grid(6));
  const Bytes merged = repack({pm_container(pm), pm_container(pm, 12)}, RepackOptions{}).file;
  Result<OpenedContainer> opened = open_container(merged);
  ASSERT_TRUE(opened.is_ok()) << opened.status().message();
  const OpenedContainer& file = opened.value();
  ASSERT_EQ(file.group_count(), 2u);
  for (uint32_t g = 0; g < 2; ++g) {
    const Section* vspl = file.find(kVsplTag, g);
    ASSERT_NE(vspl, nullptr);
    EXPECT_EQ(file.stored_of(*vspl).entry.codec, static_cast<uint16_t>(SectionCodec::kCompact));
    const Section* base = file.find(kBaseTag, g);
    Result<ProgressiveMesh> decoded =
        decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size);
    ASSERT_TRUE(decoded.is_ok()) << decoded.status().message();
    EXPECT_EQ(decoded.value().splits.size(), pm.splits.size());
    // Group 1 holds the 12-bit copy: its positions moved, group 0's did not.
    const double moved = max_position_error(decoded.value().base.positions, pm.base.positions);
    if (g == 0) {
      EXPECT_EQ(moved, 0.0);
    } else {
      EXPECT_GT(moved, 0.0);
    }
  }
  EXPECT_EQ(file.group_with({kBaseTag, kVsplTag}, "mode x", "tool y").value(), 0u);
  Result<uint32_t> missing = file.group_with({kBaseTag, kSetsTag}, "mode sets", "lodbake-strips");
  ASSERT_FALSE(missing.is_ok());
  EXPECT_EQ(missing.status().message(),
            "LBK-E024: the container has no SETS section; mode sets needs BASE + SETS "
            "(lodbake-strips)");

  // BASE in group 0 and VSPL in group 1: both present, never together.
  ContainerWriter writer;
  ASSERT_TRUE(writer.add_section(kBaseTag, encode_base(pm.base, {}).value(), true).is_ok());
  ASSERT_TRUE(writer.add_section(kVsplTag, encode_vspl(pm, {}).value(), false, 1).is_ok());
  const Bytes split = writer.finish().value();
  Result<OpenedContainer> split_open = open_container(split);
  ASSERT_TRUE(split_open.is_ok()) << split_open.status().message();
  Result<uint32_t> none = split_open.value().group_with({kBaseTag, kVsplTag}, "mode dag", "z");
  ASSERT_FALSE(none.is_ok());
  EXPECT_EQ(none.status().message(),
            "LBK-E024: no group of the container holds BASE + VSPL together over one base "
            "mesh; mode dag needs BASE + VSPL (z)");
}

}  // namespace
}  // namespace lodbake
