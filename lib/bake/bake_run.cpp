#include "lib/bake/bake_run.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

#include "formats/support/file_io.h"
#include "lib/bake/bake_cache.h"
#include "lib/bake/bake_steps.h"

namespace lodbake {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Every file of a step, or none: folders first, then the staged renames.
Status write_outputs(const std::string& out_dir,
                     const std::vector<std::pair<std::string, Bytes>>& files) {
  StagedOutputs staged;
  for (const auto& [path, bytes] : files) {
    const std::string full = output_path(out_dir, path);
    const std::filesystem::path folder = std::filesystem::path(full).parent_path();
    std::error_code error;
    if (!folder.empty()) std::filesystem::create_directories(folder, error);
    if (error)
      return Status(ErrorKind::kIo,
                    folder.string() + ": cannot create the folder: " + error.message());
    // A file that already holds these bytes (a rerun into the same folder)
    // is left as it is: no write, no flush, its time stamp kept for make.
    const uintmax_t size = std::filesystem::file_size(full, error);
    if (!error && size == bytes.size()) {
      Result<Bytes> existing = read_file(full);
      if (existing.is_ok() && existing.value() == bytes) continue;
    }
    if (Status staged_ok = staged.stage(full, bytes); !staged_ok.is_ok())
      return Status(staged_ok.kind(), full + ": " + staged_ok.message());
  }
  std::string failed;
  if (Status committed = staged.commit(&failed); !committed.is_ok())
    return Status(committed.kind(), failed + ": " + committed.message());
  return Status::ok();
}

// The files of the steps `only_step` depends on (package), read back from
// an earlier run's outputs.
Status read_earlier(const InputPlan& plan, const std::string& out_dir, const StepPlan& step,
                    std::map<std::string, std::vector<Bytes>>* earlier) {
  if (step.step != "package") return Status::ok();
  for (const nlohmann::json& from : step.options["from"]) {
    for (const StepPlan& s : plan.steps) {
      if (s.step != from.get<std::string>()) continue;
      for (const std::string& path : s.outputs) {
        Result<Bytes> bytes = read_file(output_path(out_dir, path));
        if (!bytes.is_ok())
          return Status(bytes.status().kind(), output_path(out_dir, path) + ": " +
                                                   bytes.status().message() + " (run step " +
                                                   s.step + " first)");
        (*earlier)[s.step].push_back(std::move(bytes).value());
      }
    }
  }
  return Status::ok();
}

}  // namespace

std::string output_path(const std::string& out_dir, const std::string& path) {
  if (!path.empty() && path.front() == '/') return path;
  return out_dir + "/" + path;
}

