// parse_stl: the real STL meshes of ../shared/data (counts from MANIFEST.md),
// every STL in bad/ (outcomes from its README), binary/ASCII detection,
// welding and malformed input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "lib/meshio/mesh_readers.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::expect_rejected;
using testing_util::has_note;
using testing_util::shared_file;

Result<TriangleMesh> parse(const Bytes& bytes, ImportReport* report = nullptr) {
  return parse_stl(bytes.data(), bytes.size(), report);
}
Result<TriangleMesh> parse(const std::string& text, ImportReport* report = nullptr) {
  return parse_stl(reinterpret_cast<const uint8_t*>(text.data()), text.size(), report);
}

struct Facet {
  Vec3f normal;
  Vec3f corners[3];
  uint16_t attribute = 0;
};

Bytes binary_stl(const std::vector<Facet>& facets, const std::string& header_text = "binary") {
  Bytes out(80, 0);
  std::memcpy(out.data(), header_text.data(), std::min<size_t>(header_text.size(), 80));
  auto put = [&out](const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    out.insert(out.end(), b, b + n);
  };
  uint32_t count = static_cast<uint32_t>(facets.size());
  put(&count, 4);
  for (const Facet& f : facets) {
    put(f.normal.data(), 12);
    for (const Vec3f& c : f.corners)
      put(c.data(), 12);
    put(&f.attribute, 2);
  }
  return out;
}

// A tetrahedron as facets: 12 corners at 4 distinct positions.
const Vec3f kP[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<Facet> kTetra = {
    {{0, 0, -1}, {kP[0], kP[2], kP[1]}},
    {{0, -1, 0}, {kP[0], kP[1], kP[3]}},
    {{-1, 0, 0}, {kP[0], kP[3], kP[2]}},
    {{0.577f, 0.577f, 0.577f}, {kP[1], kP[2], kP[3]}},
};
const std::vector<Triangle> kTetraTriangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {2, 1, 3}};
const std::vector<Vec3f> kTetraPositions = {kP[0], kP[2], kP[1], kP[3]};  // first appearance

const char* kTetraAscii =
    "solid tetra made by hand\n"
    "  facet normal 0 0 -1\n    outer loop\n      vertex 0 0 0\n      vertex 0 1 0\n"
    "      vertex 1 0 0\n    endloop\n  endfacet\n"
    "  facet normal 0 -1 0\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n"
    "      vertex 0 0 1\n    endloop\n  endfacet\n"
    "  facet normal -1 0 0\n    outer loop\n      vertex 0 0 0\n      vertex 0 0 1\n"
    "      vertex 0 1 0\n    endloop\n  endfacet\n"
    "  facet normal 0.577 0.577 0.577\n    outer loop\n      vertex 1 0 0\n"
    "      vertex 0 1 0\n      vertex 0 0 1\n    endloop\n  endfacet\n"
    "endsolid tetra made by hand\n";

// ---------------------------------------------------------------- real meshes

TEST(StlReaderManifest, BinaryMeshesHaveTheManifestCounts) {
  struct Row {
    const char* file;
    size_t vertices;
    size_t triangles;
  };
  for (const Row& row :
       {Row{"meshes/cgal_pig.stl", 8642, 16848}, Row{"meshes/draco_bunny.stl", 34834, 69451}}) {
    SCOPED_TRACE(row.file);
    ImportReport report;
    Result<TriangleMesh> mesh = parse(shared_file(row.file), &report);
    ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
    EXPECT_EQ(mesh.value().vertex_count(), row.vertices);
    EXPECT_EQ(mesh.value().triangle_count(), row.triangles);
    EXPECT_EQ(report.format, "stl-binary");
    EXPECT_EQ(report.file_faces, row.triangles);
    EXPECT_EQ(report.welded_vertices, 3 * row.triangles - row.vertices);
    for (const Triangle& t : mesh.value().triangles) {
      for (uint32_t v : t)
        ASSERT_LT(v, mesh.value().vertex_count());
    }
  }
}

