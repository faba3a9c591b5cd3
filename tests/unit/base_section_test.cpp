// BASE section: exact float32 round trips (with per-vertex and per-corner
// attributes, V = 0/1/2), quantization within the documented bound, the
// exact byte layout, encoder refusals, and hostile payloads that must fail
// fast with LBK-E023 without allocating.
#include "formats/sections/base.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "formats/support/bit_packing.h"
#include "formats/support/byte_reader.h"

namespace lodbake {
namespace {

TriangleMesh cube() {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.positions.push_back({static_cast<float>(i & 1), static_cast<float>((i >> 1) & 1),
                              static_cast<float>((i >> 2) & 1)});
  }
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

// Random mesh: positions spread over many magnitudes, random triangles.
TriangleMesh random_mesh(uint32_t vertices, uint32_t triangles, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-1000.0f, 1000.0f);
  TriangleMesh mesh;
  for (uint32_t i = 0; i < vertices; ++i) {
    mesh.positions.push_back({coord(rng), coord(rng) * 1e-3f, coord(rng) + 5000.0f});
  }
  for (uint32_t i = 0; i < triangles; ++i) {
    mesh.triangles.push_back({static_cast<uint32_t>(rng() % vertices),
                              static_cast<uint32_t>(rng() % vertices),
                              static_cast<uint32_t>(rng() % vertices)});
  }
  return mesh;
}

void add_per_vertex_normals(TriangleMesh* mesh) {
  mesh->normals.binding = AttributeBinding::kPerVertex;
  mesh->normals.components = 3;
  for (size_t i = 0; i < mesh->positions.size(); ++i) {
    mesh->normals.values.insert(mesh->normals.values.end(), {0.0f, -1.0f, static_cast<float>(i)});
  }
}

void add_per_corner_texcoords(TriangleMesh* mesh, uint32_t value_count) {
  mesh->texcoords.binding = AttributeBinding::kPerCorner;
  mesh->texcoords.components = 2;
  for (uint32_t i = 0; i < value_count; ++i) {
    mesh->texcoords.values.insert(mesh->texcoords.values.end(), {0.5f * i, 0.25f});
  }
  for (size_t t = 0; t < mesh->triangles.size(); ++t) {
    mesh->texcoords.corners.push_back({static_cast<uint32_t>(t % value_count),
                                       static_cast<uint32_t>((t + 1) % value_count),
                                       static_cast<uint32_t>((t + 2) % value_count)});
  }
}

Result<TriangleMesh> decode_copy(const Bytes& payload, BaseSummary* summary = nullptr) {
  Bytes copy(payload);
  copy.shrink_to_fit();
  return decode_base(copy.empty() ? nullptr : copy.data(), copy.size(), summary);
}

TriangleMesh round_trip(const TriangleMesh& mesh, const BaseEncodeOptions& options) {
  Result<Bytes> bytes = encode_base(mesh, options);
  EXPECT_TRUE(bytes.is_ok()) << bytes.status().message();
  if (!bytes.is_ok()) return {};
  Result<TriangleMesh> back = decode_copy(bytes.value());
  EXPECT_TRUE(back.is_ok()) << back.status().message();
  return back.is_ok() ? back.value() : TriangleMesh{};
}

TEST(BaseSection, Float32RoundTripIsExact) {
  TriangleMesh mesh = cube();
  EXPECT_EQ(round_trip(mesh, {}), mesh);
  add_per_vertex_normals(&mesh);
  add_per_corner_texcoords(&mesh, 5);
  EXPECT_EQ(round_trip(mesh, {}), mesh);
  // The other way round: per-corner normals, per-vertex texture coordinates.
  TriangleMesh other = cube();
  other.normals.binding = AttributeBinding::kPerCorner;
  other.normals.components = 3;
  other.normals.values = {0, 0, 1, 0, 1, 0, 1, 0, 0, -0.0f, 1e-38f, -3e38f};
  for (size_t t = 0; t < other.triangles.size(); ++t) {
    other.normals.corners.push_back({static_cast<uint32_t>(t % 4), 3, 0});
  }
  other.texcoords.binding = AttributeBinding::kPerVertex;
  other.texcoords.components = 2;
  for (int i = 0; i < 8; ++i)
    other.texcoords.values.insert(other.texcoords.values.end(), {0.125f * i, 1});
  EXPECT_EQ(round_trip(other, {}), other);
  TriangleMesh big = random_mesh(5000, 9000, 1);
  EXPECT_EQ(round_trip(big, {}), big);
}

TEST(BaseSection, TinyMeshes) {
  TriangleMesh empty;
  EXPECT_EQ(round_trip(empty, {}), empty);
  EXPECT_EQ(round_trip(empty, {true, 12}), empty);

  TriangleMesh one;
  one.positions = {{1.5f, -2.0f, 3.25f}};
  add_per_vertex_normals(&one);
  EXPECT_EQ(round_trip(one, {}), one);
  // One vertex is its own box: quantization reproduces it exactly.
  EXPECT_EQ(round_trip(one, {true, 1}), one);

  TriangleMesh two;
  two.positions = {{0, 0, 0}, {1, 2, 3}};
  two.triangles = {{0, 1, 1}, {1, 0, 0}};
  add_per_corner_texcoords(&two, 1);  // corner indices take 0 bits
  EXPECT_EQ(round_trip(two, {}), two);
  EXPECT_EQ(round_trip(two, {true, 1}), two);  // both vertices are box corners

  // Per-corner attribute values with no triangles.
  TriangleMesh points;
  points.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  points.texcoords.binding = AttributeBinding::kPerCorner;
  points.texcoords.components = 2;
  points.texcoords.values = {1, 2, 3, 4};
  EXPECT_EQ(round_trip(points, {}), points);
}

TEST(BaseSection, ExactLayout) {
  TriangleMesh mesh;
  mesh.positions = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  mesh.triangles = {{0, 1, 2}};
  Result<Bytes> result = encode_base(mesh, {});
  ASSERT_TRUE(result.is_ok());
  const Bytes& b = result.value();
  // 12 fixed + 36 positions + ceil(3 * 2 / 8) = 1 index byte.
  ASSERT_EQ(b.size(), 49u);
  ByteReader reader(b.data(), b.size());
  uint32_t v = 0, t = 0;
  uint8_t encoding = 9, qbits = 9, ibits = 9, mask = 9;
  ASSERT_TRUE(reader.read(&v) && reader.read(&t) && reader.read(&encoding) && reader.read(&qbits) &&
              reader.read(&ibits) && reader.read(&mask));
  EXPECT_EQ(v, 3u);
  EXPECT_EQ(t, 1u);
  EXPECT_EQ(encoding, 0);
  EXPECT_EQ(qbits, 0);
  EXPECT_EQ(ibits, 2);
  EXPECT_EQ(mask, 0);
  float first = 0;
  std::memcpy(&first, b.data() + 12, 4);
  EXPECT_EQ(first, 1.0f);
  // Indices 0, 1, 2 at 2 bits, LSB first: 00 | 01 << 2 | 10 << 4.
  EXPECT_EQ(b[48], 0x24u);

  // Quantized, 4 bits, 2 vertices, a per-vertex normal.
  TriangleMesh q;
  q.positions = {{0, 10, -1}, {1, 20, 1}};
  q.triangles = {{0, 1, 1}};
  add_per_vertex_normals(&q);
  Result<Bytes> qbytes = encode_base(q, {true, 4});
  ASSERT_TRUE(qbytes.is_ok());
  const Bytes& c = qbytes.value();
  // 12 fixed + 24 box + ceil(6 * 4 / 8) = 3 + 1 index byte + (1 + 4 + 24) normals.
  ASSERT_EQ(c.size(), 12u + 24 + 3 + 1 + 29);
  EXPECT_EQ(c[8], 1);   // quantized
  EXPECT_EQ(c[9], 4);   // bits
  EXPECT_EQ(c[10], 1);  // index bits for 2 vertices
  EXPECT_EQ(c[11], kBaseHasNormals);
  // Vertex 0 is the box minimum (0, 0, 0), vertex 1 the maximum (15, 15, 15).
  EXPECT_EQ(c[36], 0x00u);
  EXPECT_EQ(c[37], 0xF0u);
  EXPECT_EQ(c[38], 0xFFu);
  EXPECT_EQ(c[39], 0x06u);  // indices 0, 1, 1
  EXPECT_EQ(c[40], 1);      // per-vertex binding
}

TEST(BaseSection, QuantizationStaysWithinTheDocumentedBound) {
  const TriangleMesh mesh = random_mesh(3000, 100, 5);
  for (int bits : {1, 2, 5, 8, 11, 16, 20, 24, 30}) {
    Result<QuantizationReport> report = measure_quantization(mesh.positions, bits);
    ASSERT_TRUE(report.is_ok());
    EXPECT_LE(report.value().max_error, report.value().error_bound) << bits;
    BaseSummary summary;
    Result<Bytes> bytes = encode_base(mesh, {true, bits});
    ASSERT_TRUE(bytes.is_ok());
    Result<TriangleMesh> back = decode_copy(bytes.value(), &summary);
    ASSERT_TRUE(back.is_ok()) << back.status().message();
    EXPECT_EQ(back.value().triangles, mesh.triangles);
    EXPECT_EQ(summary.quantization_bits, bits);
    EXPECT_EQ(summary.box_min, report.value().box_min);
    double worst = 0;
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      for (int a = 0; a < 3; ++a) {
        const double error =
            std::fabs(static_cast<double>(back.value().positions[i][a]) - mesh.positions[i][a]);
        ASSERT_LE(error, report.value().error_bound) << "bits " << bits << " vertex " << i;
        worst = std::max(worst, error);
      }
    }
    // The decoder and measure_quantization compute the same thing.
    EXPECT_EQ(worst, report.value().max_error) << bits;
  }
  // Finer quantization is more accurate.
  const double coarse = measure_quantization(mesh.positions, 8).value().max_error;
  const double fine = measure_quantization(mesh.positions, 16).value().max_error;
  EXPECT_LT(fine, coarse / 100);
}

