// Runs bake plans (lib/bake/recipe.h): every input's building steps side by
// side on one import of it, then package; each step's files written
// atomically once all of them are made, a failed step failing its input.
// Outputs are a function of the plans alone.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "formats/support/status.h"
#include "lib/bake/recipe.h"

namespace lodbake {

struct BakeOptions {
  std::string out_dir = ".";             // the plans' outputs are relative to it
  unsigned jobs = 0;                     // inputs baked at once; 0: one per core (bake_jobs())
  bool keep_going = false;               // run the other inputs after one failed
  std::optional<std::string> only_step;  // run this step alone (package: its inputs made before)
  // The content cache (lib/bake/bake_cache.h): a step whose key is there is
  // copied from it, not baked; a baked step is stored. None: no cache.
  std::optional<std::string> cache_dir;
  bool force = false;  // bake every step, and store it again
};

struct StepReport {
  std::string step;
  // "baked", "cached" (copied from the cache), "failed", or "skipped"
  // (package, when a step of its input failed)
  std::string status;
  double seconds = 0;
  std::vector<std::pair<std::string, uint64_t>> outputs;  // file (in out_dir), bytes
  std::vector<std::string> warnings;
  std::string error;  // when failed
  ErrorKind error_kind = ErrorKind::kOk;
  nlohmann::json report = nlohmann::json::object();
};

struct InputReport {
  std::string input;
  std::string status = "skipped";  // "ok", "failed", or "skipped" (the run stopped first)
  double seconds = 0;
  std::vector<StepReport> steps;
};

// Called as the run goes, from the threads baking (never two at once): a
// step starts, an input ends.
struct BakeEvents {
  std::function<void(size_t input, const std::string& step)> step_started;
  std::function<void(size_t input, const InputReport& report)> input_done;
};

// The inputs baked at once for `requested` (0: TBB's default concurrency,
// the cores this process may use).
unsigned bake_jobs(unsigned requested);

// Bakes `plans`, `options.jobs` inputs at once (oneTBB); the reports come in
// the plans' order. Without keep_going, inputs not started when one fails
// are left "skipped".
std::vector<InputReport> run_bake(const std::vector<InputPlan>& plans, const BakeOptions& options,
                                  const BakeEvents& events);

// `out_dir` + "/" + `path` unless `path` is absolute.
std::string output_path(const std::string& out_dir, const std::string& path);

}  // namespace lodbake
