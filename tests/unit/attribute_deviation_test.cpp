// measure_scene_deviation: known UV shifts and normal rotations come back
// exactly, world space makes a node transform and its baked form agree,
// samples look only at their own material, results do not depend on runs
// or threads, and real assets (and gltfpack's output of them) measure.
#include "lib/metrics/attribute_deviation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "lib/scene/scene_from_mesh.h"
#include "lib/scene/scene_io.h"
#include "lib/scene/scene_lods.h"

namespace lodbake {
namespace {

const std::string kAssets = std::string(LODBAKE_TEST_SHARED_DATA) + "/assets/";
constexpr double kPi = 3.14159265358979323846;

// A bumpy n x n heightfield over [0, 1]^2, z = h(x, y), with UV (x, y) and
// its analytic unit normal, as POSITION, NORMAL and TEXCOORD_0 streams.
struct Grid {
  std::vector<float> positions, normals, uvs;
  std::vector<uint32_t> indices;
};

double height(double x, double y) {
  return 0.1 * std::sin(3 * x) * std::cos(2 * y);
}

Grid make_grid(int n) {
  Grid g;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
      const double hx = 0.3 * std::cos(3 * x) * std::cos(2 * y);
      const double hy = -0.2 * std::sin(3 * x) * std::sin(2 * y);
      const double len = std::sqrt(hx * hx + hy * hy + 1);
      g.positions.insert(g.positions.end(), {static_cast<float>(x), static_cast<float>(y),
                                             static_cast<float>(height(x, y))});
      g.normals.insert(g.normals.end(),
                       {static_cast<float>(-hx / len), static_cast<float>(-hy / len),
                        static_cast<float>(1 / len)});
      g.uvs.insert(g.uvs.end(), {static_cast<float>(x), static_cast<float>(y)});
    }
  }
  const uint32_t row = static_cast<uint32_t>(n + 1);
  for (uint32_t j = 0; j < static_cast<uint32_t>(n); ++j) {
    for (uint32_t i = 0; i < static_cast<uint32_t>(n); ++i) {
      const uint32_t v = j * row + i;
      g.indices.insert(g.indices.end(), {v, v + 1, v + row + 1, v, v + row + 1, v + row});
    }
  }
  return g;
}

ScenePrimitive primitive_of(const Grid& g, int32_t material = -1) {
  ScenePrimitive p;
  p.material = material;
  p.indices = g.indices;
  const uint32_t count = static_cast<uint32_t>(g.positions.size() / 3);
  p.attributes.push_back({"NORMAL", float_accessor(g.normals.data(), count, 3)});
  p.attributes.push_back({"POSITION", float_accessor(g.positions.data(), count, 3)});
  p.attributes.push_back({"TEXCOORD_0", float_accessor(g.uvs.data(), count, 2)});
  return p;
}

Scene scene_of(const Grid& g) {
  return scene_of_mesh("grid", {primitive_of(g)});
}

DeviationOptions small_options() {
  DeviationOptions options;
  options.area_samples = 20000;
  options.threads = 1;
  return options;
}

SceneDeviation measure_ok(const Scene& a, const Scene& b,
                          const DeviationOptions& options = small_options()) {
  Result<SceneDeviation> d = measure_scene_deviation(a, b, options);
  EXPECT_TRUE(d.is_ok()) << d.status().message();
  return d.is_ok() ? d.value() : SceneDeviation{};
}

TEST(AttributeDeviation, IdenticalScenesAreAtZero) {
  const Scene s = scene_of(make_grid(12));
  const SceneDeviation d = measure_ok(s, s);
  ASSERT_EQ(d.primitives.size(), 1u);
  EXPECT_GT(d.distance.samples, 19000u);
  EXPECT_EQ(d.uv.samples, d.distance.samples);
  EXPECT_EQ(d.normal_degrees.samples, d.distance.samples);
  EXPECT_LT(d.hausdorff, 1e-12);
  EXPECT_LT(d.uv.p95, 1e-12);
  EXPECT_LT(d.normal_degrees.p95, 1e-5);
  EXPECT_GT(d.diagonal, 1.4);
}

