// VSPL section: exact float32 round trips (half and optimal placement,
// identity and stored permutations, boundary splits missing either wing,
// per-vertex normals and texture coordinates, no splits), quantized
// positions within the documented bound, the exact byte layout (both
// examples of docs/format.md), encoder refusals, hostile payloads that fail
// fast with LBK-E023, truncation and bit flips, BASE/VSPL attribute
// mismatches, and the container-level cross-checks against BASE and META.
// The progressive meshes are built by hand: the format does not need the
// engine, only records whose indices are valid at their step.
#include "formats/sections/vspl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/sections/section_validation.h"
#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

// A tetrahedron recorded as a PM: the base is a double-sided triangle
// (0, 1, 2) / (0, 2, 1); splitting vertex 0 with wings 1 and 2 brings back
// the apex, vertex 3.
ProgressiveMesh tetrahedron_pm() {
  ProgressiveMesh pm;
  pm.base.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  pm.base.triangles = {{0, 1, 2}, {0, 2, 1}};
  VertexSplit split;
  split.vs = 0;
  split.vl = 1;
  split.vr = 2;
  split.vt_position = {0, 0, 1};
  split.vs_position = {0, 0, 0};
  split.error = 0.5f;
  pm.splits = {split};
  pm.input_vertex = {0, 1, 2, 3};
  return pm;
}

// An open quad: base triangle (0, 1, 2); a boundary split of vertex 0 (no
// right wing) adds vertex 3 and one triangle.
ProgressiveMesh open_quad_pm() {
  ProgressiveMesh pm;
  pm.base.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  pm.base.triangles = {{0, 1, 2}};
  VertexSplit split;
  split.vs = 0;
  split.vl = 2;
  split.vr = kNoVertex;
  split.vt_position = {0, 1, 0};
  split.vs_position = {0, 0, 0};
  split.error = 0.25f;
  pm.splits = {split};
  pm.input_vertex = {0, 1, 2, 3};
  return pm;
}

// The open quad of docs/format.md's second VSPL example: a boundary split
// without a left wing, with per-vertex normals and texture coordinates.
ProgressiveMesh open_quad_with_attributes_pm() {
  ProgressiveMesh pm;
  pm.base.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  pm.base.triangles = {{0, 1, 2}};
  VertexSplit split;
  split.vs = 0;
  split.vl = kNoVertex;
  split.vr = 2;
  split.vt_position = {0, 1, 0};
  split.vs_position = {0, 0, 0};
  split.error = 0.25f;
  pm.splits = {split};
  pm.input_vertex = {0, 1, 2, 3};
  pm.normals = {AttributeBinding::kPerVertex, 3, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, {}};
  pm.texcoords = {AttributeBinding::kPerVertex, 2, {0, 0, 1, 0, 1, 1, 0, 1}, {}};
  pm.base.normals = {AttributeBinding::kPerVertex, 3, {0, 0, 1, 0, 0, 1, 0, 0, 1}, {}};
  pm.base.texcoords = {AttributeBinding::kPerVertex, 2, {0, 0, 1, 0, 1, 1}, {}};
  return pm;
}

// Gives `pm` random per-vertex normals (and texture coordinates), the base
// holding the first ones, as lib/simplify records them.
void add_attributes(ProgressiveMesh* pm, bool normals, bool texcoords, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  const size_t full = pm->full_vertex_count();
  const size_t n0 = pm->base.vertex_count();
  for (auto [attr, base_attr, components, wanted] :
       {std::make_tuple(&pm->normals, &pm->base.normals, 3u, normals),
        std::make_tuple(&pm->texcoords, &pm->base.texcoords, 2u, texcoords)}) {
    if (!wanted) continue;
    *attr = MeshAttribute{AttributeBinding::kPerVertex, components, {}, {}};
    for (size_t k = 0; k < full * components; ++k)
      attr->values.push_back(k % 11 == 4 ? -0.0f : value(rng));
    *base_attr = *attr;
    base_attr->values.resize(n0 * components);
  }
}

// Random records with valid indices at every step. `optimal` moves vs at
// every split; `permuted` shuffles input_vertex; boundary splits appear
// with probability 1/4, half of them without the left wing and half
// without the right one.
ProgressiveMesh random_pm(uint32_t base_vertices, uint32_t splits, uint32_t seed, bool optimal,
                          bool permuted) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-100.0f, 100.0f);
  std::uniform_real_distribution<float> cost(0.0f, 3.0f);
  ProgressiveMesh pm;
  for (uint32_t i = 0; i < base_vertices; ++i)
    pm.base.positions.push_back({coord(rng), coord(rng) * 1e-3f, coord(rng) + 500.0f});
  std::vector<Vec3f> current = pm.base.positions;
  for (uint32_t i = 0; i < splits; ++i) {
    const uint32_t n = base_vertices + i;
    VertexSplit s;
    s.vs = static_cast<uint32_t>(rng() % n);
    do {
      s.vl = static_cast<uint32_t>(rng() % n);
    } while (s.vl == s.vs);
    s.vr = kNoVertex;
    if (n >= 3 && rng() % 4 != 0) {
      do {
        s.vr = static_cast<uint32_t>(rng() % n);
      } while (s.vr == s.vs || s.vr == s.vl);
    } else if (rng() % 2 == 0) {
      std::swap(s.vl, s.vr);
    }
    s.vt_position = {coord(rng), coord(rng), coord(rng)};
    s.vs_position = optimal ? Vec3f{coord(rng), coord(rng), coord(rng)} : current[s.vs];
    s.error = i % 7 == 3 ? -0.0f : cost(rng);
    current[s.vs] = s.vs_position;
    current.push_back(s.vt_position);
    pm.splits.push_back(s);
  }
  pm.input_vertex.resize(base_vertices + splits);
  for (uint32_t v = 0; v < pm.input_vertex.size(); ++v)
    pm.input_vertex[v] = v;
  if (permuted) std::shuffle(pm.input_vertex.begin(), pm.input_vertex.end(), rng);
  return pm;
}

Result<VsplSection> decode_copy(const Bytes& payload, const std::vector<Vec3f>& base_positions,
                                VsplSummary* summary = nullptr) {
  Bytes copy(payload);
  copy.shrink_to_fit();
  return decode_vspl(copy.empty() ? nullptr : copy.data(), copy.size(), base_positions, summary);
}

ProgressiveMesh round_trip(const ProgressiveMesh& pm, const VsplEncodeOptions& options,
                           VsplSummary* summary = nullptr) {
  Result<Bytes> bytes = encode_vspl(pm, options);
  EXPECT_TRUE(bytes.is_ok()) << bytes.status().message();
  if (!bytes.is_ok()) return {};
  Result<VsplSection> back = decode_copy(bytes.value(), pm.base.positions, summary);
  EXPECT_TRUE(back.is_ok()) << back.status().message();
  if (!back.is_ok()) return {};
  Result<ProgressiveMesh> joined = join_progressive_mesh(pm.base, std::move(back).value());
  EXPECT_TRUE(joined.is_ok()) << joined.status().message();
  if (!joined.is_ok()) return {};
  return std::move(joined).value();
}