TEST(StlReaderBadInputs, EachFileHasItsDocumentedOutcome) {
  expect_rejected(parse(shared_file("bad/hw_empty.stl")), "empty file");
  expect_rejected(parse(shared_file("bad/hw_garbage.stl")),
                  "binary stl header says 2355462449 triangles (117773122534 bytes), but the "
                  "file has 4096 bytes");
  expect_rejected(parse(shared_file("bad/hw_stl_count_exceeds_length.stl")),
                  "binary stl header says 1000000000 triangles (50000000084 bytes), but the file "
                  "has 184 bytes and does not start with 'solid'");
}

// ------------------------------------------------------------------- features

TEST(StlReader, BinaryTetrahedronIsWeldedInFirstAppearanceOrder) {
  ImportReport report;
  Result<TriangleMesh> mesh = parse(binary_stl(kTetra), &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().positions, kTetraPositions);
  EXPECT_EQ(mesh.value().triangles, kTetraTriangles);
  EXPECT_EQ(report.welded_vertices, 8u);
  EXPECT_EQ(report.file_faces, 4u);
  EXPECT_TRUE(has_note(report, "ignored stl facet normals"));
  EXPECT_FALSE(mesh.value().normals.present());
}

TEST(StlReader, AsciiGivesTheSameMeshAsBinary) {
  ImportReport report;
  Result<TriangleMesh> ascii = parse(std::string(kTetraAscii), &report);
  ASSERT_TRUE(ascii.is_ok()) << ascii.status().message();
  EXPECT_EQ(report.format, "stl-ascii");
  EXPECT_EQ(report.welded_vertices, 8u);
  Result<TriangleMesh> binary = parse(binary_stl(kTetra));
  ASSERT_TRUE(binary.is_ok());
  EXPECT_TRUE(ascii.value() == binary.value());
}

TEST(StlReader, AsciiAcceptsSeveralSolidsAnyCaseAndAnyLayout) {
  std::string two = std::string(kTetraAscii) +
                    "SOLID second\nFACET NORMAL 0 0 0 OUTER LOOP\n"
                    "VERTEX 5 5 5 VERTEX 6 5 5\nVERTEX 5 6 5 ENDLOOP ENDFACET\nENDSOLID\n";
  Result<TriangleMesh> mesh = parse(two);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(mesh.value().vertex_count(), 7u);
  EXPECT_EQ(mesh.value().triangle_count(), 5u);
  EXPECT_EQ(mesh.value().triangles.back(), (Triangle{4, 5, 6}));
}

