// One input's steps (lib/bake/bake_run.h, bake_steps.h): the input is
// imported once per set of import options and shared by its steps, which run
// side by side; a failed step fails its input and skips package.
#include <gtest/gtest.h>

#include <filesystem>

#include "lib/bake/bake_run.h"
#include "lib/bake/bake_steps.h"
#include "lib/bake/strips_step.h"
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
  Result<std::shared_ptr<const LoadedMesh>> first = meshes.load(kMesh, bytes_of(kMesh), options);
  ASSERT_TRUE(first.is_ok());
  ASSERT_GT(first.value()->mesh.triangle_count(), 0u);
  // Later steps' bytes are never parsed: the first parse is shared, and so
  // is the mesh prepared with the same options.
  Result<std::shared_ptr<const LoadedMesh>> second = meshes.load(kMesh, Bytes{'x'}, options);
  ASSERT_TRUE(second.is_ok());
  EXPECT_EQ(second.value().get(), first.value().get());
  // Other options prepare that parse again: --repair repairs it.
  EXPECT_FALSE(first.value()->repair.has_value());
  options.repair = true;
  Result<std::shared_ptr<const LoadedMesh>> repaired = meshes.load(kMesh, Bytes{'x'}, options);
  ASSERT_TRUE(repaired.is_ok());
  EXPECT_TRUE(repaired.value()->repair.has_value());
  EXPECT_EQ(repaired.value()->sha256, first.value()->sha256);
}

TEST(InputMeshes, TheParseIsReleasedOnceEveryStepHasLoaded) {
  // Two steps: after both have loaded, a third load (one more than
  // planned) with new options parses the input again, from its bytes.
  const std::string kMesh = mesh_path();
  std::vector<StepPlan> steps(2);
  steps[0].step = "fan";
  steps[1].step = "hierarchy";
  InputMeshes meshes(steps);
  LoadOptions options;
  ASSERT_TRUE(meshes.load(kMesh, bytes_of(kMesh), options).is_ok());
  ASSERT_TRUE(meshes.load(kMesh, Bytes{'x'}, options).is_ok());
  options.repair = true;
  EXPECT_FALSE(meshes.load(kMesh, Bytes{'O', 'F', 'F', '\n', '9'}, options).is_ok());
  // Without a plan the parse is kept.
  InputMeshes kept;
  options.repair = false;
  ASSERT_TRUE(kept.load(kMesh, bytes_of(kMesh), options).is_ok());
  ASSERT_TRUE(kept.load(kMesh, Bytes{'x'}, options).is_ok());
  options.repair = true;
  EXPECT_TRUE(kept.load(kMesh, Bytes{'x'}, options).is_ok());
}

TEST(InputMeshes, TheSeamSplitIsOnlyAPreparationOfItsOwnWhereItSplits) {
  // spot has per-corner texture coordinates: split and unsplit differ.
  const std::string spot = env_or_fail("LODBAKE_SHARED_DATA") + "/meshes/c3d_spot.obj";
  InputMeshes meshes;
  LoadOptions options;
  Result<std::shared_ptr<const LoadedMesh>> corners = meshes.load(spot, bytes_of(spot), options);
  options.per_vertex_attributes = true;
  Result<std::shared_ptr<const LoadedMesh>> split = meshes.load(spot, Bytes{}, options);
  ASSERT_TRUE(corners.is_ok());
  ASSERT_TRUE(split.is_ok());
  EXPECT_EQ(corners.value()->seam_vertices, 0u);
  EXPECT_GT(split.value()->seam_vertices, 0u);
  EXPECT_GT(split.value()->mesh.positions.size(), corners.value()->mesh.positions.size());
  // Each is what load_mesh_bytes() makes with the same options.
  LoadedMesh direct;
  ASSERT_TRUE(load_mesh_bytes(spot, bytes_of(spot), options, &direct).is_ok());
  EXPECT_EQ(direct.mesh.positions, split.value()->mesh.positions);
  EXPECT_EQ(direct.mesh.triangles, split.value()->mesh.triangles);
}

