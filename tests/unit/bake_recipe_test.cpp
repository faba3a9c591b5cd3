// Recipes (lib/bake/recipe.h): every error names the line and the key,
// defaults are filled in, overrides merge in order, globs expand sorted and
// outputs that collide are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "lib/bake/recipe.h"

namespace lodbake {
namespace {

Result<Recipe> parse(const std::string& text, const std::map<std::string, std::string>& set = {}) {
  return parse_recipe("/recipes/r.toml", text, set);
}

std::string error_of(const std::string& text) {
  Result<Recipe> r = parse(text);
  EXPECT_FALSE(r.is_ok()) << text;
  if (r.is_ok()) return "";
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
  return r.status().message();
}

const char kMinimal[] = "[inputs]\nglobs = [\"*.off\"]\n[steps.pack]\n";

TEST(BakeRecipe, MinimalRecipeGetsDefaults) {
  Result<Recipe> r = parse(kMinimal);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().globs, std::vector<std::string>{"/recipes/*.off"});
  EXPECT_EQ(r.value().output, "{name}/{step}.lbk");
  Result<InputPlan> plan = plan_input(r.value(), "/recipes/a.off");
  ASSERT_TRUE(plan.is_ok());
  ASSERT_EQ(plan.value().steps.size(), 1u);
  EXPECT_EQ(plan.value().steps[0].options["quantize"], 0);
  EXPECT_EQ(plan.value().steps[0].options["repair"], "default");
  EXPECT_EQ(plan.value().steps[0].outputs, std::vector<std::string>{"a.off/pack.lbk"});
}

TEST(BakeRecipe, ErrorsNameLineAndKey) {
  EXPECT_EQ(error_of(std::string(kMinimal) + "[steps.simplify]\nratoi = 0.5\n"),
            "line 5: steps.simplify.ratoi: unknown key");
  EXPECT_EQ(error_of(std::string(kMinimal) + "[steps.simplify]\nratio = \"half\"\n"),
            "line 5: steps.simplify.ratio: must be a number");
  EXPECT_EQ(error_of(std::string(kMinimal) + "[steps.simplify]\nratio = 1.5\n"),
            "line 5: steps.simplify.ratio: must be above 0.0 and at most 1.0");
  EXPECT_EQ(error_of(std::string(kMinimal) + "[steps.hierarchy]\nsections = [\"vhie\", \"x\"]\n"),
            "line 5: steps.hierarchy.sections: each must be one of 'vhie' 'dage' 'vtre', not 'x'");
  EXPECT_EQ(
      error_of(std::string(kMinimal) + "[steps.strip]\n"),
      "line 4: steps.strip: unknown step (pack, simplify, lods, hierarchy, fan, strips, package)");
  EXPECT_EQ(error_of(std::string(kMinimal) + "colour = 1\n"),
            "line 4: steps.pack.colour: unknown key");
  EXPECT_EQ(error_of("repair = \"always\"\n" + std::string(kMinimal)),
            "line 1: repair: must be 'default', 'repair' or 'strict', not 'always'");
  EXPECT_EQ(error_of(std::string(kMinimal) + "[output]\npath = \"{nmae}.lbk\"\n"),
            "line 5: output.path: unknown placeholder {nmae}");
  EXPECT_EQ(
      error_of("[inputs]\nglobs = [\"{data}/*.off\"]\n[steps.pack]\n"),
      "line 1: inputs: unknown variable {data} in '{data}/*.off' (give it in [vars] or --set)");
  EXPECT_EQ(error_of("[steps.pack]\n"), "line 1: inputs.globs: missing (the inputs to bake)");
  // TOML itself: toml++'s message and line.
  EXPECT_EQ(error_of("[inputs]\nglobs = [\"a\"\n").rfind("line 2: Error while parsing array", 0),
            0u);
  EXPECT_EQ(error_of(std::string(kMinimal) + "[[override]]\nglob = \"*\"\nskip = [\"fan\"]\n"),
            "line 6: override[0].skip: 'fan' is not a step of this recipe");
}

TEST(BakeRecipe, VariablesAndOverrides) {
  const std::string text =
      "[vars]\ndata = \"/d\"\n[inputs]\nglobs = [\"{data}/*.off\"]\n"
      "[output]\npath = \"{stem}-{step}.lbk\"\n"
      "[steps.simplify]\nratio = 0.5\n[steps.fan]\n"
      "[[override]]\nglob = \"*/b.off\"\nrepair = \"strict\"\n[override.steps.simplify]\n"
      "ratio = 0.25\n"
      "[[override]]\nglob = \"*/b.*\"\nskip = [\"fan\"]\n";
  Result<Recipe> r = parse(text, {{"data", "/other"}});
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().globs, std::vector<std::string>{"/other/*.off"});
  Result<InputPlan> a = plan_input(r.value(), "/other/a.off");
  Result<InputPlan> b = plan_input(r.value(), "/other/b.off");
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  ASSERT_EQ(a.value().steps.size(), 2u);
  EXPECT_EQ(a.value().steps[0].options["ratio"], 0.5);
  EXPECT_EQ(a.value().steps[0].options["repair"], "default");
  EXPECT_EQ(a.value().steps[1].outputs, std::vector<std::string>{"a-fan.lbk"});
  ASSERT_EQ(b.value().steps.size(), 1u);
  EXPECT_EQ(b.value().steps[0].options["ratio"], 0.25);
  EXPECT_EQ(b.value().steps[0].options["repair"], "strict");
  EXPECT_EQ(b.value().steps[0].options["placement"], "half");
}