TEST(BaseSection, QuantizationIsDeterministicAndIdempotent) {
  const TriangleMesh mesh = random_mesh(500, 800, 9);
  const Bytes a = encode_base(mesh, {true, 14}).value();
  const Bytes b = encode_base(mesh, {true, 14}).value();
  EXPECT_EQ(a, b);
  // Re-encoding decoded positions gives the same integers: the box is the
  // same and every value sits exactly on a step.
  const TriangleMesh decoded = decode_copy(a).value();
  EXPECT_EQ(encode_base(decoded, {true, 14}).value(), a);
}

TEST(BaseSection, SummaryWithoutDecoding) {
  TriangleMesh mesh = cube();
  add_per_vertex_normals(&mesh);
  add_per_corner_texcoords(&mesh, 7);
  const Bytes bytes = encode_base(mesh, {true, 10}).value();
  Result<BaseSummary> summary = read_base_summary(bytes.data(), bytes.size());
  ASSERT_TRUE(summary.is_ok()) << summary.status().message();
  EXPECT_EQ(summary.value().vertex_count, 8u);
  EXPECT_EQ(summary.value().triangle_count, 12u);
  EXPECT_EQ(summary.value().position_encoding, PositionEncoding::kQuantized);
  EXPECT_EQ(summary.value().quantization_bits, 10);
  EXPECT_EQ(summary.value().index_bits, 3);
  EXPECT_EQ(summary.value().attribute_mask, kBaseHasNormals | kBaseHasTexcoords);
  EXPECT_EQ(summary.value().normals_binding, AttributeBinding::kPerVertex);
  EXPECT_EQ(summary.value().normals_count, 8u);
  EXPECT_EQ(summary.value().texcoords_binding, AttributeBinding::kPerCorner);
  EXPECT_EQ(summary.value().texcoords_count, 7u);
  EXPECT_EQ(summary.value().box_max, (Vec3f{1, 1, 1}));
}

