// lodbake-bake: runs a recipe (lib/bake/recipe.h) over many inputs, each
// step in-process with the code its tool runs. Thin: parsing, planning,
// steps and the run live in lib/bake; this file reads options, draws
// progress and prints the reports.
#include <unistd.h>
#if defined(__GLIBC__)  // set by <unistd.h>'s <features.h>
#include <malloc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>

#include "formats/support/file_io.h"
#include "lib/bake/bake_cache.h"
#include "lib/bake/bake_run.h"
#include "lib/bake/recipe.h"
#include "tools/common/cli.h"

namespace lodbake::cli {
namespace {

constexpr const char* kBakeSchema = "lodbake.bake/1";
// Beyond the shared table: how many inputs failed.
constexpr int kSomeFailed = 8;
constexpr int kAllFailed = 9;

// Progress on stderr: one redrawn line on a terminal (inputs done, the
// steps running, ETA), one plain line per finished input otherwise.
class BakeProgress {
 public:
  BakeProgress(const Tool& tool, size_t total)
      : enabled_(!tool.quiet()),
        terminal_(isatty(STDERR_FILENO) != 0),
        tool_(tool.name()),
        total_(total),
        start_(std::chrono::steady_clock::now()) {}
  ~BakeProgress() {
    if (enabled_ && terminal_ && drawn_) std::cerr << "\r\033[K" << std::flush;
  }

  void step_started(const std::string& input, const std::string& step) {
    std::lock_guard<std::mutex> lock(mutex_);
    running_[input] = step;
    draw();
  }

  void input_done(const InputReport& report) {
    std::lock_guard<std::mutex> lock(mutex_);
    running_.erase(report.input);
    ++done_;
    if (!enabled_) return;
    if (terminal_) {
      draw();
      return;
    }
    std::ostringstream line;
    line.precision(3);
    line << tool_ << ": [" << done_ << "/" << total_ << "] " << report.input << ": "
         << report.status << " in " << report.seconds << " s\n";
    std::cerr << line.str() << std::flush;
  }

 private:
  void draw() {
    if (!enabled_ || !terminal_) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::ostringstream line;
    line << "\r\033[K" << tool_ << ": " << done_ << "/" << total_ << " inputs";
    if (!running_.empty()) {
      const auto& [input, step] = *running_.begin();
      const size_t slash = input.find_last_of('/');
      line << ", " << step << " " << (slash == std::string::npos ? input : input.substr(slash + 1));
      if (running_.size() > 1) line << " (+" << running_.size() - 1 << ")";
    }
    if (done_ > 0 && done_ < total_)
      line << ", ETA " << static_cast<long>(elapsed / done_ * (total_ - done_) + 0.5) << " s";
    std::cerr << line.str() << std::flush;
    drawn_ = true;
  }

  bool enabled_;
  bool terminal_;
  std::string tool_;
  size_t total_;
  size_t done_ = 0;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::map<std::string, std::string> running_;  // input -> its current step
  std::mutex mutex_;
};

nlohmann::json step_json(const StepReport& s) {
  nlohmann::json outputs = nlohmann::json::array();
  for (const auto& [file, bytes] : s.outputs)
    outputs.push_back({{"file", file}, {"bytes", bytes}});
  nlohmann::json j = {{"step", s.step},     {"status", s.status},     {"seconds", s.seconds},
                      {"outputs", outputs}, {"warnings", s.warnings}, {"report", s.report}};
  if (s.status == "failed") j["error"] = s.error;
  return j;
}

nlohmann::json plan_json(const std::vector<InputPlan>& plans) {
  nlohmann::json inputs = nlohmann::json::array();
  for (const InputPlan& plan : plans) {
    nlohmann::json steps = nlohmann::json::array();
    for (const StepPlan& s : plan.steps)
      steps.push_back({{"step", s.step}, {"options", s.options}, {"outputs", s.outputs}});
    // The buffers, images and material files it reads, so that a workflow
    // engine reruns its steps when one changes; an unreadable input has
    // none (its steps report the error).
    std::vector<std::string> references;
    if (Result<Bytes> bytes = read_file(plan.input); bytes.is_ok())
      references = referenced_files(plan.input, input_fingerprint(plan.input, bytes.value()));
    inputs.push_back({{"input", plan.input}, {"references", references}, {"steps", steps}});
  }
  return {{"schema", "lodbake.bake.plan/1"}, {"inputs", inputs}};
}

void print_summary(const std::vector<InputReport>& reports, double seconds) {
  size_t width = 5;
  for (const InputReport& r : reports)
    width = std::max(width, r.input.size());
  std::cout << std::left << std::setw(static_cast<int>(width)) << "input"
            << "  status   steps  cached  seconds      bytes\n";
  for (const InputReport& r : reports) {
    uint64_t bytes = 0;
    size_t baked = 0, cached = 0;
    for (const StepReport& s : r.steps) {
      baked += s.status == "baked" || s.status == "cached";
      cached += s.status == "cached";
      for (const auto& [file, size] : s.outputs)
        bytes += size;
    }
    std::ostringstream steps;
    steps << baked << "/" << r.steps.size();
    std::cout << std::left << std::setw(static_cast<int>(width)) << r.input << "  " << std::setw(7)
              << r.status << "  " << std::setw(5) << steps.str() << std::right << std::setw(8)
              << cached << std::fixed << std::setprecision(2) << std::setw(9) << r.seconds
              << std::setw(11) << bytes << "\n";
    std::cout.unsetf(std::ios::fixed);
  }
  std::cout << "baked " << reports.size() << " inputs in " << std::fixed << std::setprecision(2)
            << seconds << " s\n";
}

}  // namespace
}  // namespace lodbake::cli

