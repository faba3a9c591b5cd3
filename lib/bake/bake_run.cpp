#include "lib/bake/bake_run.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>

#include "formats/support/file_io.h"
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
    if (error) return Status(ErrorKind::kIo, "cannot create the folder: " + error.message());
    LODBAKE_RETURN_IF_ERROR(staged.stage(full, bytes));
  }
  std::string failed;
  return staged.commit(&failed);
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

std::vector<InputReport> run_bake(const std::vector<InputPlan>& plans, const BakeOptions& options,
                                  const BakeEvents& events) {
  std::vector<InputReport> reports(plans.size());
  bool stopped = false;
  for (size_t i = 0; i < plans.size(); ++i) {
    const InputPlan& plan = plans[i];
    InputReport& report = reports[i];
    report.input = plan.input;
    if (stopped) continue;
    const auto input_start = std::chrono::steady_clock::now();
    report.status = "ok";
    Result<Bytes> bytes = read_file(plan.input);
    std::map<std::string, std::vector<Bytes>> earlier;
    for (const StepPlan& step : plan.steps) {
      if (options.only_step && step.step != *options.only_step) continue;
      StepReport s;
      s.step = step.step;
      if (report.status == "failed") {
        s.status = "skipped";
        report.steps.push_back(std::move(s));
        continue;
      }
      if (events.step_started) events.step_started(i, step.step);
      const auto start = std::chrono::steady_clock::now();
      Status status = bytes.status();
      if (status.is_ok() && options.only_step)
        status = read_earlier(plan, options.out_dir, step, &earlier);
      Result<StepResult> made = status.is_ok()
                                    ? run_bake_step(step, plan.input, bytes.value(), earlier)
                                    : Result<StepResult>(status);
      if (made.is_ok()) status = write_outputs(options.out_dir, made.value().files);
      if (made.is_ok() && status.is_ok()) {
        s.status = "baked";
        s.warnings = made.value().warnings;
        s.report = made.value().report;
        for (auto& [path, file] : made.value().files) {
          s.outputs.emplace_back(output_path(options.out_dir, path), file.size());
          earlier[step.step].push_back(std::move(file));
        }
      } else {
        const Status& failed = made.is_ok() ? status : made.status();
        s.status = "failed";
        s.error = failed.message();
        s.error_kind = failed.kind();
        report.status = "failed";
      }
      s.seconds = seconds_since(start);
      report.steps.push_back(std::move(s));
    }
    report.seconds = seconds_since(input_start);
    if (report.status == "failed" && !options.keep_going) stopped = true;
    if (events.input_done) events.input_done(i, report);
  }
  return reports;
}

}  // namespace lodbake