TEST(StlReader, BinaryWithSolidHeaderIsBinaryWhenTheSizeMatches) {
  ImportReport report;
  Result<TriangleMesh> mesh =
      parse(binary_stl(kTetra, "solid exported by a binary writer"), &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(report.format, "stl-binary");
  EXPECT_EQ(mesh.value().triangles, kTetraTriangles);

  // Same header, one byte more: neither binary nor valid ASCII.
  Bytes longer = binary_stl(kTetra, "solid exported by a binary writer");
  longer.push_back(0);
  expect_rejected(parse(longer), "and not binary stl (binary stl header says 4 triangles");
}

TEST(StlReader, WeldingTreatsSignedZerosAsEqualAndKeepsTheFirst) {
  std::vector<Facet> facets = {
      {{0, 0, 0}, {{-0.0f, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
      {{0, 0, 0}, {{0.0f, 0, 0}, {0, 1, 0}, {0, 0, -0.0f}}},
  };
  ImportReport report;
  Result<TriangleMesh> mesh = parse(binary_stl(facets), &report);
  ASSERT_TRUE(mesh.is_ok());
  ASSERT_EQ(mesh.value().vertex_count(), 3u);
  EXPECT_TRUE(std::signbit(mesh.value().positions[0][0]));
  EXPECT_EQ(mesh.value().triangles[1], (Triangle{0, 2, 0}));  // degenerate, kept
  EXPECT_EQ(report.welded_vertices, 3u);
  EXPECT_FALSE(has_note(report, "normals"));  // all zero: nothing was dropped
}

TEST(StlReader, NonZeroAttributeBytesAreNoted) {
  std::vector<Facet> facets = kTetra;
  facets[1].attribute = 0x7c00;
  facets[3].attribute = 1;
  ImportReport report;
  ASSERT_TRUE(parse(binary_stl(facets), &report).is_ok());
  EXPECT_TRUE(has_note(report, "attribute bytes (e.g. colour) of 2 stl facets"));
}

TEST(StlReader, ManyFacetsGrowTheWelderDeterministically) {
  // A 100 x 100 grid of quads as a soup: 10,201 distinct positions.
  std::vector<Facet> facets;
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) {
      Vec3f a{float(x), float(y), 0}, b{float(x + 1), float(y), 0};
      Vec3f c{float(x + 1), float(y + 1), 0}, d{float(x), float(y + 1), 0};
      facets.push_back({{0, 0, 1}, {a, b, c}});
      facets.push_back({{0, 0, 1}, {a, c, d}});
    }
  }
  std::string ascii = "solid grid\n";
  for (const Facet& f : facets) {
    ascii += "facet normal 0 0 1\nouter loop\n";
    for (const Vec3f& p : f.corners) {
      ascii += "vertex " + std::to_string(int(p[0])) + " " + std::to_string(int(p[1])) + " 0\n";
    }
    ascii += "endloop\nendfacet\n";
  }
  ascii += "endsolid grid\n";
  Result<TriangleMesh> binary = parse(binary_stl(facets));
  Result<TriangleMesh> text = parse(ascii);
  ASSERT_TRUE(binary.is_ok());
  ASSERT_TRUE(text.is_ok()) << text.status().message();
  EXPECT_EQ(binary.value().vertex_count(), 101u * 101u);
  EXPECT_TRUE(binary.value() == text.value());
  EXPECT_EQ(binary.value().positions[2], (Vec3f{1, 1, 0}));
}

// -------------------------------------------------------------------- failures

std::string tetra_with(const std::string& from, const std::string& to) {
  return testing_util::replace_once(kTetraAscii, from, to);
}

TEST(StlReaderErrors, AsciiProblemsAreNamed) {
  expect_rejected(parse(tetra_with("endsolid tetra made by hand\n", "")),
                  "the file ends before 'endsolid'");
  expect_rejected(parse(tetra_with("vertex 0 1 0\n      vertex 1 0 0\n    endloop",
                                   "vertex 0 1 0\n      vertex 1 0 0\n      vertex 2 2 2\n"
                                   "    endloop")),
                  "line 7: expected 'endloop', found 'vertex'");
  expect_rejected(parse(tetra_with("vertex 0 1 0", "vertex 0 one 0")),
                  "line 5: expected a vertex coordinate, found 'one'");
  expect_rejected(parse(tetra_with("vertex 0 1 0", "vertex 0 inf 0")),
                  "line 5: non-finite vertex coordinate");
  expect_rejected(parse(tetra_with("  facet normal 0 -1 0", "  face normal 0 -1 0")),
                  "line 9: expected 'facet' or 'endsolid', found 'face'");
  expect_rejected(parse(tetra_with("outer loop", "outer ring")),
                  "line 3: expected 'loop', found 'ring'");
  expect_rejected(parse(std::string("solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2")),
                  "expected a vertex coordinate, found the end of the file");
  expect_rejected(parse(std::string("solid x\n\0", 9)), "NUL byte");
}

TEST(StlReaderErrors, BinaryNonFiniteCoordinatesAreRejected) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity()}) {
    std::vector<Facet> facets = kTetra;
    facets[2].corners[1][2] = bad;
    expect_rejected(parse(binary_stl(facets)),
                    "byte 184: facet 3 of 4 has a non-finite coordinate");
  }
}

TEST(StlReaderErrors, EveryTruncationOfABinaryFileIsRejected) {
  Bytes full = binary_stl(kTetra);
  for (size_t length = 0; length < full.size(); ++length) {
    Bytes cut(full.begin(), full.begin() + static_cast<ptrdiff_t>(length));
    EXPECT_FALSE(parse(cut).is_ok()) << "length " << length;
  }
}

TEST(StlReaderErrors, EveryTruncationOfAnAsciiFileIsRejected) {
  const std::string full = kTetraAscii;
  const size_t end = full.find("endsolid");
  for (size_t length = 0; length < end + 8; ++length) {
    EXPECT_FALSE(parse(full.substr(0, length)).is_ok()) << "length " << length;
  }
  EXPECT_TRUE(parse(full.substr(0, end + 8)).is_ok());  // "endsolid" without a name
}

}  // namespace
}  // namespace lodbake