TEST(BaseSection, EncoderRefusesUnstorableMeshes) {
  auto refused = [](const TriangleMesh& mesh, BaseEncodeOptions options, const std::string& part) {
    Result<Bytes> bytes = encode_base(mesh, options);
    ASSERT_FALSE(bytes.is_ok()) << part;
    EXPECT_EQ(bytes.status().kind(), ErrorKind::kInvalidInput);
    EXPECT_NE(bytes.status().message().find(part), std::string::npos) << bytes.status().message();
    EXPECT_EQ(bytes.status().message().rfind("cannot encode BASE: ", 0), 0u);
  };
  TriangleMesh mesh = cube();
  refused(mesh, {true, 0}, "quantization bits 0 outside 1..30");
  refused(mesh, {true, 31}, "quantization bits 31");
  mesh.triangles[3][1] = 8;
  refused(mesh, {}, "1 vertex indices out of range (8 vertices), first: triangle 3 (5, 8, 6)");
  mesh = cube();
  mesh.positions[2][1] = std::numeric_limits<float>::quiet_NaN();
  refused(mesh, {}, "non-finite coordinate, first: vertex 2");
  mesh = cube();
  mesh.positions.resize(1);
  mesh.triangles = {{0, 0, 0}};
  refused(mesh, {}, "1 triangles over 1 vertices");
  mesh = cube();
  add_per_vertex_normals(&mesh);
  mesh.normals.values.resize(21);
  refused(mesh, {}, "7 per-vertex normals for 8 vertices");
  mesh = cube();
  add_per_corner_texcoords(&mesh, 4);
  mesh.texcoords.corners.pop_back();
  refused(mesh, {}, "11 corner triples of texture coordinates for 12 triangles");
  mesh = cube();
  add_per_corner_texcoords(&mesh, 4);
  mesh.texcoords.corners[5][2] = 4;
  refused(mesh, {}, "1 texture coordinates corner indices out of range (4 values)");
  mesh = cube();
  add_per_vertex_normals(&mesh);
  mesh.normals.components = 2;
  refused(mesh, {}, "normals have 2 components, expected 3");
  mesh = cube();
  mesh.texcoords.values = {1, 2};
  refused(mesh, {}, "texture coordinates have values but no binding");
  mesh = cube();
  add_per_vertex_normals(&mesh);
  mesh.normals.values[4] = std::numeric_limits<float>::infinity();
  refused(mesh, {}, "normals hold 1 non-finite floats");
}