namespace {

// One step: from the cache, or baked and its files written. `earlier` holds
// the files of the steps `step` merges (package), which it takes.
StepReport bake_step(const InputPlan& plan, const BakeOptions& options, const StepPlan& step,
                     const Result<Bytes>& bytes, const std::optional<BakeCache>& cache,
                     const std::string& key, std::map<std::string, std::vector<Bytes>>* earlier,
                     InputMeshes* meshes, std::vector<Bytes>* files) {
  StepReport s;
  s.step = step.step;
  const auto start = std::chrono::steady_clock::now();
  Status status = bytes.status();
  std::optional<StepResult> hit;
  if (status.is_ok() && cache && !options.force) hit = cache->load(key, step);
  std::map<std::string, std::vector<Bytes>> read_back;
  if (status.is_ok() && !hit && options.only_step)
    status = read_earlier(plan, options.out_dir, step, &read_back);
  Result<StepResult> made = hit ? Result<StepResult>(std::move(*hit))
                            : status.is_ok()
                                ? run_bake_step(step, plan.input, bytes.value(),
                                                options.only_step ? &read_back : earlier, meshes)
                                : Result<StepResult>(status);
  if (made.is_ok()) status = write_outputs(options.out_dir, made.value().files);
  if (made.is_ok() && status.is_ok()) {
    s.status = hit ? "cached" : "baked";
    s.warnings = made.value().warnings;
    s.report = made.value().report;
    if (cache && !hit) {
      // A cache that cannot be written costs the next run time, not this
      // run its outputs.
      Status stored = cache->store(key, made.value());
      if (!stored.is_ok()) s.warnings.push_back("cache: " + stored.message());
    }
    for (auto& [path, file] : made.value().files) {
      s.outputs.emplace_back(output_path(options.out_dir, path), file.size());
      files->push_back(std::move(file));
    }
  } else {
    const Status& failed = made.is_ok() ? status : made.status();
    s.status = "failed";
    s.error = failed.message();
    s.error_kind = failed.kind();
  }
  s.seconds = seconds_since(start);
  return s;
}

// One input's steps. The steps that build from the input share nothing but
// its loaded meshes, so they run side by side on the bake's threads (a
// single large scan keeps every thread busy where one builder alone would
// not); package runs after them, on their files, and is skipped when one of
// them failed. Every report and file is the same as when they run in turn.
InputReport bake_input(const InputPlan& plan, const BakeOptions& options,
                       const std::function<void(const std::string&)>& step_started) {
  InputReport report;
  report.input = plan.input;
  const auto input_start = std::chrono::steady_clock::now();
  report.status = "ok";
  Result<Bytes> bytes = read_file(plan.input);
  std::optional<BakeCache> cache;
  nlohmann::json fingerprint;
  if (options.cache_dir && bytes.is_ok()) {
    cache.emplace(*options.cache_dir);
    fingerprint = input_fingerprint(plan.input, bytes.value());
  }
  std::map<std::string, std::string> keys;  // step -> its cache key
  std::vector<size_t> builds, merges;       // indices into plan.steps, to run
  for (size_t i = 0; i < plan.steps.size(); ++i) {
    const StepPlan& step = plan.steps[i];
    if (cache) {
      std::vector<std::string> merged;
      if (step.step == "package")
        for (const nlohmann::json& from : step.options["from"])
          merged.push_back(keys[from.get<std::string>()]);
      keys[step.step] = step_key(fingerprint, step, merged);
    }
    if (options.only_step && step.step != *options.only_step) continue;
    (step.step == "package" ? merges : builds).push_back(i);
  }

  std::vector<StepPlan> building;
  for (size_t i : builds)
    building.push_back(plan.steps[i]);
  std::optional<InputMeshes> meshes(std::in_place, building);
  std::vector<StepReport> reports(plan.steps.size());
  std::vector<std::vector<Bytes>> files(plan.steps.size());
  auto run = [&](size_t i, std::map<std::string, std::vector<Bytes>>* earlier) {
    step_started(plan.steps[i].step);
    reports[i] = bake_step(plan, options, plan.steps[i], bytes, cache, keys[plan.steps[i].step],
                           earlier, meshes ? &*meshes : nullptr, &files[i]);
  };
  // Isolated: a thread that waits for this input's last step must not take
  // up another input meanwhile, which would hold both inputs' meshes.
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, builds.size(), 1),
        [&](const tbb::blocked_range<size_t>& range) {
          for (size_t k = range.begin(); k != range.end(); ++k)
            run(builds[k], nullptr);
        },
        tbb::simple_partitioner());
  });
  // Package merges the steps' files: the input's bytes and meshes are of
  // no more use, and a large scan's are as large as some of those files.
  meshes.reset();
  if (bytes.is_ok()) Bytes().swap(bytes.value());
  bool failed = false;
  for (size_t i : builds)
    failed = failed || reports[i].status == "failed";
  std::map<std::string, std::vector<Bytes>> earlier;
  for (size_t i : builds)
    earlier[plan.steps[i].step] = std::move(files[i]);
  for (size_t i : merges) {
    if (failed) {
      reports[i].step = plan.steps[i].step;
      reports[i].status = "skipped";
      continue;
    }
    run(i, &earlier);
    failed = failed || reports[i].status == "failed";
  }
  for (size_t i = 0; i < plan.steps.size(); ++i) {
    if (reports[i].step.empty()) continue;  // not asked for (--step)
    if (reports[i].status == "failed") report.status = "failed";
    report.steps.push_back(std::move(reports[i]));
  }
  report.seconds = seconds_since(input_start);
  return report;
}

}  // namespace

unsigned bake_jobs(unsigned requested) {
  return requested != 0 ? requested
                        : static_cast<unsigned>(std::max(1, tbb::info::default_concurrency()));
}

std::vector<InputReport> run_bake(const std::vector<InputPlan>& plans, const BakeOptions& options,
                                  const BakeEvents& events) {
  std::vector<InputReport> reports(plans.size());
  for (size_t i = 0; i < plans.size(); ++i)
    reports[i].input = plans[i].input;
  std::atomic<bool> stopped{false};
  std::mutex events_mutex;  // events are never called two at once
  // Each input is one task: inputs share nothing, so their outputs are the
  // same whatever thread bakes them and in whatever order. The largest
  // files start first, so that a big asset does not run alone at the end.
  std::vector<std::pair<uint64_t, size_t>> order;
  for (size_t i = 0; i < plans.size(); ++i) {
    std::error_code error;
    const uintmax_t size = std::filesystem::file_size(plans[i].input, error);
    order.emplace_back(error ? 0 : static_cast<uint64_t>(size), i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  tbb::task_arena arena(static_cast<int>(bake_jobs(options.jobs)));
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, order.size(), 1),
        [&](const tbb::blocked_range<size_t>& range) {
          for (size_t k = range.begin(); k != range.end(); ++k) {
            const size_t i = order[k].second;
            if (stopped.load()) continue;
            reports[i] = bake_input(plans[i], options, [&](const std::string& step) {
              if (!events.step_started) return;
              std::lock_guard<std::mutex> lock(events_mutex);
              events.step_started(i, step);
            });
            if (reports[i].status == "failed" && !options.keep_going) stopped.store(true);
            if (events.input_done) {
              std::lock_guard<std::mutex> lock(events_mutex);
              events.input_done(i, reports[i]);
            }
          }
        },
        tbb::simple_partitioner());
  });
  return reports;
}

}  // namespace lodbake
