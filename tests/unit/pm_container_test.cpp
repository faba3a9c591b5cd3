// End to end: a progressive mesh recorded by the QEM engine, stored as BASE +
// VSPL in a container, read back and replayed, gives the input again. The
// format tests (vspl_section_test) build their records by hand; these check
// what the engine really records: boundary splits missing either wing, real
// meshes with holes, per-vertex normals and texture coordinates, and the
// quantized encoding, through the same calls lodbake-simplify --pm and
// lodbake-inspect use.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/section_validation.h"
#include "formats/sections/vspl.h"
#include "formats/support/quantization.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "simplify_test_meshes.h"

namespace lodbake {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A wavy open grid (a height field, so it has a boundary) with the analytic
// per-vertex normal and texture coordinates (u, v) in [0, 1].
TriangleMesh wavy_grid(int cells) {
  TriangleMesh mesh;
  mesh.normals = {AttributeBinding::kPerVertex, 3, {}, {}};
  mesh.texcoords = {AttributeBinding::kPerVertex, 2, {}, {}};
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const double u = static_cast<double>(i) / cells;
      const double v = static_cast<double>(j) / cells;
      const double z = 0.1 * std::sin(2 * kPi * u) * std::cos(3 * kPi * v);
      const double dzdu = 0.2 * kPi * std::cos(2 * kPi * u) * std::cos(3 * kPi * v);
      const double dzdv = -0.3 * kPi * std::sin(2 * kPi * u) * std::sin(3 * kPi * v);
      const double len = std::sqrt(dzdu * dzdu + dzdv * dzdv + 1);
      mesh.positions.push_back(
          {static_cast<float>(u), static_cast<float>(v), static_cast<float>(z)});
      mesh.normals.values.insert(mesh.normals.values.end(),
                                 {static_cast<float>(-dzdu / len), static_cast<float>(-dzdv / len),
                                  static_cast<float>(1 / len)});
      mesh.texcoords.values.insert(mesh.texcoords.values.end(),
                                   {static_cast<float>(u), static_cast<float>(v)});
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

// A closed UV sphere: poles plus rings, normals = positions, texture
// coordinates from longitude and latitude (per vertex, so no seam vertices).
TriangleMesh uv_sphere(int rings, int segments) {
  TriangleMesh mesh;
  mesh.normals = {AttributeBinding::kPerVertex, 3, {}, {}};
  mesh.texcoords = {AttributeBinding::kPerVertex, 2, {}, {}};
  auto add = [&](double theta, double phi) {
    const Vec3f p{static_cast<float>(std::sin(theta) * std::cos(phi)),
                  static_cast<float>(std::sin(theta) * std::sin(phi)),
                  static_cast<float>(std::cos(theta))};
    mesh.positions.push_back(p);
    mesh.normals.values.insert(mesh.normals.values.end(), p.begin(), p.end());
    mesh.texcoords.values.insert(mesh.texcoords.values.end(), {static_cast<float>(phi / (2 * kPi)),
                                                               static_cast<float>(theta / kPi)});
  };
  add(0, 0);
  for (int r = 1; r < rings; ++r) {
    for (int s = 0; s < segments; ++s)
      add(kPi * r / rings, 2 * kPi * s / segments);
  }
  add(kPi, 0);
  const uint32_t south = static_cast<uint32_t>(mesh.positions.size() - 1);
  const auto ring = [segments](int r, int s) {
    return static_cast<uint32_t>(1 + (r - 1) * segments + (s % segments));
  };
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
    mesh.triangles.push_back({south, ring(rings - 1, s + 1), ring(rings - 1, s)});
  }
  for (int r = 1; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      mesh.triangles.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      mesh.triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  }
  return mesh;
}

// Edges with one incident triangle.
size_t boundary_edges(const TriangleMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> count;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      ++count[std::minmax(t[k], t[(k + 1) % 3])];
  }
  size_t boundary = 0;
  for (const auto& [edge, n] : count)
    boundary += n == 1;
  return boundary;
}

ProgressiveMesh record(const TriangleMesh& mesh, double ratio, Placement placement) {
  SimplifyOptions options;
  options.record_pm = true;
  options.target_ratio = ratio;
  options.placement = placement;
  Result<SimplifyResult> result = simplify(mesh, options);
  EXPECT_TRUE(result.is_ok()) << result.status().message();
  if (!result.is_ok() || !result.value().pm) return ProgressiveMesh();
  return *std::move(result).value().pm;
}