TEST(AttributeDeviation, ShiftedUvsGiveTheShift) {
  Grid g = make_grid(12);
  const Scene input = scene_of(g);
  for (size_t i = 0; i < g.uvs.size(); i += 2) {
    g.uvs[i] += 0.125f;
    g.uvs[i + 1] -= 0.25f;
  }
  const SceneDeviation d = measure_ok(input, scene_of(g));
  const double shift = std::sqrt(0.125 * 0.125 + 0.25 * 0.25);
  EXPECT_NEAR(d.uv.mean, shift, 1e-7);
  EXPECT_NEAR(d.uv.p95, shift, 1e-7);
  EXPECT_NEAR(d.primitives[0].uv.mean, shift, 1e-7);
  EXPECT_LT(d.hausdorff, 1e-12);
  EXPECT_LT(d.normal_degrees.p95, 1e-5);
}

TEST(AttributeDeviation, RotatedNormalsGiveTheAngle) {
  Grid g = make_grid(12);
  // Every normal turned by 20 degrees about the x axis (so each stays unit
  // and the interpolated normals turn by the same angle).
  for (float& n : g.normals)
    n = 0;
  const Scene flat_normals = [&] {
    Grid up = g;
    for (size_t i = 0; i < up.normals.size(); i += 3)
      up.normals[i + 2] = 1;
    return scene_of(up);
  }();
  const double a = 20 * kPi / 180;
  for (size_t i = 0; i < g.normals.size(); i += 3) {
    g.normals[i + 1] = static_cast<float>(-std::sin(a));
    g.normals[i + 2] = static_cast<float>(std::cos(a));
  }
  const SceneDeviation d = measure_ok(flat_normals, scene_of(g));
  EXPECT_NEAR(d.normal_degrees.mean, 20.0, 1e-4);
  EXPECT_NEAR(d.normal_degrees.p95, 20.0, 1e-4);
  EXPECT_LT(d.uv.p95, 1e-12);
}

TEST(AttributeDeviation, NodeTransformEqualsItsBakedForm) {
  const Grid g = make_grid(16);
  Scene output = scene_of(g);
  SceneNode& node = output.nodes[0];
  node.translation = std::array<double, 3>{1, -2, 3};
  const double half = 0.5 * (60 * kPi / 180);
  node.rotation = std::array<double, 4>{0, 0, std::sin(half), std::cos(half)};  // 60 deg about z
  node.scale = std::array<double, 3>{2, 0.5, 3};
  // The input: the same surface with the transform in its positions, its
  // normals those of the scaled heightfield turned by the rotation.
  Grid baked = g;
  const double c = std::cos(2 * half), s = std::sin(2 * half);
  for (size_t i = 0; i < g.positions.size(); i += 3) {
    const double x = 2 * g.positions[i], y = 0.5 * g.positions[i + 1], z = 3 * g.positions[i + 2];
    baked.positions[i] = static_cast<float>(c * x - s * y + 1);
    baked.positions[i + 1] = static_cast<float>(s * x + c * y - 2);
    baked.positions[i + 2] = static_cast<float>(z + 3);
    // A normal of z = 3 h(x / 2, y / 0.5) before the rotation.
    const double nx = g.normals[i] * 3 / 2, ny = g.normals[i + 1] * 3 / 0.5, nz = g.normals[i + 2];
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    baked.normals[i] = static_cast<float>((c * nx - s * ny) / len);
    baked.normals[i + 1] = static_cast<float>((s * nx + c * ny) / len);
    baked.normals[i + 2] = static_cast<float>(nz / len);
  }
  const SceneDeviation d = measure_ok(scene_of(baked), output);
  EXPECT_LT(d.hausdorff_relative, 1e-6);
  EXPECT_LT(d.uv.p95, 1e-5);
  EXPECT_LT(d.normal_degrees.p95, 1e-3);
  EXPECT_GT(d.diagonal, 2.0);  // the world-space extent, not the unit square's

  // Without the transform the output is elsewhere: the distance shows it.
  Scene untransformed = output;
  untransformed.nodes[0].translation.reset();
  untransformed.nodes[0].rotation.reset();
  untransformed.nodes[0].scale.reset();
  EXPECT_GT(measure_ok(scene_of(baked), untransformed).hausdorff_relative, 0.1);
}

TEST(AttributeDeviation, EveryInstanceIsSampled) {
  // One mesh used by two nodes, one of them moved: against a scene with the
  // first node only, the second copy is far from every output point.
  Scene two = scene_of(make_grid(8));
  SceneNode copy = two.nodes[0];
  copy.translation = std::array<double, 3>{0, 0, 5};
  two.nodes.push_back(copy);
  two.scenes[0].nodes.push_back(1);
  const SceneDeviation d = measure_ok(two, scene_of(make_grid(8)));
  EXPECT_NEAR(d.hausdorff, 5.0, 0.2);
  EXPECT_GT(d.distance.mean, 2.0);
  EXPECT_EQ(d.primitives.size(), 1u);  // both instances in the mesh's one primitive
}

