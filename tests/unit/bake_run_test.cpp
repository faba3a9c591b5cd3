// One input's steps (lib/bake/bake_run.h, bake_steps.h): the input is
// imported once per set of import options and shared by its steps, which run
// side by side; a failed step fails its input and skips package.
#include <gtest/gtest.h>

#include <filesystem>

#include "lib/bake/bake_run.h"
#include "lib/bake/bake_steps.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::env_or_fail;
using testing_util::read_bytes;

std::string mesh_path() {
  return env_or_fail("LODBAKE_SHARED_DATA") + "/meshes/cgal_mushroom.off";
}

Bytes bytes_of(const std::string& path) {
  return read_bytes(path);
}

TEST(InputMeshes, TheInputIsParsedOnceAndPreparedPerSetOfOptions) {
  const std::string kMesh = mesh_path();
  InputMeshes meshes;
  LoadOptions options;
  options.drop_unreferenced = true;
  LoadedMesh first;
  ASSERT_TRUE(meshes.load(kMesh, bytes_of(kMesh), options, &first).is_ok());
  ASSERT_GT(first.mesh.triangle_count(), 0u);
  // Later steps' bytes are never parsed: the first parse is shared.
  LoadedMesh second;
  ASSERT_TRUE(meshes.load(kMesh, Bytes{'x'}, options, &second).is_ok());
  EXPECT_EQ(second.mesh.positions, first.mesh.positions);
  EXPECT_EQ(second.mesh.triangles, first.mesh.triangles);
  EXPECT_EQ(second.sha256, first.sha256);
  // Other options prepare that parse again: --repair repairs it.
  EXPECT_FALSE(first.repair.has_value());
  options.repair = true;
  LoadedMesh repaired;
  ASSERT_TRUE(meshes.load(kMesh, Bytes{'x'}, options, &repaired).is_ok());
  EXPECT_TRUE(repaired.repair.has_value());
}

TEST(InputMeshes, TheSeamSplitIsOnlyAPreparationOfItsOwnWhereItSplits) {
  // spot has per-corner texture coordinates: split and unsplit differ.
  const std::string spot = env_or_fail("LODBAKE_SHARED_DATA") + "/meshes/c3d_spot.obj";
  InputMeshes meshes;
  LoadOptions options;
  LoadedMesh corners, split;
  ASSERT_TRUE(meshes.load(spot, bytes_of(spot), options, &corners).is_ok());
  options.per_vertex_attributes = true;
  ASSERT_TRUE(meshes.load(spot, Bytes{}, options, &split).is_ok());
  EXPECT_EQ(corners.seam_vertices, 0u);
  EXPECT_GT(split.seam_vertices, 0u);
  EXPECT_GT(split.mesh.positions.size(), corners.mesh.positions.size());
  // Each is what load_mesh_bytes() makes with the same options.
  LoadedMesh direct;
  ASSERT_TRUE(load_mesh_bytes(spot, bytes_of(spot), options, &direct).is_ok());
  EXPECT_EQ(direct.mesh.positions, split.mesh.positions);
  EXPECT_EQ(direct.mesh.triangles, split.mesh.triangles);
}

TEST(InputMeshes, AFailedImportFailsEveryStepThatAsks) {
  InputMeshes meshes;
  LoadOptions options;
  LoadedMesh loaded;
  Status first = meshes.load("broken.off", Bytes{'O', 'F', 'F', '\n', '9'}, options, &loaded);
  ASSERT_FALSE(first.is_ok());
  Status second = meshes.load("broken.off", bytes_of(mesh_path()), options, &loaded);
  EXPECT_EQ(second.kind(), first.kind());
  EXPECT_EQ(second.message(), first.message());
}

std::vector<InputPlan> plans_for(const std::string& input, const std::string& steps) {
  Result<Recipe> recipe =
      parse_recipe("/recipes/r.toml", "[inputs]\nglobs = [\"" + input + "\"]\n" + steps, {});
  EXPECT_TRUE(recipe.is_ok()) << recipe.status().message();
  Result<InputPlan> plan = plan_input(recipe.value(), input);
  EXPECT_TRUE(plan.is_ok()) << plan.status().message();
  return {plan.value()};
}

const char kSteps[] =
    "[steps.pack]\n[steps.hierarchy]\n[steps.fan]\n[steps.package]\nfrom = [\"pack\", \"fan\"]\n";

TEST(BakeInput, StepsSideBySideMakeTheSameFilesAsInTurn) {
  const std::string out = testing::TempDir() + "/bake_run_side_by_side";
  std::filesystem::remove_all(out);
  std::vector<InputPlan> plans = plans_for(mesh_path(), kSteps);
  BakeOptions options;
  options.out_dir = out + "/together";
  options.jobs = 2;
  std::vector<InputReport> together = run_bake(plans, options, {});
  ASSERT_EQ(together.size(), 1u);
  EXPECT_EQ(together[0].status, "ok");
  ASSERT_EQ(together[0].steps.size(), 4u);
  // Each step alone (--step), package last, in a folder of its own.
  options.out_dir = out + "/alone";
  options.jobs = 1;
  for (const char* step : {"pack", "hierarchy", "fan", "package"}) {
    options.only_step = step;
    std::vector<InputReport> alone = run_bake(plans, options, {});
    ASSERT_EQ(alone[0].status, "ok") << step;
  }
  for (size_t s = 0; s < together[0].steps.size(); ++s) {
    EXPECT_EQ(together[0].steps[s].step, plans[0].steps[s].step);
    for (const std::string& path : plans[0].steps[s].outputs) {
      EXPECT_EQ(bytes_of(output_path(out + "/together", path)),
                bytes_of(output_path(out + "/alone", path)))
          << path;
    }
  }
  std::filesystem::remove_all(out);
}

TEST(BakeInput, AFailedStepFailsItsInputAndSkipsPackage) {
  const std::string out = testing::TempDir() + "/bake_run_failed";
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  const std::string broken = out + "/broken.off";
  ASSERT_TRUE(write_file_atomic(broken, Bytes{'O', 'F', 'F', '\n', '9'}).is_ok());
  BakeOptions options;
  options.out_dir = out;
  std::vector<InputReport> reports = run_bake(plans_for(broken, kSteps), options, {});
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].status, "failed");
  ASSERT_EQ(reports[0].steps.size(), 4u);
  for (size_t s = 0; s < 3; ++s) {
    EXPECT_EQ(reports[0].steps[s].status, "failed") << reports[0].steps[s].step;
    EXPECT_EQ(reports[0].steps[s].error, reports[0].steps[0].error);
    EXPECT_EQ(reports[0].steps[s].error_kind, ErrorKind::kInvalidInput);
  }
  EXPECT_EQ(reports[0].steps[3].step, "package");
  EXPECT_EQ(reports[0].steps[3].status, "skipped");
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace lodbake
