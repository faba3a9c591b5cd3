// One step of a bake plan (lib/bake/recipe.h) on one input, in memory: the
// same library calls, options and META as the tool the step stands for, so
// its files are byte for byte what that tool writes (pack: lodbake-pack;
// simplify: lodbake-simplify --pm; lods: lodbake-simplify --lods; hierarchy,
// fan: lodbake-hierarchy, lodbake-fan; package: lodbake-pack A.lbk B.lbk ...).
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/bake/recipe.h"

namespace lodbake {

struct StepResult {
  std::vector<std::pair<std::string, Bytes>> files;  // the plan's outputs, in its order
  std::vector<std::string> warnings;                 // one line each, as the tool warns
  nlohmann::json report = nlohmann::json::object();  // counts the tool reports
};

// Runs `step` on `input` (its content `bytes`; referenced buffers and
// images are read next to it). `earlier` holds the files of the input's
// earlier steps by step name (package merges them). Deterministic; fails
// with the status the tool would print.
Result<StepResult> run_bake_step(const StepPlan& step, const std::string& input, const Bytes& bytes,
                                 const std::map<std::string, std::vector<Bytes>>& earlier);

}  // namespace lodbake