TEST(AttributeDeviation, SamplesCompareWithTheirOwnMaterial) {
  // Two primitives with different materials over the same surface. Input:
  // A at UV (x, y), B at (x + 0.5, y). Output: A shifted by 0.45, B by 0.1.
  // Matched by material: 0.45 and 0.1; over all triangles, the nearer UVs
  // would have given 0.05 and 0.1 instead.
  const Grid g = make_grid(10);
  auto shifted = [&](double du) {
    Grid s = g;
    for (size_t i = 0; i < s.uvs.size(); i += 2)
      s.uvs[i] = static_cast<float>(s.uvs[i] + du);
    return s;
  };
  auto two_materials = [&](const Grid& a, const Grid& b) {
    Scene s = scene_of_mesh("two", {primitive_of(a, 0), primitive_of(b, 1)});
    s.materials = SceneJson::array({{{"name", "A"}}, {{"name", "B"}}});
    return s;
  };
  const Scene input = two_materials(shifted(0), shifted(0.5));
  Scene output = two_materials(shifted(0.45), shifted(0.6));
  // The output lists its materials the other way round: matched by JSON,
  // not by index.
  std::swap(output.meshes[0].primitives[0], output.meshes[0].primitives[1]);
  output.meshes[0].primitives[0].material = 0;
  output.meshes[0].primitives[1].material = 1;
  output.materials = SceneJson::array({{{"name", "B"}}, {{"name", "A"}}});
  const SceneDeviation d = measure_ok(input, output);
  ASSERT_EQ(d.primitives.size(), 2u);
  EXPECT_NEAR(d.primitives[0].uv.mean, 0.45, 1e-6);
  EXPECT_NEAR(d.primitives[1].uv.mean, 0.1, 1e-6);
  EXPECT_NEAR(d.primitives[0].uv.p95, 0.45, 1e-6);
  EXPECT_NEAR(d.primitives[1].uv.p95, 0.1, 1e-6);

  // Numbers written at another length are the same float: still matched.
  Scene shortened = output;
  shortened.materials[0]["f"] = 0.0405062996;
  shortened.materials[1]["f"] = 0.04050629958510399;
  Scene long_input = input;
  long_input.materials[0]["f"] = 0.04050629958510399;
  long_input.materials[1]["f"] = 0.04050629958510399;
  EXPECT_NEAR(measure_ok(long_input, shortened).primitives[1].uv.mean, 0.1, 1e-6);

  // A material the output does not have: compared with every triangle.
  Scene renamed = output;
  renamed.materials = SceneJson::array({{{"name", "C"}}, {{"name", "D"}}});
  const SceneDeviation any = measure_ok(input, renamed);
  EXPECT_NEAR(any.primitives[0].uv.mean, 0.45, 1e-6);  // 0.45 and 0.6 away: the nearer
  EXPECT_NEAR(any.primitives[1].uv.mean, 0.05, 1e-6);  // 0.05 and 0.1 away
}

TEST(AttributeDeviation, MissingStreamsGiveNoSamples) {
  const Grid g = make_grid(8);
  Scene bare = scene_of(g);
  auto& attributes = bare.meshes[0].primitives[0].attributes;
  attributes.erase(attributes.begin());  // NORMAL
  attributes.pop_back();                 // TEXCOORD_0
  const Scene full = scene_of(g);
  const SceneDeviation from_bare = measure_ok(bare, full);
  EXPECT_GT(from_bare.distance.samples, 0u);
  EXPECT_EQ(from_bare.uv.samples, 0u);
  EXPECT_EQ(from_bare.normal_degrees.samples, 0u);
  const SceneDeviation to_bare = measure_ok(full, bare);
  EXPECT_EQ(to_bare.uv.samples, 0u);
  EXPECT_EQ(to_bare.normal_degrees.samples, 0u);
  EXPECT_EQ(to_bare.uv.p95, 0.0);
}