// Builds a payload field by field for the decoder's error paths.
struct Payload {
  Bytes bytes;
  ByteWriter w{&bytes};
  Payload(uint32_t v, uint32_t t, uint8_t encoding, uint8_t qbits, uint8_t ibits, uint8_t mask) {
    w.write(v);
    w.write(t);
    w.write(encoding);
    w.write(qbits);
    w.write(ibits);
    w.write(mask);
  }
};

void expect_malformed(const Bytes& payload, const std::string& part) {
  Result<TriangleMesh> mesh = decode_copy(payload);
  ASSERT_FALSE(mesh.is_ok()) << part;
  EXPECT_EQ(mesh.status().code(), 23);
  EXPECT_EQ(mesh.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(mesh.status().message().rfind("LBK-E023: section BASE: ", 0), 0u);
  EXPECT_NE(mesh.status().message().find(part), std::string::npos) << mesh.status().message();
  EXPECT_FALSE(validate_base_payload(payload.data(), payload.size()).empty());
}

TEST(BaseSection, HostileCountsFailFastWithoutAllocating) {
  expect_malformed(Payload(UINT32_MAX, 0, 0, 0, 32, 0).bytes,
                   "4294967295 vertices need 51539607540 bytes at offset 12, only 0 remain");
  expect_malformed(Payload(UINT32_MAX, 0, 1, 1, 32, 0).bytes,
                   "payload ends inside the quantization box");
  {
    Payload p(UINT32_MAX, UINT32_MAX, 1, 1, 32, 0);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    expect_malformed(p.bytes, "4294967295 vertices need 1610612736 bytes");
  }
  {
    Payload p(2, UINT32_MAX, 0, 0, 1, 0);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    expect_malformed(p.bytes, "4294967295 triangles need 1610612736 bytes at offset 36");
  }
  {
    Payload p(2, 0, 0, 0, 1, kBaseHasNormals);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    p.w.write(uint8_t{2});
    p.w.write(UINT32_MAX);
    expect_malformed(p.bytes, "4294967295 normals need 51539607540 bytes");
  }
  {
    // Per-corner corner indices for many triangles.
    Payload p(2, 8, 0, 0, 1, kBaseHasTexcoords);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    for (int i = 0; i < 3; ++i)
      p.w.write(uint8_t{0});  // 24 index bits
    p.w.write(uint8_t{2});
    p.w.write(uint32_t{3});
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    expect_malformed(p.bytes, "the texture coordinates corner indices need 6 bytes");
  }
  expect_malformed(Payload(0, UINT32_MAX, 0, 0, 0, 0).bytes,
                   "4294967295 triangles over 0 vertices");
  expect_malformed(Payload(1, UINT32_MAX, 0, 0, 0, 0).bytes,
                   "4294967295 triangles over 1 vertices");
}

TEST(BaseSection, MalformedFields) {
  expect_malformed(Bytes(11, 0), "payload has 11 bytes, the fixed fields need 12");
  expect_malformed(Payload(0, 0, 2, 0, 0, 0).bytes, "position encoding 2 is unknown");
  expect_malformed(Payload(0, 0, 1, 31, 0, 0).bytes, "quantization bits 31 outside 1..30");
  expect_malformed(Payload(0, 0, 1, 0, 0, 0).bytes, "quantization bits 0 outside 1..30");
  expect_malformed(Payload(0, 0, 0, 8, 0, 0).bytes, "quantization bits 8 with float32 positions");
  expect_malformed(Payload(5, 0, 0, 0, 4, 0).bytes, "index bits 4, 5 vertices need exactly 3");
  expect_malformed(Payload(0, 0, 0, 0, 0, 0x04).bytes, "unknown attribute mask bits 0x04");
  {
    Payload p(1, 0, 1, 8, 0, 0);
    for (float f : {0.0f, 0.0f, 0.0f, -1.0f, 1.0f, 1.0f})
      p.w.write(f);
    p.w.write(uint8_t{0});
    p.w.write(uint8_t{0});
    p.w.write(uint8_t{0});
    expect_malformed(p.bytes, "quantization box axis 0 [0, -1] is not finite and ordered");
  }
  {
    Payload p(1, 0, 1, 8, 0, 0);
    for (float f : {0.0f, 0.0f, 0.0f, 1.0f, std::numeric_limits<float>::infinity(), 1.0f}) {
      p.w.write(f);
    }
    expect_malformed(p.bytes, "quantization box axis 1");
  }
  {
    Payload p(2, 0, 0, 0, 1, 0);
    for (float f : {0.0f, 0.0f, 0.0f, 1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f}) {
      p.w.write(f);
    }
    expect_malformed(p.bytes, "position float 4 is not finite");
  }
  {
    // Index 3 with 3 vertices (2 bits can say 3).
    Payload p(3, 1, 0, 0, 2, 0);
    for (int i = 0; i < 9; ++i)
      p.w.write(0.0f);
    p.w.write(uint8_t{0x03 | 0x01 << 2 | 0x02 << 4});
    expect_malformed(p.bytes, "vertex index 0 of triangle 0 is 3, out of range (3 values)");
  }
  {
    Payload p(3, 1, 0, 0, 2, 0);
    for (int i = 0; i < 9; ++i)
      p.w.write(0.0f);
    p.w.write(uint8_t{0x24 | 0x40});  // indices 0 1 2, then a padding bit
    expect_malformed(p.bytes, "nonzero padding bits after vertex index");
  }
  {
    Payload p(2, 0, 1, 3, 1, 0);
    for (float f : {0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f})
      p.w.write(f);
    p.w.write(uint8_t{0});
    p.w.write(uint8_t{0});
    p.w.write(uint8_t{0x80});  // 18 position bits, bit 23 is padding
    expect_malformed(p.bytes, "nonzero padding bits after the positions");
  }
  {
    Payload p(2, 0, 0, 0, 1, kBaseHasNormals);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    p.w.write(uint8_t{3});
    p.w.write(uint32_t{2});
    expect_malformed(p.bytes, "normals binding 3 is unknown");
  }
  {
    Payload p(2, 0, 0, 0, 1, kBaseHasNormals);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    p.w.write(uint8_t{1});
    p.w.write(uint32_t{3});
    expect_malformed(p.bytes, "3 per-vertex normals for 2 vertices");
  }
  {
    Payload p(2, 1, 0, 0, 1, kBaseHasNormals);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    p.w.write(uint8_t{0x06});
    p.w.write(uint8_t{2});
    p.w.write(uint32_t{0});
    expect_malformed(p.bytes, "no normals values for the corners of 1 triangles");
  }
  {
    Payload p(2, 0, 0, 0, 1, 0);
    for (int i = 0; i < 6; ++i)
      p.w.write(0.0f);
    p.w.write(uint8_t{0});
    expect_malformed(p.bytes, "1 trailing bytes after the last field (offset 36)");
  }
}

TEST(BaseSection, TruncationAtEveryLengthAndBitFlipsNeverCrash) {
  TriangleMesh mesh = cube();
  add_per_vertex_normals(&mesh);
  add_per_corner_texcoords(&mesh, 6);
  for (bool quantize : {false, true}) {
    const Bytes payload = encode_base(mesh, {quantize, 9}).value();
    for (size_t length = 0; length < payload.size(); ++length) {
      Bytes prefix(payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(length));
      Result<TriangleMesh> decoded = decode_copy(prefix);
      ASSERT_FALSE(decoded.is_ok()) << length;
      EXPECT_EQ(decoded.status().code(), 23);
    }
    for (size_t byte = 0; byte < payload.size(); ++byte) {
      for (int bit = 0; bit < 8; ++bit) {
        Bytes flipped = payload;
        flipped[byte] ^= static_cast<uint8_t>(1u << bit);
        Result<TriangleMesh> decoded = decode_copy(flipped);
        if (decoded.is_ok()) {
          // Whatever decodes must be storable again.
          EXPECT_TRUE(encode_base(decoded.value(), {}).is_ok());
        } else {
          EXPECT_EQ(decoded.status().code(), 23);
        }
      }
    }
  }
}

TEST(BaseSection, ValidateFindsDeepProblems) {
  TriangleMesh mesh = cube();
  EXPECT_TRUE(validate_base(mesh).empty());
  const Bytes payload = encode_base(mesh, {}).value();
  EXPECT_TRUE(validate_base_payload(payload.data(), payload.size()).empty());

  mesh.positions.push_back({5, 5, 5});
  mesh.triangles[4] = {0, 0, 4};
  mesh.triangles[7] = {3, 6, 6};
  std::vector<std::string> findings = validate_base(mesh);
  ASSERT_EQ(findings.size(), 2u);
  EXPECT_EQ(findings[0], "2 triangles repeat a vertex index, first: triangle 4 (0, 0, 4)");
  EXPECT_EQ(findings[1], "1 vertices are used by no triangle, first: vertex 8");

  mesh.triangles[0][0] = 100;
  mesh.positions[1][0] = std::numeric_limits<float>::infinity();
  findings = validate_base(mesh);
  ASSERT_GE(findings.size(), 3u);
  EXPECT_EQ(findings[0], "1 vertices have a non-finite coordinate, first: vertex 1");
  EXPECT_EQ(findings[1],
            "1 vertex indices out of range (9 vertices), first: triangle 0 (100, 2, 1)");

  const Bytes junk(5, 0xFF);
  findings = validate_base_payload(junk.data(), junk.size());
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].rfind("LBK-E023: section BASE: ", 0), 0u);
}