TEST(BakeRecipe, LodChainByRatiosOrErrors) {
  EXPECT_EQ(error_of(std::string(kMinimal) + "[steps.lods]\nratios = [0.5]\nerrors = [0.1]\n"),
            "line 4: steps.lods: give ratios or errors, not both");
  Result<Recipe> r = parse(std::string(kMinimal) +
                           "[steps.lods]\nratios = [0.5, 0.25]\n[[override]]\nglob = \"*.ply\"\n"
                           "[override.steps.lods]\nerrors = [0.01, 0.02, 0.04]\n");
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  Result<InputPlan> off = plan_input(r.value(), "/a.off");
  Result<InputPlan> ply = plan_input(r.value(), "/a.ply");
  ASSERT_TRUE(off.is_ok() && ply.is_ok());
  EXPECT_EQ(off.value().steps[1].outputs.size(), 2u);
  EXPECT_TRUE(off.value().steps[1].options["errors"].is_null());
  // The override's chain by errors replaces the ratios: one level per error.
  EXPECT_EQ(ply.value().steps[1].outputs,
            (std::vector<std::string>{"a.ply/lod0.glb", "a.ply/lod1.glb", "a.ply/lod2.glb"}));
  EXPECT_TRUE(ply.value().steps[1].options["ratios"].is_null());
}

TEST(BakeRecipe, CollidingOutputsAreRefused) {
  Result<Recipe> r = parse(
      "[inputs]\nglobs = [\"*\"]\n[output]\npath = \"{stem}/{step}.lbk\"\n"
      "[steps.pack]\n");
  ASSERT_TRUE(r.is_ok());
  EXPECT_TRUE(plan_inputs(r.value(), {"/x/Duck.glb", "/y/Box.glb"}).is_ok());
  Result<std::vector<InputPlan>> plans = plan_inputs(r.value(), {"/x/Duck.glb", "/x/Duck.gltf"});
  ASSERT_FALSE(plans.is_ok());
  EXPECT_NE(plans.status().message().find("'Duck/pack.lbk' is the output of both"),
            std::string::npos);
}

TEST(BakeRecipe, GlobsExpandSortedOnceAndWarnOnNoMatch) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("bake_recipe_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  for (const char* name : {"c.off", "a.off", "b.ply"})
    std::ofstream(dir / name) << "x";
  Result<Recipe> r =
      parse_recipe((dir / "r.toml").string(),
                   "[inputs]\nglobs = [\"*.off\", \"a.*\", \"*.stl\", \"none/*.off\"]\n"
                   "exclude = [\"c.*\"]\n[steps.pack]\n",
                   {});
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  std::vector<std::string> warnings;
  Result<std::vector<std::string>> inputs = expand_inputs(r.value(), &warnings);
  ASSERT_TRUE(inputs.is_ok());
  EXPECT_EQ(inputs.value(), std::vector<std::string>{(dir / "a.off").string()});
  // A folder that does not exist is a glob matching nothing, not an error.
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("*.stl' matches no file"), std::string::npos);
  EXPECT_NE(warnings[1].find("none/*.off' matches no file"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(BakeRecipe, PackageTakesTheListedStepsThatRun) {
  Result<Recipe> r = parse(
      "[inputs]\nglobs = [\"*\"]\n[steps.simplify]\n[steps.fan]\n[steps.package]\n"
      "from = [\"fan\", \"hierarchy\"]\n[[override]]\nglob = \"*.ply\"\nskip = [\"fan\"]\n");
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  Result<InputPlan> off = plan_input(r.value(), "/a.off");
  ASSERT_TRUE(off.is_ok());
  EXPECT_EQ(off.value().steps.back().options["from"], nlohmann::json::array({"fan"}));
  Result<InputPlan> ply = plan_input(r.value(), "/a.ply");
  ASSERT_FALSE(ply.is_ok());
  EXPECT_NE(ply.status().message().find("steps.package.from"), std::string::npos);
}

}  // namespace
}  // namespace lodbake