TEST(AttributeDeviation, PercentileIsTheNearestRank) {
  // UV deviation equal to x on a flat grid of 20 x 20 squares: with one
  // area sample per (equal) triangle the 95th percentile is the
  // ceil(0.95 n)-th smallest of the centroids' x.
  Grid g = make_grid(20);
  for (size_t i = 0; i < g.positions.size(); i += 3) {
    g.positions[i + 2] = 0;
    g.normals[i] = g.normals[i + 1] = 0;
    g.normals[i + 2] = 1;
  }
  const Scene input = scene_of(g);
  for (size_t i = 0; i < g.uvs.size(); i += 2)
    g.uvs[i + 1] += g.uvs[i];  // v' - v = x
  DeviationOptions options = small_options();
  options.area_samples = 800;  // one centroid per triangle
  const SceneDeviation d = measure_ok(input, scene_of(g), options);
  ASSERT_EQ(d.uv.samples, 800u);
  // Centroid x of column i's two triangles: (i + 1/3) / 20 and (i + 2/3) / 20;
  // sorted, rank 760 of 800 is column 18's upper one.
  EXPECT_NEAR(d.uv.p95, (18 + 2.0 / 3) / 20, 1e-6);
  EXPECT_NEAR(d.uv.mean, 0.5, 1e-6);
}