TEST(BaseSection, LargeGridRoundTrip) {
  // 160k triangles: exercises multi-byte index widths (17 bits) and speed.
  const uint32_t n = 284;
  TriangleMesh mesh;
  for (uint32_t y = 0; y < n; ++y) {
    for (uint32_t x = 0; x < n; ++x) {
      mesh.positions.push_back({x * 0.01f, y * 0.01f, std::sin(x * 0.1f) * std::cos(y * 0.1f)});
    }
  }
  for (uint32_t y = 0; y + 1 < n; ++y) {
    for (uint32_t x = 0; x + 1 < n; ++x) {
      const uint32_t i = y * n + x;
      mesh.triangles.push_back({i, i + 1, i + n});
      mesh.triangles.push_back({i + 1, i + n + 1, i + n});
    }
  }
  EXPECT_EQ(round_trip(mesh, {}), mesh);
  const Bytes quantized = encode_base(mesh, {true, 16}).value();
  Result<BaseSummary> summary = read_base_summary(quantized.data(), quantized.size());
  ASSERT_TRUE(summary.is_ok());
  EXPECT_EQ(summary.value().index_bits, 17);
  // Fixed fields, box, 3 x 16 bits per vertex, 3 x 17 bits per triangle.
  EXPECT_EQ(quantized.size(), 12u + 24 + 6 * 80656 + (3 * 160178 * 17 + 7) / 8);
}

}  // namespace
}  // namespace lodbake
