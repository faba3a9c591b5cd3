// A bake recipe (lodbake-bake RECIPE): which inputs, which steps with which
// options, per-glob overrides and where the outputs go, read from TOML with
// toml++ (docs/tools.md "lodbake-bake" has the reference). Parsing checks
// every key, type and range and names the recipe's line; planning turns the
// recipe into one plan per input (its steps' merged options and output
// paths), which is all a step needs: the same plan gives the same bytes.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "formats/support/status.h"

namespace lodbake {

// The steps, in the order they run for each input.
const std::vector<std::string>& bake_step_names();

struct RecipeOverride {
  std::string glob;         // matched against the input's path (fnmatch, '*' spans '/')
  nlohmann::json settings;  // "repair", "skip" and "steps" as given
};

struct Recipe {
  std::string file;    // as given, for messages
  std::string folder;  // inputs are relative to it
  std::map<std::string, std::string> vars;
  std::vector<std::string> globs;     // with vars substituted, relative to `folder` unless absolute
  std::vector<std::string> excludes;  // the same, matched against the expanded paths
  std::string output;                 // path template of a container step
  std::string lods_output;            // path template of an LOD level
  std::string repair = "default";     // "default", "repair" or "strict"
  nlohmann::json steps;               // step -> its options as given (object)
  std::vector<RecipeOverride> overrides;
};

// Parses `text`, read from `file`. `set` holds --set NAME=VALUE pairs, which
// replace the recipe's [vars]. Fails with kInvalidInput, "line N: KEY: what
// is wrong" (toml++'s own message and position for a TOML syntax error).
Result<Recipe> parse_recipe(const std::string& file, const std::string& text,
                            const std::map<std::string, std::string>& set);

// The inputs the globs match, each once, sorted by path (so a run's order
// and report do not depend on the file system). A glob that matches nothing
// adds a warning; one that cannot be read (a folder without permission)
// fails with kIo.
Result<std::vector<std::string>> expand_inputs(const Recipe& recipe,
                                               std::vector<std::string>* warnings);

struct StepPlan {
  std::string step;
  // Every option of the step with its default filled in, and "repair": what
  // the step's output is a function of, besides the input's bytes.
  nlohmann::json options;
  std::vector<std::string> outputs;  // relative to the output folder; lods: one per level
};

struct InputPlan {
  std::string input;  // as expanded
  std::vector<StepPlan> steps;
};

// The steps of `input` after the overrides that match it (in recipe order,
// later ones winning). Fails with kInvalidInput when merged options
// contradict each other (e.g. a package step naming a step that is skipped).
Result<InputPlan> plan_input(const Recipe& recipe, const std::string& input);

// plan_input() for every input; fails with kInvalidInput when two outputs
// (of two inputs or two steps) are one path: the template needs {name},
// {stem}, {dir} or {step} to tell them apart.
Result<std::vector<InputPlan>> plan_inputs(const Recipe& recipe,
                                           const std::vector<std::string>& inputs);

}  // namespace lodbake