// Rounding errors to fewer significant bits (lodbake-pack --error-bits):
// up, never down, to the next value with that many bits; values that fit
// and non-finite ones unchanged; 24 bits is float32 itself.
TEST(RoundUpToSignificantBits, RoundsTowardsPlusInfinityAndKeepsWhatFits) {
  EXPECT_EQ(round_up_to_significant_bits(1.0f, 1), 1.0f);
  EXPECT_EQ(round_up_to_significant_bits(1.5f, 2), 1.5f);
  EXPECT_EQ(round_up_to_significant_bits(1.25f, 2), 1.5f);
  EXPECT_EQ(round_up_to_significant_bits(1.75f, 2), 2.0f);  // carries into the exponent
  EXPECT_EQ(round_up_to_significant_bits(1.005f, 8), 1.0f + 1.0f / 128);
  EXPECT_EQ(round_up_to_significant_bits(-1.25f, 2), -1.0f);  // towards +infinity
  EXPECT_EQ(round_up_to_significant_bits(0.0f, 4), 0.0f);
  const float max = std::numeric_limits<float>::max();
  EXPECT_EQ(round_up_to_significant_bits(max, 8), max);  // would overflow: kept
  EXPECT_TRUE(std::isinf(round_up_to_significant_bits(INFINITY, 8)));
  EXPECT_TRUE(std::isnan(round_up_to_significant_bits(NAN, 8)));
  const float tiny = std::numeric_limits<float>::denorm_min() * 3;
  // A subnormal's pattern rounds like any other: up to the smallest normal.
  EXPECT_EQ(round_up_to_significant_bits(tiny, 1), std::numeric_limits<float>::min());
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(0.0f, 1000.0f);
  for (int i = 0; i < 2000; ++i) {
    const float x = value(random);
    const int bits = 1 + i % 24;
    const float r = round_up_to_significant_bits(x, bits);
    EXPECT_GE(r, x);
    EXPECT_LE(r - x, std::ldexp(x, 1 - bits));
    EXPECT_EQ(round_up_to_significant_bits(r, bits), r);
    EXPECT_EQ(float_bits(r) & ((1u << (24 - bits)) - 1), 0u);
    if (bits == 24) {
      EXPECT_EQ(r, x);
    }
  }
}

TEST(VsplSection, Float32RoundTripIsExact) {
  VsplSummary summary;
  const ProgressiveMesh tetra = tetrahedron_pm();
  EXPECT_EQ(round_trip(tetra, {}, &summary), tetra);
  EXPECT_EQ(summary.flags, 0);

  ProgressiveMesh permuted = tetrahedron_pm();
  permuted.input_vertex = {2, 0, 3, 1};
  EXPECT_EQ(round_trip(permuted, {}, &summary), permuted);
  EXPECT_EQ(summary.flags, kVsplStoresPermutation);

  ProgressiveMesh moved = tetrahedron_pm();
  moved.splits[0].vs_position = {-0.0f, 1e-38f, -3e38f};
  EXPECT_EQ(round_trip(moved, {}, &summary), moved);
  EXPECT_EQ(summary.flags, kVsplStoresVsPositions);

  // Half placement over many splits: vs positions come from the base mesh
  // and earlier records.
  const ProgressiveMesh half = random_pm(50, 3000, 1, false, true);
  EXPECT_EQ(round_trip(half, {}, &summary), half);
  EXPECT_EQ(summary.flags, kVsplStoresPermutation);
  const ProgressiveMesh optimal = random_pm(2, 5000, 2, true, false);
  EXPECT_EQ(round_trip(optimal, {}, &summary), optimal);
  EXPECT_EQ(summary.flags, kVsplStoresVsPositions);
  EXPECT_EQ(summary.split_count, 5000u);
  EXPECT_EQ(summary.base_vertex_count, 2u);
}

TEST(VsplSection, BoundarySplits) {
  const ProgressiveMesh quad = open_quad_pm();
  EXPECT_EQ(round_trip(quad, {}), quad);
  ProgressiveMesh mirrored = open_quad_pm();
  std::swap(mirrored.splits[0].vl, mirrored.splits[0].vr);
  EXPECT_EQ(round_trip(mirrored, {}), mirrored);
  EXPECT_EQ(round_trip(mirrored, {true, 8}).splits[0].vl, kNoVertex);
  // n = 4 vertices before the split: vs takes 2 bits, each wing bits(5) = 3
  // and the value 4 says "no such wing".
  ProgressiveMesh pm = random_pm(4, 0, 3, false, false);
  VertexSplit s;
  s.vs = 3;
  s.vl = 0;
  s.vr = kNoVertex;
  s.vt_position = {1, 2, 3};
  s.vs_position = pm.base.positions[3];
  pm.splits.push_back(s);
  pm.input_vertex.push_back(4);
  const Bytes bytes = encode_vspl(pm, {}).value();
  EXPECT_EQ(bytes[kVsplFixedBytes], 3 | 0 << 2 | 4 << 5);
  EXPECT_EQ(round_trip(pm, {}), pm);
  std::swap(pm.splits[0].vl, pm.splits[0].vr);
  EXPECT_EQ(encode_vspl(pm, {}).value()[kVsplFixedBytes], 3 | 4 << 2 | 0 << 5);
  EXPECT_EQ(round_trip(pm, {}), pm);
  EXPECT_EQ(full_triangle_count(10, pm.splits), 11u);
  EXPECT_EQ(full_triangle_count(2, tetrahedron_pm().splits), 4u);
  EXPECT_EQ(full_triangle_count(1, open_quad_with_attributes_pm().splits), 2u);
}

TEST(VsplSection, AttributesRoundTrip) {
  for (auto [normals, texcoords] : {std::pair{true, false}, {false, true}, {true, true}}) {
    ProgressiveMesh pm = random_pm(30, 500, 31, false, true);
    add_attributes(&pm, normals, texcoords, 7);
    VsplSummary summary;
    EXPECT_EQ(round_trip(pm, {}, &summary), pm);
    EXPECT_EQ(summary.flags, kVsplStoresPermutation | (normals ? kVsplStoresNormals : 0) |
                                 (texcoords ? kVsplStoresTexcoords : 0));
    // Quantized positions leave the attributes exact.
    const ProgressiveMesh quantized = round_trip(pm, {true, 6});
    EXPECT_EQ(quantized.normals, pm.normals);
    EXPECT_EQ(quantized.texcoords, pm.texcoords);
    EXPECT_NE(quantized.splits, pm.splits);
  }
  // With no splits the flag still says the PM carries the attribute.
  ProgressiveMesh empty = random_pm(4, 0, 2, false, false);
  add_attributes(&empty, true, false, 1);
  VsplSummary summary;
  EXPECT_EQ(round_trip(empty, {}, &summary), empty);
  EXPECT_EQ(summary.flags, kVsplStoresNormals);
  EXPECT_EQ(encode_vspl(empty, {}).value().size(), kVsplFixedBytes);
}

