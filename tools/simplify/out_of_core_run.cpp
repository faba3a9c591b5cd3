#include "tools/simplify/out_of_core_run.h"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iostream>

#include "formats/support/file_io.h"
#include "lib/meshio/mesh_writers.h"
#include "lib/outofcore/memory_size.h"
#include "lib/outofcore/out_of_core.h"
#include "lib/outofcore/work_folder_guard.h"

namespace lodbake::cli {
namespace {

namespace fs = std::filesystem;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::json plan_json(const OutOfCorePlan& plan, const std::string& work) {
  return {{"memory_limit", plan.memory_limit},
          {"blocks", plan.block_count()},
          {"block_budget", plan.block_budget},
          {"block_triangles", plan.block_triangles},
          {"block_ratio",
           plan.block_ratio ? nlohmann::json(*plan.block_ratio) : nlohmann::json(nullptr)},
          {"peak_estimate", plan.peak_estimate},
          {"dropped_degenerate", plan.dropped_degenerate},
          {"work", work}};
}

// The split into an existing or new folder that holds no plan yet.
Result<OutOfCorePlan> run_split(const Tool& tool, const OutOfCoreRequest& request, uint64_t limit) {
  std::error_code error;
  if (fs::exists(plan_path(request.work), error))
    return Status(ErrorKind::kUsage, "the work folder '" + request.work +
                                         "' already holds a split (plan.json); give a new one");
  fs::create_directories(request.work, error);
  if (error)
    return io_error("cannot make the work folder '" + request.work + "': " + error.message());
  OutOfCoreOptions options;
  options.memory_limit = limit;
  options.simplify = request.options;
  Progress progress(tool, "cutting into blocks");
  return split_input(request.input, request.work, options, [&](double f) { progress.update(f); });
}

Status run_blocks(const Tool& tool, const OutOfCorePlan& plan, const std::string& work,
                  unsigned threads) {
  Progress progress(tool, "simplifying blocks");
  for (uint32_t b = 0; b < plan.block_count(); ++b) {
    LODBAKE_RETURN_IF_ERROR(simplify_block(work, plan, b, threads));
    progress.update(static_cast<double>(b + 1) / plan.block_count());
  }
  return Status::ok();
}

// Writes the merged mesh to `output`, all or nothing.
Status write_output(const std::string& output, const TriangleMesh& mesh) {
  LODBAKE_ASSIGN_OR_RETURN(Bytes bytes, write_mesh_for_path(output, mesh));
  return write_file_atomic(output, bytes);
}

void print_result(const Tool& tool, const OutOfCoreRequest& request, const OutOfCorePlan& plan,
                  const MergeResult& merged, double seconds) {
  if (tool.json()) {
    tool.print_json(
        {{"schema", "lodbake.simplify/1"},
         {"input", request.input},
         {"input_counts",
          {{"vertices", plan.referenced_vertices}, {"triangles", plan.input_triangles}}},
         {"output_counts",
          {{"vertices", merged.mesh.vertex_count()}, {"triangles", merged.mesh.triangle_count()}}},
         {"seconds", seconds},
         {"collapses", merged.stats.collapses},
         {"max_collapse_error", merged.stats.max_collapse_error},
         {"metrics", nullptr},
         {"out_of_core",
          [&] {
            nlohmann::json j = plan_json(plan, request.work);
            j["stitched_triangles"] = merged.stitched_triangles;
            return j;
          }()},
         {"outputs", nlohmann::json::array({{{"file", request.output},
                                             {"vertices", merged.mesh.vertex_count()},
                                             {"triangles", merged.mesh.triangle_count()}}})}});
    return;
  }
  std::cout << "input         " << request.input << ": " << plan.referenced_vertices
            << " vertices, " << plan.input_triangles << " triangles\n";
  std::cout << "out of core   " << plan.block_count()
            << (plan.block_count() == 1 ? " block" : " blocks") << " of at most "
            << plan.block_budget << " triangles, stitched to " << merged.stitched_triangles
            << " triangles, estimated peak " << plan.peak_estimate << " bytes\n";
  std::cout << "simplified    " << merged.mesh.vertex_count() << " vertices, "
            << merged.mesh.triangle_count() << " triangles in " << seconds
            << " s (metrics are not measured out of core)\n";
  std::cout << "wrote         " << request.output << ": " << merged.mesh.triangle_count()
            << " triangles\n";
}

int run_one_shot(const Tool& tool, OutOfCoreRequest request, uint64_t limit) {
  if (request.work.empty()) {
    // Beside the output, not in /tmp: a tmpfs would hold the blocks in memory.
    fs::path folder = fs::absolute(request.output).parent_path();
    request.work = (folder / (".lodbake-work-" + std::to_string(::getpid()))).string();
  }
  // Removes the work files however the run ends, a signal included.
  WorkFolderGuard cleanup(request.work);
  const auto start = std::chrono::steady_clock::now();
  Result<OutOfCorePlan> plan = run_split(tool, request, limit);
  if (!plan.is_ok()) {
    if (plan.status().kind() == ErrorKind::kUsage) cleanup.release();
    return plan.status().kind() == ErrorKind::kUsage ? tool.usage_error(plan.status().message())
                                                     : tool.fail(request.input, plan.status());
  }
  if (Status done = run_blocks(tool, plan.value(), request.work, request.options.threads);
      !done.is_ok())
    return tool.fail(request.input, done);
  Progress progress(tool, "merging");
  Result<MergeResult> merged = merge_blocks(request.work, plan.value(), request.options.threads,
                                            [&](double f) { progress.update(f); });
  if (!merged.is_ok()) return tool.fail(request.input, merged.status());
  if (Status written = write_output(request.output, merged.value().mesh); !written.is_ok())
    return tool.fail(request.output, written);
  print_result(tool, request, plan.value(), merged.value(), seconds_since(start));
  return 0;
}

}  // namespace

int run_out_of_core(const Tool& tool, const OutOfCoreRequest& request) {
  uint64_t limit = 0;
  if (request.stage.empty() || request.stage == "split") {
    Result<uint64_t> parsed = parse_memory_size(request.memory_limit);
    if (!parsed.is_ok())
      return tool.fail(
          "", Status(parsed.status().kind(), "--memory-limit: " + parsed.status().message()));
    limit = parsed.value();
  }
  if (request.stage.empty()) return run_one_shot(tool, request, limit);
  if (request.stage == "split") {
    Result<OutOfCorePlan> plan = run_split(tool, request, limit);
    if (!plan.is_ok())
      return plan.status().kind() == ErrorKind::kUsage ? tool.usage_error(plan.status().message())
                                                       : tool.fail(request.input, plan.status());
    if (tool.json()) {
      tool.print_json({{"schema", "lodbake.simplify/1"},
                       {"input", request.input},
                       {"stage", "split"},
                       {"input_counts",
                        {{"vertices", plan.value().referenced_vertices},
                         {"triangles", plan.value().input_triangles}}},
                       {"out_of_core", plan_json(plan.value(), request.work)}});
    } else {
      std::cout << "split         " << request.input << " into " << plan.value().block_count()
                << " blocks in " << request.work << "\n";
    }
    return 0;
  }
  Result<OutOfCorePlan> plan = read_plan(request.work);
  if (!plan.is_ok()) return tool.fail(plan_path(request.work), plan.status());
  if (request.stage == "block") {
    Status done =
        simplify_block(request.work, plan.value(), request.block, request.options.threads);
    if (!done.is_ok()) return tool.fail(block_input_path(request.work, request.block), done);
    if (tool.json()) {
      tool.print_json({{"schema", "lodbake.simplify/1"},
                       {"stage", "block"},
                       {"block", request.block},
                       {"file", block_output_path(request.work, request.block)}});
    } else {
      std::cout << "simplified    block " << request.block << " into "
                << block_output_path(request.work, request.block) << "\n";
    }
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  Progress progress(tool, "merging");
  Result<MergeResult> merged = merge_blocks(request.work, plan.value(), request.options.threads,
                                            [&](double f) { progress.update(f); });
  if (!merged.is_ok()) return tool.fail(request.work, merged.status());
  if (Status written = write_output(request.output, merged.value().mesh); !written.is_ok())
    return tool.fail(request.output, written);
  print_result(tool, request, plan.value(), merged.value(), seconds_since(start));
  return 0;
}

}  // namespace lodbake::cli