TEST(InputMeshes, AFailedImportFailsEveryStepThatAsks) {
  InputMeshes meshes;
  LoadOptions options;
  Result<std::shared_ptr<const LoadedMesh>> first =
      meshes.load("broken.off", Bytes{'O', 'F', 'F', '\n', '9'}, options);
  ASSERT_FALSE(first.is_ok());
  Result<std::shared_ptr<const LoadedMesh>> second =
      meshes.load("broken.off", bytes_of(mesh_path()), options);
  EXPECT_EQ(second.status().kind(), first.status().kind());
  EXPECT_EQ(second.status().message(), first.status().message());
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

TEST(InputMeshes, OneSimplificationServesEveryStepAskingWithTheSameOptions) {
  const std::string kMesh = mesh_path();
  std::vector<InputPlan> plans = plans_for(kMesh, "[steps.simplify]\n[steps.strips]\n");
  InputMeshes meshes(plans[0].steps);
  LoadOptions load;
  load.drop_unreferenced = true;
  load.per_vertex_attributes = true;
  SimplifyOptions options = strips_pm_options(0);
  Result<std::shared_ptr<const LoadedMesh>> loaded = meshes.load(kMesh, bytes_of(kMesh), load);
  ASSERT_TRUE(loaded.is_ok());
  const TriangleMesh& mesh = loaded.value()->mesh;
  Result<std::shared_ptr<const SimplifyResult>> first = meshes.simplified(mesh, load, options);
  ASSERT_TRUE(first.is_ok()) << first.status().message();
  options.threads = 3;  // cannot change the result: the same run
  Result<std::shared_ptr<const SimplifyResult>> second = meshes.simplified(mesh, load, options);
  ASSERT_TRUE(second.is_ok());
  EXPECT_EQ(first.value().get(), second.value().get());
  // Any option that can change the result is a run of its own.
  options.placement = Placement::kOptimal;
  Result<std::shared_ptr<const SimplifyResult>> other = meshes.simplified(mesh, load, options);
  ASSERT_TRUE(other.is_ok());
  EXPECT_NE(other.value().get(), first.value().get());
  EXPECT_FALSE(*other.value()->pm == *first.value()->pm);
  // The shared one is what a run of its own gives.
  LoadedMesh direct;
  ASSERT_TRUE(load_mesh_bytes(kMesh, bytes_of(kMesh), load, &direct).is_ok());
  Result<ProgressiveMesh> own = record_pm(direct.mesh, nullptr, 1);
  ASSERT_TRUE(own.is_ok());
  EXPECT_EQ(*first.value()->pm, own.value());
}

TEST(BakeInput, TheStripsOfASharedProgressiveMeshAreThoseOfTheirOwn) {
  // simplify and strips on the same mesh share one simplification; strips
  // alone (--step) runs its own: the same files.
  const std::string out = testing::TempDir() + "/bake_run_shared_pm";
  std::filesystem::remove_all(out);
  std::vector<InputPlan> plans = plans_for(mesh_path(), "[steps.simplify]\n[steps.strips]\n");
  BakeOptions options;
  options.out_dir = out + "/together";
  options.jobs = 2;
  std::vector<InputReport> together = run_bake(plans, options, {});
  ASSERT_EQ(together[0].status, "ok");
  options.out_dir = out + "/alone";
  for (const char* step : {"simplify", "strips"}) {
    options.only_step = step;
    ASSERT_EQ(run_bake(plans, options, {})[0].status, "ok") << step;
  }
  for (const StepPlan& step : plans[0].steps) {
    ASSERT_EQ(step.outputs.size(), 1u);
    const Bytes shared = bytes_of(output_path(out + "/together", step.outputs[0]));
    EXPECT_FALSE(shared.empty());
    EXPECT_EQ(shared, bytes_of(output_path(out + "/alone", step.outputs[0]))) << step.step;
  }
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace lodbake