TEST(VsplSection, BoundaryAndAttributesExampleOfTheSpec) {
  const ProgressiveMesh pm = open_quad_with_attributes_pm();
  const Bytes b = encode_vspl(pm, {}).value();
  // docs/format.md, "Example with a boundary split and attributes".
  EXPECT_EQ(b, (Bytes{0x01, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x00,
                      0x00, 0x80, 0x3e, 0x00, 0x00, 0x80, 0x3e, 0x2c, 0x00, 0x00, 0x00, 0x00,
                      0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3e,
                      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f,
                      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f}));
  const Bytes base = encode_base(pm.base, {}).value();
  Result<ProgressiveMesh> back =
      decode_progressive_mesh(base.data(), base.size(), b.data(), b.size());
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(back.value(), pm);
}

TEST(VsplSection, BaseAndVsplAttributesMustAgree) {
  const ProgressiveMesh pm = open_quad_with_attributes_pm();
  const Bytes vspl = encode_vspl(pm, {}).value();
  auto joined = [&](const TriangleMesh& base) {
    return decode_progressive_mesh(encode_base(base, {}).value().data(),
                                   encode_base(base, {}).value().size(), vspl.data(), vspl.size());
  };
  TriangleMesh base = pm.base;
  base.normals = MeshAttribute();
  Result<ProgressiveMesh> r = joined(base);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(),
            "LBK-E023: section VSPL: VSPL stores the split vertices' normals but BASE has none for "
            "its vertices");
  base = pm.base;
  base.texcoords = {AttributeBinding::kPerCorner, 2, {0, 0, 1, 0, 1, 1}, {{0, 1, 2}}};
  r = joined(base);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().code(), 23);
  EXPECT_EQ(r.status().message(),
            "LBK-E023: section VSPL: VSPL stores the split vertices' texture coordinates but "
            "BASE's are per corner, a progressive mesh needs them per vertex");
  // BASE has normals, the VSPL of a PM without them does not.
  ProgressiveMesh plain = tetrahedron_pm();
  const Bytes plain_vspl = encode_vspl(plain, {}).value();
  plain.base.normals = {AttributeBinding::kPerVertex, 3, std::vector<float>(9, 0.5f), {}};
  const Bytes normals_base = encode_base(plain.base, {}).value();
  r = decode_progressive_mesh(normals_base.data(), normals_base.size(), plain_vspl.data(),
                              plain_vspl.size());
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(),
            "LBK-E023: section VSPL: BASE has normals but VSPL does not store those of the split "
            "vertices");
  // join_progressive_mesh() checks what it is given, too.
  VsplSection section = decode_copy(vspl, pm.base.positions).value();
  section.split_normals.pop_back();
  EXPECT_EQ(join_progressive_mesh(pm.base, section).status().code(), 23);
  section = decode_copy(vspl, pm.base.positions).value();
  EXPECT_EQ(
      join_progressive_mesh(random_pm(4, 0, 1, false, false).base, section).status().message(),
      "LBK-E023: section VSPL: base vertex count 3, but the base mesh has 4 vertices");
  TriangleMesh wrong_components = pm.base;
  wrong_components.normals.components = 2;
  wrong_components.normals.values.resize(6);
  EXPECT_EQ(join_progressive_mesh(wrong_components, section).status().message(),
            "LBK-E023: section VSPL: BASE's normals have 2 components and 6 floats, expected 3 "
            "for each of 3 vertices");
  EXPECT_TRUE(join_progressive_mesh(pm.base, section).is_ok());
}

TEST(VsplSection, NoSplits) {
  for (uint32_t base : {0u, 1u, 2u, 7u}) {
    ProgressiveMesh pm = random_pm(base, 0, 4, false, false);
    VsplSummary summary;
    EXPECT_EQ(round_trip(pm, {}, &summary), pm) << base;
    EXPECT_EQ(summary.split_count, 0u);
    EXPECT_EQ(summary.base_vertex_count, base);
    EXPECT_EQ(summary.min_error, 0.0f);
    EXPECT_EQ(summary.max_error, 0.0f);
    EXPECT_EQ(encode_vspl(pm, {}).value().size(), kVsplFixedBytes);
    EXPECT_EQ(encode_vspl(pm, {true, 12}).value().size(), kVsplFixedBytes + 24);
    EXPECT_EQ(round_trip(pm, {true, 12}), pm);
  }
  // A permutation of the base vertices alone.
  ProgressiveMesh pm = random_pm(7, 0, 4, false, true);
  pm.input_vertex = {6, 5, 4, 3, 2, 1, 0};
  const Bytes bytes = encode_vspl(pm, {}).value();
  EXPECT_EQ(bytes.size(), kVsplFixedBytes + 3);  // 7 values of 3 bits
  EXPECT_EQ(round_trip(pm, {}), pm);
}

TEST(VsplSection, ExactLayout) {
  ProgressiveMesh pm = tetrahedron_pm();
  pm.input_vertex = {2, 0, 3, 1};
  const Bytes b = encode_vspl(pm, {}).value();
  // 19 fixed + 1 topology byte (2 + 2 + 2 bits) + 12 position + 4 error +
  // 1 permutation byte (4 x 2 bits).
  ASSERT_EQ(b.size(), 37u);
  ByteReader reader(b.data(), b.size());
  uint32_t r = 0, base = 0;
  uint8_t encoding = 9, qbits = 9, flags = 9;
  float lo = 0, hi = 0;
  ASSERT_TRUE(reader.read(&r) && reader.read(&base) && reader.read(&encoding) &&
              reader.read(&qbits) && reader.read(&flags) && reader.read(&lo) && reader.read(&hi));
  EXPECT_EQ(r, 1u);
  EXPECT_EQ(base, 3u);
  EXPECT_EQ(encoding, 0);
  EXPECT_EQ(qbits, 0);
  EXPECT_EQ(flags, kVsplStoresPermutation);
  EXPECT_EQ(lo, 0.5f);
  EXPECT_EQ(hi, 0.5f);
  EXPECT_EQ(b[19], 0x24u);  // vs 0, vl 1, vr 2 at 2 bits, LSB first
  float z = 0;
  std::memcpy(&z, b.data() + 28, 4);
  EXPECT_EQ(z, 1.0f);  // vt's z
  float error = 0;
  std::memcpy(&error, b.data() + 32, 4);
  EXPECT_EQ(error, 0.5f);
  EXPECT_EQ(b[36], 2 | 0 << 2 | 3 << 4 | 1 << 6);
  // docs/format.md's first example, byte for byte.
  EXPECT_EQ(b, (Bytes{0x01, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00,
                      0x00, 0x3f, 0x00, 0x00, 0x00, 0x3f, 0x24, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
                      0x00, 0x00, 0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x3f, 0x72}));

  // Boundary split: vr is written as n = 3.
  const Bytes q = encode_vspl(open_quad_pm(), {}).value();
  ASSERT_EQ(q.size(), 36u);
  EXPECT_EQ(q[19], 0 | 2 << 2 | 3 << 4);

  // Quantized to 4 bits: box (0,0,1)..(0,0,1), all three coordinates 0.
  const Bytes c = encode_vspl(tetrahedron_pm(), {true, 4}).value();
  ASSERT_EQ(c.size(), 19u + 24 + 1 + 2 + 4);
  EXPECT_EQ(c[8], 1);
  EXPECT_EQ(c[9], 4);
  std::memcpy(&z, c.data() + 19 + 8, 4);
  EXPECT_EQ(z, 1.0f);  // box_min.z
  EXPECT_EQ(c[44], 0);
  EXPECT_EQ(c[45], 0);
}