TEST(AttributeDeviation, RejectsBadInput) {
  const Scene good = scene_of(make_grid(4));
  Grid nan = make_grid(4);
  nan.positions[4] = std::numeric_limits<float>::quiet_NaN();
  Result<SceneDeviation> d = measure_scene_deviation(scene_of(nan), good, small_options());
  ASSERT_FALSE(d.is_ok());
  EXPECT_EQ(d.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(d.status().message().find("non-finite"), std::string::npos);

  Scene out_of_range = good;
  out_of_range.meshes[0].primitives[0].indices->back() = 1000;
  d = measure_scene_deviation(good, out_of_range, small_options());
  ASSERT_FALSE(d.is_ok());
  EXPECT_EQ(d.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_NE(d.status().message().find("out of range"), std::string::npos);

  Scene empty = good;
  empty.meshes[0].primitives[0].indices->clear();
  d = measure_scene_deviation(good, empty, small_options());
  ASSERT_FALSE(d.is_ok());
  EXPECT_EQ(d.status().kind(), ErrorKind::kInvalidInput);

  Scene cycle = good;
  cycle.nodes[0].children = {0};
  d = measure_scene_deviation(cycle, good, small_options());
  ASSERT_FALSE(d.is_ok());
  EXPECT_EQ(d.status().kind(), ErrorKind::kInvalidInput);
}

Scene read_asset(const std::string& path) {
  ImportReport report;
  Result<Scene> scene = read_scene_file(path, {}, &report);
  EXPECT_TRUE(scene.is_ok()) << path << ": " << scene.status().message();
  return scene.is_ok() ? std::move(scene).value() : Scene();
}

Scene simplified(const Scene& scene, double ratio) {
  SceneLodOptions options;
  options.ratios = {ratio};
  Result<SceneLods> lods = simplify_scene(scene, options);
  EXPECT_TRUE(lods.is_ok()) << lods.status().message();
  return lods.is_ok() ? lods.value().levels[0] : Scene();
}

bool bit_equal(const DeviationStats& a, const DeviationStats& b) {
  return std::memcmp(&a.mean, &b.mean, sizeof(double)) == 0 &&
         std::memcmp(&a.p95, &b.p95, sizeof(double)) == 0 && a.samples == b.samples;
}

bool bit_equal(const SceneDeviation& a, const SceneDeviation& b) {
  if (a.primitives.size() != b.primitives.size()) return false;
  for (size_t i = 0; i < a.primitives.size(); ++i) {
    const PrimitiveDeviation &p = a.primitives[i], &q = b.primitives[i];
    if (!bit_equal(p.distance, q.distance) || !bit_equal(p.uv, q.uv) ||
        !bit_equal(p.normal_degrees, q.normal_degrees) ||
        std::memcmp(&p.max_distance, &q.max_distance, sizeof(double)) != 0)
      return false;
  }
  return bit_equal(a.distance, b.distance) && bit_equal(a.uv, b.uv) &&
         bit_equal(a.normal_degrees, b.normal_degrees) &&
         std::memcmp(&a.hausdorff, &b.hausdorff, sizeof(double)) == 0 &&
         std::memcmp(&a.diagonal, &b.diagonal, sizeof(double)) == 0;
}

TEST(AttributeDeviation, DeterministicAcrossRunsAndThreads) {
  const Scene duck = read_asset(kAssets + "Duck/Duck.gltf");
  const Scene half = simplified(duck, 0.5);
  DeviationOptions one = small_options();
  DeviationOptions two = one;
  two.threads = 2;
  DeviationOptions seven = one;
  seven.threads = 7;
  DeviationOptions every_core = one;
  every_core.threads = 0;
  const SceneDeviation a = measure_ok(duck, half, one);
  EXPECT_TRUE(bit_equal(a, measure_ok(duck, half, one)));
  EXPECT_TRUE(bit_equal(a, measure_ok(duck, half, two)));
  EXPECT_TRUE(bit_equal(a, measure_ok(duck, half, seven)));
  EXPECT_TRUE(bit_equal(a, measure_ok(duck, half, every_core)));
}

TEST(AttributeDeviation, RealAssetsAgainstThemselvesAndTheirSimplification) {
  for (const char* name : {"Duck/Duck.gltf", "CesiumMilkTruck/CesiumMilkTruck.gltf",
                           "SpheresScaledInstances/spheres_scaled_instances.gltf",
                           "Lantern/Lantern.gltf", "CesiumMan/CesiumMan.glb"}) {
    SCOPED_TRACE(name);
    const Scene scene = read_asset(kAssets + name);
    const SceneDeviation self = measure_ok(scene, scene);
    EXPECT_LT(self.hausdorff_relative, 1e-9);
    EXPECT_LT(self.uv.p95, 1e-9);
    EXPECT_LT(self.normal_degrees.p95, 1e-4);
    EXPECT_GT(self.uv.samples + self.normal_degrees.samples, 0u);
    const SceneDeviation half = measure_ok(scene, simplified(scene, 0.5));
    EXPECT_TRUE(std::isfinite(half.hausdorff) && std::isfinite(half.uv.mean) &&
                std::isfinite(half.normal_degrees.mean));
    EXPECT_GT(half.hausdorff, 0.0);
    EXPECT_GT(half.distance.mean, 0.0);
    EXPECT_LT(half.hausdorff_relative, 0.2);
  }
}

// gltfpack (npm, from the npm-deps target) merges meshes and bakes node
// transforms into positions: uncompressed and unsimplified, its output is
// the same surface with the same attributes in world space.
class Gltfpack : public testing::Test {
 protected:
  void SetUp() override {
    cli_ = std::string(LODBAKE_TEST_NPM_DIR) + "/node_modules/gltfpack/cli.js";
    if (!std::filesystem::exists(cli_) || std::system("node --version > /dev/null 2>&1") != 0)
      GTEST_SKIP() << "gltfpack is not installed (" << cli_ << "): build the npm-deps target";
  }
  Scene pack(const std::string& input, const std::string& ratio) {
    const std::string out = testing::TempDir() + "/attribute_deviation_" +
                            std::filesystem::path(input).stem().string() + "_" + ratio + ".glb";
    const std::string command =
        "node " + cli_ + " -i " + input + " -o " + out + " -noq -si " + ratio + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return read_asset(out);
  }
  std::string cli_;
};

TEST_F(Gltfpack, UnsimplifiedOutputIsAtZero) {
  for (const char* name : {"Duck/Duck.gltf", "CesiumMilkTruck/CesiumMilkTruck.gltf",
                           "SpheresScaledInstances/spheres_scaled_instances.gltf",
                           "Lantern/Lantern.gltf", "SheenCloth/SheenCloth.glb"}) {
    SCOPED_TRACE(name);
    const Scene input = read_asset(kAssets + name);
    const SceneDeviation d = measure_ok(input, pack(kAssets + name, "1"));
    // gltfpack drops the UVs of an asset without textures (the spheres):
    // no UV to compare then.
    if (input.textures.is_array() && !input.textures.empty()) {
      EXPECT_GT(d.uv.samples, 0u);
    } else {
      EXPECT_EQ(d.uv.samples, 0u);
    }
    EXPECT_GT(d.normal_degrees.samples, 0u);
    EXPECT_LT(d.hausdorff_relative, 1e-5);
    EXPECT_LT(d.uv.p95, 1e-5);
    EXPECT_LT(d.normal_degrees.p95, 0.1);
  }
}

TEST_F(Gltfpack, SimplifiedOutputMeasures) {
  const std::string input = kAssets + "CesiumMilkTruck/CesiumMilkTruck.gltf";
  const SceneDeviation d = measure_ok(read_asset(input), pack(input, "0.5"));
  EXPECT_EQ(d.primitives.size(), 4u);
  EXPECT_GT(d.uv.samples, 0u);
  EXPECT_GT(d.normal_degrees.samples, 0u);
  EXPECT_GT(d.hausdorff, 0.0);
  EXPECT_LT(d.hausdorff_relative, 0.1);
  EXPECT_TRUE(std::isfinite(d.uv.p95) && std::isfinite(d.normal_degrees.p95));
}

}  // namespace
}  // namespace lodbake