int main(int argc, char** argv) {
  using namespace lodbake;
  using namespace lodbake::cli;
#if defined(__GLIBC__)
  // One malloc arena, as lodbake-hierarchy and lodbake-pack: with one per
  // thread, what a step frees on one thread is not reused by the next
  // step's allocations on another (the dragon's bake with --jobs 2: 508 MiB
  // peak, 466 MiB with one arena; docs/lab/bake-speed.md).
  mallopt(M_ARENA_MAX, 1);
#endif
  Tool tool("lodbake-bake", "RECIPE.toml [options]",
            "Bakes every input a recipe names (globs over meshes and glTF assets) through\n"
            "its steps: pack, simplify (progressive mesh), lods (LOD chain), hierarchy, fan,\n"
            "strips and package (the earlier containers merged and recoded), each in-process with\n"
            "the code its tool runs, so every file is byte for byte what the tool writes with\n"
            "the same options (docs/tools.md \"lodbake-bake\" has the recipe reference).\n"
            "Outputs go to the recipe's path templates under --out, each step's files\n"
            "written atomically. A failed input stops the run unless --keep-going.");
  std::string out_dir = ".";
  std::vector<std::string> sets;
  std::string asset;
  std::string step;
  unsigned jobs = 0;
  std::string cache_dir;
  tool.options().add_options()("out", po::value<std::string>(&out_dir)->value_name("DIR"),
                               "the folder the output templates are relative to (default: the "
                               "current folder)")(
      "set", po::value<std::vector<std::string>>(&sets)->value_name("NAME=VALUE"),
      "set a recipe variable ([vars]), e.g. --set data=../shared/data; repeatable")(
      "jobs,j", po::value<unsigned>(&jobs)->value_name("N"),
      "bake N inputs at once (default: one per core); the outputs are the same for any N")(
      "keep-going", "bake the other inputs after one failed")(
      "cache", po::value<std::string>(&cache_dir)->value_name("DIR"),
      "the content cache: a step whose input files, options and lodbake version are "
      "unchanged is copied from it instead of baked (default: $LODBAKE_CACHE_DIR, else "
      "$XDG_CACHE_HOME/lodbake, else ~/.cache/lodbake)")("no-cache",
                                                         "neither read nor fill the cache")(
      "force", "bake every step even when the cache has it (and store it again)")(
      "asset", po::value<std::string>(&asset)->value_name("PATH"),
      "bake only this input (a path the globs match, as --list prints it)")(
      "step", po::value<std::string>(&step)->value_name("NAME"),
      "run only this step of each input (package reads the outputs of the steps it merges)")(
      "list", "print the plan (inputs, each step's options and outputs) as JSON and bake nothing");
  tool.positional("recipe", -1);
  tool.set_help_epilog(
      "Exit codes of a bake (besides the table below: 1 for a usage error, 2 when the\n"
      "recipe cannot be read, 3 for a bad recipe, naming its line and key):\n"
      "  0  every input baked\n"
      "  8  some inputs failed (each named on stderr and in the report)\n"
      "  9  no input baked (all failed, or the run stopped at the first)\n");
  if (std::optional<int> done = tool.parse(argc, argv)) return *done;
  std::string recipe_file;
  if (std::optional<int> code = tool.single_positional("recipe", "RECIPE", &recipe_file))
    return *code;
  std::map<std::string, std::string> set;
  for (const std::string& pair : sets) {
    const size_t eq = pair.find('=');
    if (eq == std::string::npos || eq == 0)
      return tool.usage_error("--set takes NAME=VALUE, not '" + pair + "'");
    set[pair.substr(0, eq)] = pair.substr(eq + 1);
  }
  if (tool.has("cache") && tool.has("no-cache"))
    return tool.usage_error("--cache and --no-cache contradict each other: give one");
  if (tool.has("step")) {
    const std::vector<std::string>& names = bake_step_names();
    if (std::find(names.begin(), names.end(), step) == names.end())
      return tool.usage_error(
          "--step takes pack, simplify, lods, hierarchy, fan, strips or package, not '" + step +
          "'");
  }
  return tool.run([&]() -> int {
    Result<Bytes> text = read_file(recipe_file);
    if (!text.is_ok()) return tool.fail(recipe_file, text.status());
    Result<Recipe> recipe =
        parse_recipe(recipe_file, std::string(text.value().begin(), text.value().end()), set);
    if (!recipe.is_ok()) return tool.fail(recipe_file, recipe.status());
    std::vector<std::string> warnings;
    Result<std::vector<std::string>> inputs = expand_inputs(recipe.value(), &warnings);
    if (!inputs.is_ok()) return tool.fail(recipe_file, inputs.status());
    for (const std::string& w : warnings)
      tool.warn(recipe_file, w);
    if (tool.has("asset")) {
      std::vector<std::string> chosen;
      for (const std::string& input : inputs.value())
        if (input == asset || same_file(input, asset)) chosen.push_back(input);
      if (chosen.empty())
        return tool.fail(recipe_file,
                         Status(ErrorKind::kUsage, "--asset " + asset + ": no glob matches it"));
      inputs.value() = chosen;
    }
    Result<std::vector<InputPlan>> plans = plan_inputs(recipe.value(), inputs.value());
    if (!plans.is_ok()) return tool.fail(recipe_file, plans.status());
    if (tool.has("list")) {
      tool.print_json(plan_json(plans.value()));
      return 0;
    }
    BakeOptions options;
    options.out_dir = out_dir;
    options.jobs = jobs;
    if (!tool.has("no-cache"))
      options.cache_dir = tool.has("cache") ? cache_dir : default_bake_cache_folder();
    options.force = tool.has("force");
    options.keep_going = tool.has("keep-going");
    if (tool.has("step")) options.only_step = step;
    const auto start = std::chrono::steady_clock::now();
    std::vector<InputReport> reports;
    {
      BakeProgress progress(tool, plans.value().size());
      BakeEvents events;
      events.step_started = [&](size_t i, const std::string& s) {
        progress.step_started(plans.value()[i].input, s);
      };
      events.input_done = [&](size_t, const InputReport& r) { progress.input_done(r); };
      reports = run_bake(plans.value(), options, events);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    size_t ok = 0, failed = 0;
    for (const InputReport& r : reports) {
      ok += r.status == "ok";
      failed += r.status == "failed";
      for (const StepReport& s : r.steps) {
        for (const std::string& w : s.warnings)
          tool.warn(r.input, s.step + ": " + w);
        if (s.status == "failed") {
          std::cerr << tool.name() << ": error: " << r.input << ": " << s.step << ": " << s.error
                    << "\n";
        }
      }
    }
    if (tool.json()) {
      nlohmann::json inputs_json = nlohmann::json::array();
      for (const InputReport& r : reports) {
        nlohmann::json steps = nlohmann::json::array();
        for (const StepReport& s : r.steps)
          steps.push_back(step_json(s));
        inputs_json.push_back(
            {{"input", r.input}, {"status", r.status}, {"seconds", r.seconds}, {"steps", steps}});
      }
      tool.print_json({{"schema", kBakeSchema},
                       {"recipe", recipe_file},
                       {"inputs", inputs_json},
                       {"summary",
                        {{"inputs", reports.size()},
                         {"ok", ok},
                         {"failed", failed},
                         {"skipped", reports.size() - ok - failed},
                         {"seconds", seconds}}}});
    } else if (!tool.quiet()) {
      print_summary(reports, seconds);
    }
    if (ok == reports.size()) return 0;
    return ok == 0 ? kAllFailed : kSomeFailed;
  });
}