TEST(VsplSection, QuantizationStaysWithinTheDocumentedBound) {
  for (bool optimal : {false, true}) {
    const ProgressiveMesh pm = random_pm(20, 2000, 5, optimal, true);
    for (int bits : {1, 3, 8, 11, 16, 24, 30}) {
      VsplSummary summary;
      const Bytes bytes = encode_vspl(pm, {true, bits}).value();
      Result<VsplSection> back = decode_copy(bytes, pm.base.positions, &summary);
      ASSERT_TRUE(back.is_ok()) << back.status().message();
      EXPECT_EQ(summary.quantization_bits, bits);
      const double bound = quantization_error_bound(summary.box_min, summary.box_max, bits);
      std::vector<Vec3f> current = pm.base.positions;
      for (size_t i = 0; i < pm.splits.size(); ++i) {
        const VertexSplit& want = pm.splits[i];
        const VertexSplit& got = back.value().splits[i];
        ASSERT_EQ(got.vs, want.vs);
        ASSERT_EQ(got.vl, want.vl);
        ASSERT_EQ(got.vr, want.vr);
        ASSERT_EQ(got.error, want.error);
        for (int a = 0; a < 3; ++a) {
          ASSERT_LE(std::fabs(static_cast<double>(got.vt_position[a]) - want.vt_position[a]), bound)
              << "bits " << bits << " split " << i;
          ASSERT_LE(std::fabs(static_cast<double>(got.vs_position[a]) - want.vs_position[a]), bound)
              << "bits " << bits << " split " << i;
        }
        // Without stored vs positions, vs keeps its decoded position.
        if (!optimal) {
          ASSERT_EQ(got.vs_position, current[got.vs]);
        }
        current[got.vs] = got.vs_position;
        current.push_back(got.vt_position);
      }
      EXPECT_EQ(back.value().input_vertex, pm.input_vertex);
    }
  }
}

TEST(VsplSection, SizeIsTheDocumentedFormula) {
  // 40 base vertices, 70000 splits: index widths grow from 6 to 17 bits.
  const ProgressiveMesh pm = random_pm(40, 70000, 23, false, true);
  uint64_t topology_bits = 0;
  for (uint64_t n = 40; n < 40 + 70000; ++n)
    topology_bits += bits_for_count(n) + 2 * bits_for_count(n + 1);
  const uint64_t full = 70040;
  const uint64_t permutation = (full * bits_for_count(full) + 7) / 8;
  const Bytes float32 = encode_vspl(pm, {}).value();
  EXPECT_EQ(float32.size(), 19 + (topology_bits + 7) / 8 + 70000 * (12 + 4) + permutation);
  const Bytes quantized = encode_vspl(pm, {true, 16}).value();
  EXPECT_EQ(quantized.size(), 19 + 24 + (topology_bits + 7) / 8 + 70000 * (6 + 4) + permutation);
  Result<VsplSummary> summary = read_vspl_summary(quantized.data(), quantized.size());
  ASSERT_TRUE(summary.is_ok());
  EXPECT_EQ(summary.value().split_count, 70000u);
  // Normals and texture coordinates stay float32: 12 + 8 bytes per split.
  ProgressiveMesh with_attributes = pm;
  add_attributes(&with_attributes, true, true, 3);
  EXPECT_EQ(encode_vspl(with_attributes, {true, 16}).value().size(),
            quantized.size() + 70000 * (12 + 8));
  add_attributes(&with_attributes, false, true, 3);
  with_attributes.normals = MeshAttribute();
  with_attributes.base.normals = MeshAttribute();
  EXPECT_EQ(encode_vspl(with_attributes, {}).value().size(), float32.size() + 70000 * 8);
}

TEST(VsplSection, DeterministicAndIdempotent) {
  const ProgressiveMesh pm = random_pm(30, 700, 9, true, true);
  EXPECT_EQ(encode_vspl(pm, {}).value(), encode_vspl(pm, {}).value());
  const Bytes q = encode_vspl(pm, {true, 14}).value();
  EXPECT_EQ(q, encode_vspl(pm, {true, 14}).value());
  // Decoded quantized positions sit on the steps of the same box.
  ProgressiveMesh decoded = pm;
  Result<VsplSection> back = decode_copy(q, pm.base.positions);
  ASSERT_TRUE(back.is_ok());
  decoded.splits = back.value().splits;
  EXPECT_EQ(encode_vspl(decoded, {true, 14}).value(), q);
}

TEST(VsplSection, SummaryWithoutDecoding) {
  const ProgressiveMesh pm = random_pm(12, 100, 11, true, true);
  const Bytes bytes = encode_vspl(pm, {true, 10}).value();
  Result<VsplSummary> summary = read_vspl_summary(bytes.data(), bytes.size());
  ASSERT_TRUE(summary.is_ok()) << summary.status().message();
  const VsplSummary& s = summary.value();
  EXPECT_EQ(s.split_count, 100u);
  EXPECT_EQ(s.base_vertex_count, 12u);
  EXPECT_EQ(s.full_vertex_count(), 112u);
  EXPECT_EQ(s.position_encoding, PositionEncoding::kQuantized);
  EXPECT_EQ(s.quantization_bits, 10);
  EXPECT_EQ(s.flags, kVsplStoresVsPositions | kVsplStoresPermutation);
  float lo = pm.splits[0].error;
  float hi = lo;
  for (const VertexSplit& split : pm.splits) {
    lo = std::min(lo, split.error);
    hi = std::max(hi, split.error);
  }
  EXPECT_EQ(s.min_error, lo);
  EXPECT_EQ(s.max_error, hi);
  // Summary only: it does not need the base mesh.
  EXPECT_TRUE(read_vspl_summary(bytes.data(), bytes.size() - 1).status().code() == 23);
}