// BASE + VSPL in a container, as lodbake-simplify --pm writes it (META is
// not needed here).
Bytes pm_container(const ProgressiveMesh& pm, bool quantize, int bits) {
  const Bytes base = encode_base(pm.base, {quantize, bits}).value();
  Result<Bytes> vspl = encode_vspl(pm, {quantize, bits});
  EXPECT_TRUE(vspl.is_ok()) << vspl.status().message();
  ContainerWriter writer;
  EXPECT_TRUE(writer.add_section(kBaseTag, base, true).is_ok());
  EXPECT_TRUE(writer.add_section(kVsplTag, vspl.is_ok() ? vspl.value() : Bytes(), true).is_ok());
  return writer.finish().value();
}

// Reads the container back: it validates clean, and BASE + VSPL decode.
ProgressiveMesh read_pm(const Bytes& file) {
  Result<Container> container = read_container(file.data(), file.size());
  EXPECT_TRUE(container.is_ok()) << container.status().message();
  if (!container.is_ok()) return ProgressiveMesh();
  for (const SectionFinding& finding : validate_sections(container.value()))
    ADD_FAILURE() << finding.tag << ": " << finding.message;
  Result<const Section*> base = container.value().require(kBaseTag);
  Result<const Section*> vspl = container.value().require(kVsplTag);
  EXPECT_TRUE(base.is_ok() && vspl.is_ok());
  if (!base.is_ok() || !vspl.is_ok()) return ProgressiveMesh();
  Result<ProgressiveMesh> pm = decode_progressive_mesh(base.value()->data, base.value()->size,
                                                       vspl.value()->data, vspl.value()->size);
  EXPECT_TRUE(pm.is_ok()) << pm.status().message();
  return pm.is_ok() ? std::move(pm).value() : ProgressiveMesh();
}

// The fully refined PM renumbered to the input's vertex ids.
TriangleMesh replay_to_input(const ProgressiveMesh& pm) {
  Result<TriangleMesh> full = mesh_at_lod(pm, pm.full_vertex_count());
  EXPECT_TRUE(full.is_ok()) << full.status().message();
  if (!full.is_ok()) return TriangleMesh();
  Result<TriangleMesh> mapped = map_to_input(pm, full.value());
  EXPECT_TRUE(mapped.is_ok()) << mapped.status().message();
  return mapped.is_ok() ? std::move(mapped).value() : TriangleMesh();
}

TEST(PmContainer, AttributesSurviveBaseAndVspl) {
  struct Case {
    const char* name;
    TriangleMesh mesh;
    Placement placement;
  };
  const Case cases[] = {{"grid, half", wavy_grid(40), Placement::kHalf},
                        {"grid, optimal", wavy_grid(40), Placement::kOptimal},
                        {"sphere, half", uv_sphere(24, 40), Placement::kHalf}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const ProgressiveMesh pm = record(c.mesh, 0.05, c.placement);
    ASSERT_GT(pm.splits.size(), c.mesh.positions.size() / 2);
    ASSERT_EQ(pm.normals.value_count(), c.mesh.positions.size());
    ASSERT_EQ(pm.texcoords.value_count(), c.mesh.positions.size());

    const ProgressiveMesh back = read_pm(pm_container(pm, false, 16));
    EXPECT_TRUE(back == pm);
    EXPECT_EQ(back.normals, pm.normals);
    EXPECT_EQ(back.texcoords, pm.texcoords);

    // Full refinement is the input, attributes included.
    const TriangleMesh full = replay_to_input(back);
    EXPECT_EQ(full.positions, c.mesh.positions);
    EXPECT_EQ(full.normals, c.mesh.normals);
    EXPECT_EQ(full.texcoords, c.mesh.texcoords);
    EXPECT_TRUE(same_oriented_triangles(full, c.mesh));

    // Every LoD carries the attributes of the vertices it has (the replay
    // copies them), and its base LoD is BASE.
    const size_t mid = back.base.vertex_count() + back.splits.size() / 3;
    Result<TriangleMesh> at_mid = mesh_at_lod(back, mid);
    ASSERT_TRUE(at_mid.is_ok()) << at_mid.status().message();
    ASSERT_EQ(at_mid.value().normals.value_count(), mid);
    EXPECT_TRUE(std::equal(at_mid.value().normals.values.begin(),
                           at_mid.value().normals.values.end(), back.normals.values.begin()));
    ASSERT_EQ(at_mid.value().texcoords.value_count(), mid);
    EXPECT_TRUE(std::equal(at_mid.value().texcoords.values.begin(),
                           at_mid.value().texcoords.values.end(), back.texcoords.values.begin()));
    Result<TriangleMesh> coarsest = mesh_at_lod(back, back.base.vertex_count());
    ASSERT_TRUE(coarsest.is_ok());
    EXPECT_EQ(coarsest.value(), back.base);

    // Quantized positions: the attributes stay exact, the topology too.
    const ProgressiveMesh quantized = read_pm(pm_container(pm, true, 14));
    EXPECT_EQ(quantized.normals, pm.normals);
    EXPECT_EQ(quantized.texcoords, pm.texcoords);
    const TriangleMesh quantized_full = replay_to_input(quantized);
    EXPECT_EQ(quantized_full.normals, c.mesh.normals);
    EXPECT_TRUE(same_oriented_triangles(quantized_full, c.mesh));
  }
}

class PmContainerOnSharedMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(PmContainerOnSharedMesh, BaseAndVsplReplayToTheInput) {
  TriangleMesh input = load_clean_mesh(GetParam());
  ASSERT_GT(input.triangles.size(), 0u);
  // A PM records per-vertex attributes only; these files have none or
  // per-corner ones, and this test is about connectivity and positions.
  if (input.normals.binding == AttributeBinding::kPerCorner) input.normals = MeshAttribute();
  if (input.texcoords.binding == AttributeBinding::kPerCorner) input.texcoords = MeshAttribute();
  const ProgressiveMesh pm = record(input, 0.05, Placement::kHalf);
  ASSERT_EQ(pm.full_vertex_count(), input.positions.size());
  // At most 5 % of the triangles, or as far as legal collapses go (the
  // holes of elephant-with-holes stop the engine earlier).
  EXPECT_LT(pm.base.triangle_count(), input.triangles.size() / 4);

  // Boundary splits: the engine records both kinds (left or right wing
  // missing) on meshes with a boundary, none on closed ones.
  size_t no_left = 0;
  size_t no_right = 0;
  for (const VertexSplit& s : pm.splits) {
    no_left += s.vl == kNoVertex;
    no_right += s.vr == kNoVertex;
  }
  if (boundary_edges(input) == 0) {
    EXPECT_EQ(no_left + no_right, 0u);
  } else {
    EXPECT_GT(no_left, 0u);
    EXPECT_GT(no_right, 0u);
  }

  const ProgressiveMesh back = read_pm(pm_container(pm, false, 16));
  ASSERT_TRUE(back == pm);
  const TriangleMesh full = replay_to_input(back);
  EXPECT_EQ(full.positions, input.positions);
  EXPECT_TRUE(same_oriented_triangles(full, input));

  // Quantized: the same topology, positions within the documented bound.
  const ProgressiveMesh quantized = read_pm(pm_container(pm, true, 16));
  ASSERT_EQ(quantized.splits.size(), pm.splits.size());
  EXPECT_EQ(quantized.base.triangles, pm.base.triangles);
  EXPECT_EQ(quantized.input_vertex, pm.input_vertex);
  const TriangleMesh quantized_full = replay_to_input(quantized);
  EXPECT_TRUE(same_oriented_triangles(quantized_full, input));
  ASSERT_EQ(quantized_full.positions.size(), input.positions.size());
  Vec3f lo, hi;
  bounding_box(input.positions, &lo, &hi);
  // BASE and VSPL each quantize over the box of what they store, which lies
  // inside the input's box.
  const double bound = quantization_error_bound(lo, hi, 16);
  double worst = 0;
  for (size_t v = 0; v < input.positions.size(); ++v) {
    for (int a = 0; a < 3; ++a) {
      worst = std::max(
          worst, std::fabs(double{quantized_full.positions[v][a]} - double{input.positions[v][a]}));
    }
  }
  EXPECT_LE(worst, bound);
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, PmContainerOnSharedMesh,
                         ::testing::Values("cgal_mushroom.off", "igl_camelhead.off",
                                           "stanford_bun_zipper.ply",
                                           "cgal_elephant-with-holes.off", "cgal_elephant.off"));

}  // namespace
}  // namespace lodbake