TEST(VsplSection, EncoderRefusesUnstorablePms) {
  auto refused = [](const ProgressiveMesh& pm, VsplEncodeOptions options, const std::string& part) {
    Result<Bytes> bytes = encode_vspl(pm, options);
    ASSERT_FALSE(bytes.is_ok()) << part;
    EXPECT_EQ(bytes.status().kind(), ErrorKind::kInvalidInput);
    EXPECT_EQ(bytes.status().message().rfind("cannot encode VSPL: ", 0), 0u);
    EXPECT_NE(bytes.status().message().find(part), std::string::npos) << bytes.status().message();
    if (!options.quantize) {
      EXPECT_FALSE(validate_vspl(pm).empty()) << part;
    }
  };
  refused(tetrahedron_pm(), {true, 0}, "quantization bits 0 outside 1..30");
  refused(tetrahedron_pm(), {true, 31}, "quantization bits 31 outside 1..30");
  ProgressiveMesh pm = tetrahedron_pm();
  pm.splits[0].vs = 3;
  refused(pm, {},
          "1 splits have a vertex index out of range, first: split 0 (vs 3, vl 1, vr 2) with 3 "
          "vertices before it");
  pm = tetrahedron_pm();
  pm.splits[0].vr = 1;
  refused(pm, {}, "1 splits repeat a vertex, first: split 0 (vs 0, vl 1, vr 1)");
  pm = tetrahedron_pm();
  pm.splits[0].vl = 0;
  pm.splits[0].vr = kNoVertex;
  refused(pm, {}, "split 0 (vs 0, vl 0, vr none)");
  pm = tetrahedron_pm();
  pm.splits[0].vs_position[2] = std::numeric_limits<float>::infinity();
  refused(pm, {}, "1 splits have a non-finite position, first: split 0");
  pm = tetrahedron_pm();
  pm.splits[0].error = std::numeric_limits<float>::quiet_NaN();
  refused(pm, {}, "1 splits have a non-finite error, first: split 0");
  pm = tetrahedron_pm();
  pm.input_vertex.pop_back();
  refused(pm, {}, "input_vertex has 3 entries for 4 vertices");
  pm = tetrahedron_pm();
  pm.input_vertex = {0, 1, 2, 4};
  refused(pm, {}, "1 input_vertex entries out of range (4 vertices), first: PM vertex 3 -> 4");
  pm = tetrahedron_pm();
  pm.input_vertex = {3, 1, 3, 0};
  refused(pm, {},
          "input_vertex is not a permutation: 1 repeated entries, first: input vertex 3 "
          "for PM vertices 0 and 2");
  pm = tetrahedron_pm();
  pm.base.positions.resize(1);
  pm.input_vertex = {0, 1};
  refused(pm, {}, "1 splits over a base of 1 vertices (a split needs 2)");
  pm = tetrahedron_pm();
  pm.splits[0].vl = kNoVertex;
  pm.splits[0].vr = kNoVertex;
  refused(pm, {}, "1 splits have neither wing, first: split 0 (vs 0, vl none, vr none)");
}

TEST(VsplSection, EncoderRefusesAttributesItCannotStore) {
  auto refused = [](const ProgressiveMesh& pm, const std::string& message) {
    Result<Bytes> bytes = encode_vspl(pm, {});
    ASSERT_FALSE(bytes.is_ok()) << message;
    EXPECT_EQ(bytes.status().message(), "cannot encode VSPL: " + message);
    const std::vector<std::string> findings = validate_vspl(pm);
    EXPECT_NE(std::find(findings.begin(), findings.end(), message), findings.end()) << message;
  };
  const ProgressiveMesh good = open_quad_with_attributes_pm();
  ASSERT_TRUE(encode_vspl(good, {}).is_ok());
  EXPECT_TRUE(validate_vspl(good).empty());
  ProgressiveMesh pm = good;
  pm.normals.values.pop_back();
  refused(pm,
          "normals must be per-vertex with 3 components for each of the 4 vertices, they are "
          "per-vertex with 3 components and 11 floats");
  pm = good;
  pm.texcoords.binding = AttributeBinding::kPerCorner;
  refused(pm,
          "texture coordinates must be per-vertex with 2 components for each of the 4 vertices, "
          "they are per-corner with 2 components and 8 floats");
  pm = good;
  pm.normals.values[10] = std::numeric_limits<float>::quiet_NaN();
  refused(pm, "normals: 1 non-finite values, first: vertex 3");
  pm = good;
  pm.base.texcoords = MeshAttribute();
  refused(pm,
          "the progressive mesh has texture coordinates but the base mesh does not have them "
          "per-vertex for its 3 vertices");
  pm = good;
  pm.base.normals.values[4] = -0.0f;  // == 0, but not the same bits
  refused(pm, "the base mesh's normals differ from the progressive mesh's, first at vertex 1");
  pm = good;
  pm.normals = MeshAttribute();
  refused(pm, "the base mesh has normals but the progressive mesh has none for its 4 vertices");
}

TEST(VsplSection, ValidateListsEveryKindOfProblem) {
  EXPECT_TRUE(validate_vspl(tetrahedron_pm()).empty());
  EXPECT_TRUE(validate_vspl(random_pm(5, 300, 13, true, true)).empty());
  ProgressiveMesh pm = random_pm(5, 300, 13, true, true);
  pm.splits[10].vs = 1000;
  pm.splits[20].vl = pm.splits[20].vs;
  pm.splits[30].vt_position[0] = std::numeric_limits<float>::quiet_NaN();
  pm.splits[40].error = std::numeric_limits<float>::infinity();
  pm.splits[50].vl = pm.splits[50].vr = kNoVertex;
  pm.splits[60].vl = pm.splits[60].vr = kNoVertex;
  std::swap(pm.input_vertex[3], pm.input_vertex[4]);
  pm.input_vertex[7] = pm.input_vertex[9];
  add_attributes(&pm, true, true, 5);
  pm.normals.values[3 * 100 + 1] = std::numeric_limits<float>::infinity();
  pm.base.texcoords.values[2 * 4] += 1.0f;
  const std::vector<std::string> findings = validate_vspl(pm);
  ASSERT_EQ(findings.size(), 8u);
  EXPECT_EQ(findings[0].find("1 splits have a vertex index out of range, first: split 10"), 0u);
  EXPECT_EQ(findings[1].find("2 splits have neither wing, first: split 50 (vs "), 0u);
  EXPECT_EQ(findings[2].find("1 splits repeat a vertex, first: split 20"), 0u);
  EXPECT_EQ(findings[3], "1 splits have a non-finite position, first: split 30");
  EXPECT_EQ(findings[4], "1 splits have a non-finite error, first: split 40");
  EXPECT_EQ(findings[5].find("input_vertex is not a permutation: 1 repeated entries"), 0u);
  EXPECT_EQ(findings[6], "normals: 1 non-finite values, first: vertex 100");
  EXPECT_EQ(findings[7],
            "the base mesh's texture coordinates differ from the progressive mesh's, first at "
            "vertex 4");

  const ProgressiveMesh good = tetrahedron_pm();
  const Bytes bytes = encode_vspl(good, {}).value();
  EXPECT_TRUE(validate_vspl_payload(bytes.data(), bytes.size(), good.base.positions).empty());
  const std::vector<std::string> wrong_base =
      validate_vspl_payload(bytes.data(), bytes.size(), {{0, 0, 0}, {1, 1, 1}});
  ASSERT_EQ(wrong_base.size(), 1u);
  EXPECT_EQ(wrong_base[0],
            "LBK-E023: section VSPL: base vertex count 3, but the base mesh has 2 vertices");
}

// Builds a payload field by field for the decoder's error paths.
struct Payload {
  Bytes bytes;
  ByteWriter w{&bytes};
  Payload(uint32_t r, uint32_t b, uint8_t encoding, uint8_t qbits, uint8_t flags, float lo = 0,
          float hi = 0) {
    w.write(r);
    w.write(b);
    w.write(encoding);
    w.write(qbits);
    w.write(flags);
    w.write(lo);
    w.write(hi);
  }
};

void expect_malformed(const Bytes& payload, const std::string& part,
                      const std::vector<Vec3f>& base_positions) {
  Result<VsplSection> section = decode_copy(payload, base_positions);
  ASSERT_FALSE(section.is_ok()) << part;
  EXPECT_EQ(section.status().code(), 23);
  EXPECT_EQ(section.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(section.status().message().rfind("LBK-E023: section VSPL: ", 0), 0u);
  EXPECT_NE(section.status().message().find(part), std::string::npos) << section.status().message();
  EXPECT_FALSE(validate_vspl_payload(payload.data(), payload.size(), base_positions).empty());
}

std::vector<Vec3f> base_of(size_t count) {
  return std::vector<Vec3f>(count, Vec3f{1, 2, 3});
}

TEST(VsplSection, HostileCountsFailFastWithoutAllocating) {
  // Every one of these fails in the layout walk, before the records are
  // allocated (the walk needs the bytes for all records first).
  expect_malformed(Payload(UINT32_MAX - 2, 2, 0, 0, 0).bytes,
                   "the vertex indices of 4294967293 splits need", base_of(2));
  expect_malformed(Payload(UINT32_MAX, 0, 0, 0, 0).bytes,
                   "4294967295 splits over a base of 0 vertices (a split needs 2)", base_of(0));
  expect_malformed(
      Payload(1, UINT32_MAX, 0, 0, 0).bytes,
      "4294967295 base vertices and 1 splits make 4294967296 vertices, at most 2^32 - 1",
      base_of(0));
  expect_malformed(Payload(0, 1u << 31, 0, 0, kVsplStoresPermutation).bytes,
                   "the permutation entries of 2147483648 vertices need 8321499136 bytes at "
                   "offset 19, only 0 remain",
                   base_of(0));
  {
    // Topology fits (1000 splits from 2 base vertices: 3 bytes each is
    // plenty), but the positions do not.
    Payload p(1000, 2, 0, 0, 0);
    p.bytes.resize(p.bytes.size() + 4000, 0);
    expect_malformed(p.bytes, "the positions of 1000 splits need 12000 bytes", base_of(2));
  }
  {
    Payload p(1000, 2, 1, 30, kVsplStoresVsPositions);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    expect_malformed(p.bytes, "the vertex indices of 1000 splits need", base_of(2));
  }
  // The base positions the caller passes must match, and are checked before
  // any record is read.
  expect_malformed(Payload(0, 5, 0, 0, 0).bytes, "base vertex count 5, but the base mesh has 4",
                   base_of(4));
}

TEST(VsplSection, MalformedFields) {
  const std::vector<Vec3f> base3 = tetrahedron_pm().base.positions;
  expect_malformed(Bytes(18, 0), "payload has 18 bytes, the fixed fields need 19", base3);
  expect_malformed(Payload(0, 3, 2, 0, 0).bytes, "position encoding 2 is unknown", base3);
  expect_malformed(Payload(0, 3, 1, 31, 0).bytes, "quantization bits 31 outside 1..30", base3);
  expect_malformed(Payload(0, 3, 1, 0, 0).bytes, "quantization bits 0 outside 1..30", base3);
  expect_malformed(Payload(0, 3, 0, 8, 0).bytes, "quantization bits 8 with float32 positions",
                   base3);
  expect_malformed(Payload(0, 3, 0, 0, 0x10).bytes, "unknown flag bits 0x10", base3);
  expect_malformed(Payload(0, 3, 0, 0, 0xF0).bytes, "unknown flag bits 0xF0", base3);
  expect_malformed(Payload(0, 3, 0, 0, 0, std::numeric_limits<float>::quiet_NaN()).bytes,
                   "error range [nan, 0] is not finite and ordered", base3);
  expect_malformed(Payload(0, 3, 0, 0, 0, 1, 0).bytes, "error range [1, 0] is not finite", base3);
  expect_malformed(Payload(0, 3, 0, 0, 0, 1, 1).bytes,
                   "error range [1, 1] in the header, the splits' is [0, 0]", base3);
  expect_malformed(Payload(0, 3, 1, 8, 0).bytes, "payload ends inside the quantization box", base3);
  {
    Payload p(0, 3, 1, 8, 0);
    for (float f : {0.0f, 0.0f, 0.0f, 1.0f, 1.0f, -1.0f})
      p.w.write(f);
    expect_malformed(p.bytes, "quantization box axis 2 [0, -1] is not finite and ordered", base3);
  }
  {
    Payload p(0, 3, 0, 0, 0);
    p.w.write(uint8_t{0});
    expect_malformed(p.bytes, "1 trailing bytes after the last field (offset 19)", base3);
  }

  // Patches of a valid tetrahedron payload: byte 19 topology, 20..31 vt,
  // 32..35 error, 36 permutation.
  ProgressiveMesh pm = tetrahedron_pm();
  pm.input_vertex = {2, 0, 3, 1};
  const Bytes good = encode_vspl(pm, {}).value();
  ASSERT_TRUE(decode_copy(good, base3).is_ok());
  auto patched = [&](size_t offset, std::initializer_list<uint8_t> bytes) {
    Bytes b = good;
    std::copy(bytes.begin(), bytes.end(), b.begin() + static_cast<std::ptrdiff_t>(offset));
    return b;
  };
  expect_malformed(patched(19, {3 | 1 << 2 | 2 << 4}),
                   "split 0 (vs 3, vl 1, vr 2) has an index out of range (3 vertices before it, "
                   "a wing of 3 means none)",
                   base3);
  expect_malformed(patched(19, {0 | 3 << 2 | 3 << 4}),
                   "split 0 (vs 0) has neither wing (vl and vr are both 3, none)", base3);
  expect_malformed(patched(19, {2 | 3 << 2 | 2 << 4}),
                   "split 0 (vs 2, vl none, vr 2) repeats a vertex", base3);
  expect_malformed(patched(19, {0 | 0 << 2 | 2 << 4}),
                   "split 0 (vs 0, vl 0, vr 2) repeats a vertex", base3);
  expect_malformed(patched(19, {0 | 1 << 2 | 1 << 4}),
                   "split 0 (vs 0, vl 1, vr 1) repeats a vertex", base3);
  expect_malformed(patched(19, {0x24 | 0x40}), "nonzero padding bits after the vertex indices",
                   base3);
  expect_malformed(patched(24, {0x00, 0x00, 0xC0, 0x7F}),
                   "split 0: vt position coordinate 1 is not finite", base3);
  expect_malformed(patched(32, {0x00, 0x00, 0x80, 0x7F}), "split 0: error is not finite", base3);
  expect_malformed(patched(32, {0x00, 0x00, 0x80, 0x3F}),
                   "error range [0.5, 0.5] in the header, the splits' is [1, 1]", base3);
  expect_malformed(patched(36, {2 | 0 << 2 | 2 << 4 | 1 << 6}),
                   "input permutation maps PM vertex 2 to input vertex 2 a second time", base3);
  {
    // 5 base vertices, no splits: 5 entries of 3 bits; 7 is out of range.
    Payload p(0, 5, 0, 0, kVsplStoresPermutation);
    p.w.write(uint8_t{7 | 1 << 3 | 2 << 6});
    p.w.write(uint8_t{0});
    expect_malformed(p.bytes, "input permutation maps PM vertex 0 to 7, out of range (5 vertices)",
                     base_of(5));
    Payload q(0, 5, 0, 0, kVsplStoresPermutation);
    q.w.write(uint8_t{0 | 1 << 3 | 2 << 6});  // 0 1 2 3 4, then a padding bit
    q.w.write(uint8_t{0 | 3 << 1 | 4 << 4 | 1 << 7});
    expect_malformed(q.bytes, "nonzero padding bits after the input permutation", base_of(5));
  }
  {
    // n = 4: the wings take 3 bits, so 5 and above are out of range.
    Payload p(1, 4, 0, 0, 0);
    p.w.write(uint8_t{0 | 1 << 2 | 5 << 5});
    for (int i = 0; i < 4; ++i)
      p.w.write(0.0f);
    expect_malformed(p.bytes, "split 0 (vs 0, vl 1, vr 5) has an index out of range", base_of(4));
    Payload q(1, 4, 0, 0, 0);
    q.w.write(uint8_t{0 | 6 << 2 | 1 << 5});
    for (int i = 0; i < 4; ++i)
      q.w.write(0.0f);
    expect_malformed(q.bytes, "split 0 (vs 0, vl 6, vr 1) has an index out of range", base_of(4));
  }
  {
    // Quantized at 5 bits: 15 position bits, bit 15 is padding.
    Payload p(1, 3, 1, 5, 0);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    p.w.write(uint8_t{0x24});
    p.w.write(uint8_t{0});
    p.w.write(uint8_t{0x80});
    p.w.write(0.0f);
    expect_malformed(p.bytes, "nonzero padding bits after the positions", base3);
  }
  {
    // The attribute parts: byte 36..47 the normal, 48..55 the texture
    // coordinates of docs/format.md's second example.
    const Bytes with_attributes = encode_vspl(open_quad_with_attributes_pm(), {}).value();
    ASSERT_EQ(with_attributes.size(), 56u);
    Bytes b = with_attributes;
    std::copy_n(Bytes{0x00, 0x00, 0xC0, 0xFF}.begin(), 4, b.begin() + 36);
    expect_malformed(b, "split 0: normal component 0 is not finite", base3);
    b = with_attributes;
    std::copy_n(Bytes{0x00, 0x00, 0x80, 0x7F}.begin(), 4, b.begin() + 52);
    expect_malformed(b, "split 0: texture coordinate component 1 is not finite", base3);
    expect_malformed(Bytes(with_attributes.begin(), with_attributes.begin() + 47),
                     "the normals of 1 splits need 12 bytes at offset 36, only 11 remain", base3);
    expect_malformed(Bytes(with_attributes.begin(), with_attributes.end() - 1),
                     "the texture coordinates of 1 splits need 8 bytes at offset 48, only 7 remain",
                     base3);
    // Flags announcing texture coordinates that are not there.
    b = with_attributes;
    b[10] = kVsplStoresNormals;
    expect_malformed(b, "8 trailing bytes after the last field (offset 48)", base3);
  }
}

TEST(VsplSection, TruncationAtEveryLengthAndBitFlipsNeverCrash) {
  for (bool quantize : {false, true}) {
    const ProgressiveMesh pm = random_pm(6, 12, 17, true, true);
    const Bytes payload = encode_vspl(pm, {quantize, 9}).value();
    for (size_t length = 0; length < payload.size(); ++length) {
      Bytes prefix(payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(length));
      Result<VsplSection> decoded = decode_copy(prefix, pm.base.positions);
      ASSERT_FALSE(decoded.is_ok()) << length;
      EXPECT_EQ(decoded.status().code(), 23);
      EXPECT_FALSE(read_vspl_summary(prefix.data(), prefix.size()).is_ok()) << length;
    }
    Bytes longer = payload;
    longer.push_back(0);
    EXPECT_FALSE(decode_copy(longer, pm.base.positions).is_ok());
    size_t accepted = 0;
    for (size_t byte = 0; byte < payload.size(); ++byte) {
      for (int bit = 0; bit < 8; ++bit) {
        Bytes flipped = payload;
        flipped[byte] ^= static_cast<uint8_t>(1u << bit);
        Result<VsplSection> decoded = decode_copy(flipped, pm.base.positions);
        if (decoded.is_ok()) {
          // Whatever decodes must be storable again.
          ++accepted;
          ProgressiveMesh again = pm;
          again.splits = decoded.value().splits;
          again.input_vertex = decoded.value().input_vertex;
          EXPECT_TRUE(validate_vspl(again).empty());
          EXPECT_TRUE(encode_vspl(again, {}).is_ok());
        } else {
          EXPECT_EQ(decoded.status().code(), 23);
        }
      }
    }
    // Flipping a position bit still decodes: the check above ran.
    EXPECT_GT(accepted, 0u);
  }
}

TEST(VsplSection, DecodeProgressiveMeshFromBaseAndVspl) {
  ProgressiveMesh pm = random_pm(40, 400, 21, false, true);
  pm.base.triangles = {{0, 1, 2}, {2, 1, 3}};
  const Bytes base = encode_base(pm.base, {}).value();
  const Bytes vspl = encode_vspl(pm, {}).value();
  Result<ProgressiveMesh> back =
      decode_progressive_mesh(base.data(), base.size(), vspl.data(), vspl.size());
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(back.value(), pm);
  EXPECT_EQ(back.value().full_vertex_count(), 440u);

  // With attributes, quantized: the attributes come back exact.
  ProgressiveMesh attributed = pm;
  add_attributes(&attributed, true, true, 9);
  const Bytes attributed_base = encode_base(attributed.base, {true, 12}).value();
  const Bytes attributed_vspl = encode_vspl(attributed, {true, 12}).value();
  Result<ProgressiveMesh> decoded =
      decode_progressive_mesh(attributed_base.data(), attributed_base.size(),
                              attributed_vspl.data(), attributed_vspl.size());
  ASSERT_TRUE(decoded.is_ok()) << decoded.status().message();
  EXPECT_EQ(decoded.value().normals, attributed.normals);
  EXPECT_EQ(decoded.value().texcoords, attributed.texcoords);
  EXPECT_EQ(decoded.value().base.normals, attributed.base.normals);
  EXPECT_TRUE(validate_vspl(decoded.value()).empty());

  const Bytes other_base = encode_base(tetrahedron_pm().base, {}).value();
  Result<ProgressiveMesh> mismatch =
      decode_progressive_mesh(other_base.data(), other_base.size(), vspl.data(), vspl.size());
  ASSERT_FALSE(mismatch.is_ok());
  EXPECT_EQ(mismatch.status().message(),
            "LBK-E023: section VSPL: base vertex count 40, but the base mesh has 3 vertices");
}

// A container holding `sections` (tag, payload) in that order.
Bytes container_of(const std::vector<std::pair<const char*, Bytes>>& sections) {
  ContainerWriter writer;
  for (const auto& [tag, payload] : sections)
    EXPECT_TRUE(writer.add_section(tag, payload, std::string(tag) == kBaseTag).is_ok());
  return writer.finish().value();
}

std::vector<std::string> findings_of(const Bytes& file) {
  Result<Container> container = read_container(file.data(), file.size());
  EXPECT_TRUE(container.is_ok()) << container.status().message();
  std::vector<std::string> out;
  if (!container.is_ok()) return out;
  for (const SectionFinding& f : validate_sections(container.value()))
    out.push_back(f.tag + ": " + f.message);
  return out;
}

Bytes meta_with_counts(const std::map<std::string, uint64_t>& counts) {
  MetaSection meta = make_meta("lodbake-simplify");
  meta.counts = counts;
  return encode_meta(meta).value();
}

TEST(VsplSection, ContainerValidationCrossChecks) {
  const ProgressiveMesh pm = tetrahedron_pm();
  const Bytes base = encode_base(pm.base, {}).value();
  const Bytes vspl = encode_vspl(pm, {}).value();
  const Bytes meta = meta_with_counts({{"vertices", 3},
                                       {"triangles", 2},
                                       {"splits", 1},
                                       {"full_vertices", 4},
                                       {"full_triangles", 4}});
  EXPECT_TRUE(findings_of(container_of({{"META", meta}, {"BASE", base}, {"VSPL", vspl}})).empty());
  // Order does not matter.
  EXPECT_TRUE(findings_of(container_of({{"VSPL", vspl}, {"BASE", base}})).empty());
  EXPECT_TRUE(is_known_section("VSPL"));

  const Bytes wrong_meta =
      meta_with_counts({{"splits", 2}, {"full_vertices", 5}, {"full_triangles", 3}});
  EXPECT_EQ(
      findings_of(container_of({{"META", wrong_meta}, {"BASE", base}, {"VSPL", vspl}})),
      (std::vector<std::string>{"META: counts.splits is 2 but VSPL holds 1",
                                "META: counts.full_vertices is 5 but BASE and VSPL make 4",
                                "META: counts.full_triangles is 3 but BASE and VSPL make 4"}));
  EXPECT_EQ(findings_of(container_of({{"META", wrong_meta}, {"BASE", base}})),
            (std::vector<std::string>{
                "META: counts.splits is given but there is no VSPL section",
                "META: counts.full_vertices is given but there is no VSPL section",
                "META: counts.full_triangles is given but there is no VSPL section"}));
  EXPECT_EQ(
      findings_of(container_of({{"VSPL", vspl}})),
      (std::vector<std::string>{"VSPL: no BASE section holds the base mesh of the 1 splits"}));

  const Bytes bigger_base = encode_base(random_pm(5, 0, 1, false, false).base, {}).value();
  EXPECT_EQ(findings_of(container_of({{"BASE", bigger_base}, {"VSPL", vspl}})),
            (std::vector<std::string>{"VSPL: base vertex count 3 but BASE holds 5 vertices"}));

  Bytes broken = vspl;
  broken[19] = 3 | 1 << 2 | 2 << 4;
  const std::vector<std::string> findings =
      findings_of(container_of({{"BASE", base}, {"VSPL", broken}}));
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].rfind("VSPL: LBK-E023: section VSPL: split 0 (vs 3, vl 1, vr 2)", 0), 0u);

  // Attributes in VSPL but not in BASE.
  const ProgressiveMesh attributed = open_quad_with_attributes_pm();
  const Bytes attributed_vspl = encode_vspl(attributed, {}).value();
  EXPECT_TRUE(findings_of(container_of({{"BASE", encode_base(attributed.base, {}).value()},
                                        {"VSPL", attributed_vspl}}))
                  .empty());
  EXPECT_EQ(findings_of(container_of({{"BASE", encode_base(open_quad_pm().base, {}).value()},
                                      {"VSPL", attributed_vspl}})),
            (std::vector<std::string>{"VSPL: LBK-E023: section VSPL: VSPL stores the split "
                                      "vertices' normals but BASE has none for its vertices"}));

  const std::vector<std::string> truncated =
      findings_of(container_of({{"BASE", base}, {"VSPL", Bytes(vspl.begin(), vspl.end() - 1)}}));
  ASSERT_EQ(truncated.size(), 1u);
  EXPECT_NE(truncated[0].find("the errors of 1 splits need 4 bytes"), std::string::npos);
}

}  // namespace
}  // namespace lodbake
