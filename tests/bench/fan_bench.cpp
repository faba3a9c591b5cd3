// Fan-merge hierarchy benchmark (issue 5; the paper's section 5 compares
// against a view-dependence tree): on each mesh, side by side in one run,
//   - lodbake build_fan_hierarchy(): build time (median of --runs), internal
//     nodes, depth, average children, FANH bytes;
//   - the edge-collapse hierarchy to the same vertex count (lodbake
//     simplify() recording the progressive mesh, half-edge placement): build
//     time, internal nodes (one per collapse), VSPL bytes;
//   - the balanced vertex hierarchy (lib/hierarchy, as lodbake-hierarchy and
//     lodbake-fan --compare build it): build + refinement-data time, internal
//     nodes, depth, VHIE + RFIN bytes, and its ratios to the fan hierarchy
//     (the paper: 4-6x the internal nodes, 1.3-1.7x the size);
//   - the runtime: the coarse path (fan-merge every node) against the fine
//     path (every child's collapse one at a time) from the input to the
//     coarsest mesh, and the operation counts each needs.
// Times are wall-clock medians and CPU seconds of this process (other jobs
// share the machine: compare the columns of one run, not across runs).
//
//   bench_fan [--runs N] [--markdown] FILE...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "formats/sections/fanh.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "lib/core/unreferenced_vertices.h"
#include "lib/fanmerge/fan_build.h"
#include "lib/fanmerge/fan_runtime.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/meshio/mesh_import.h"
#include "lib/simplify/simplify.h"

namespace {

using lodbake::TriangleMesh;

struct Timing {
  double wall = 0;
  double cpu = 0;
};

template <typename F>
Timing time_once(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  f();
  Timing t;
  t.cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

Timing median(std::vector<Timing> v) {
  std::sort(v.begin(), v.end(), [](const Timing& a, const Timing& b) { return a.wall < b.wall; });
  return v[v.size() / 2];
}

int usage() {
  std::fprintf(stderr, "usage: bench_fan [--runs N] [--markdown] FILE...\n");
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lodbake;
  int runs = 3;
  bool markdown = false;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--markdown") {
      markdown = true;
    } else if (!arg.empty() && arg[0] == '-') {
      return usage();
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) return usage();
  if (markdown) {
    std::printf(
        "| mesh | triangles | fan build s (cpu) | internal nodes | depth | avg children | FANH "
        "bytes | PM build s (cpu) | PM internal nodes | VSPL bytes | node ratio | size ratio | "
        "coarse path s (ops) | fine path s (ops) | balanced build s (cpu) | balanced internal "
        "nodes | "
        "balanced depth | VHIE+RFIN bytes | balanced node ratio | balanced size ratio |\n"
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
        "---:|---:|\n");
  }
  int status = 0;
  for (const std::string& file : files) {
    ImportReport report;
    auto loaded = import_mesh_file(file, &report);
    if (!loaded.is_ok()) {
      std::fprintf(stderr, "bench_fan: error: %s: %s\n", file.c_str(),
                   loaded.status().message().c_str());
      status = 2;
      continue;
    }
    TriangleMesh input = std::move(loaded).value();
    remove_unreferenced_vertices(input);
    input.normals = {};
    input.texcoords = {};
    const std::string name = file.substr(file.find_last_of('/') + 1);

    std::vector<Timing> fan_times;
    FanBuildResult fan;
    bool failed = false;
    for (int r = 0; r < runs && !failed; ++r) {
      fan_times.push_back(time_once([&] {
        Result<FanBuildResult> built = build_fan_hierarchy(input, {});
        if (!built.is_ok()) {
          std::fprintf(stderr, "bench_fan: error: %s: %s\n", file.c_str(),
                       built.status().message().c_str());
          failed = true;
          return;
        }
        fan = std::move(built).value();
      }));
    }
    if (failed) {
      status = 3;
      continue;
    }
    const FanhStats stats = fanh_stats(fan.hierarchy);
    const size_t fanh_bytes = encode_fanh(fan.hierarchy).value().size();

    SimplifyOptions pm_options;
    pm_options.record_pm = true;
    pm_options.target_triangles = fan.stats.output_triangles;
    std::vector<Timing> pm_times;
    uint64_t pm_nodes = 0;
    size_t vspl_bytes = 0;
    for (int r = 0; r < runs && !failed; ++r) {
      SimplifyResult simplified;
      pm_times.push_back(time_once([&] {
        Result<SimplifyResult> s = simplify(input, pm_options);
        if (!s.is_ok()) {
          failed = true;
          return;
        }
        simplified = std::move(s).value();
      }));
      if (!failed && r == 0) {
        pm_nodes = simplified.pm->splits.size();
        vspl_bytes = encode_vspl(*simplified.pm, {}).value().size();
      }
    }
    if (failed) {
      std::fprintf(stderr, "bench_fan: error: %s: simplify failed\n", file.c_str());
      status = 3;
      continue;
    }

    // Runtime: coarse and fine paths from the input to the coarsest mesh.
    Result<FanRuntime> created = FanRuntime::create(input, fan.hierarchy);
    if (!created.is_ok()) {
      status = 3;
      continue;
    }
    FanRuntime& rt = created.value();
    bool ok = true;
    const Timing coarse = time_once([&] { ok = rt.merge_all() && ok; });
    ok = rt.split_all() && ok;
    uint64_t fine_ops = 0;
    const Timing fine = time_once([&] {
      for (uint32_t node = rt.leaf_count(); node < rt.node_count(); ++node)
        while (!rt.fully_merged(node) && (ok = rt.advance(node) && ok))
          ++fine_ops;
    });
    if (!ok) {
      std::fprintf(stderr, "bench_fan: error: %s: the runtime refused a recorded step\n",
                   file.c_str());
      status = 3;
    }
    // The balanced vertex hierarchy of the same mesh, timed like
    // lodbake-hierarchy (build + refinement data); depth in edges as FANH's.
    std::vector<Timing> balanced_times;
    HierarchyShape shape;
    size_t balanced_bytes = 0;
    for (int r = 0; r < runs && !failed; ++r) {
      BalancedHierarchy balanced;
      std::vector<NodeRefinement> refinement;
      balanced_times.push_back(time_once([&] {
        Result<BalancedHierarchy> b = build_balanced_hierarchy(input, {});
        if (!b.is_ok()) {
          failed = true;
          return;
        }
        balanced = std::move(b).value();
        Result<std::vector<NodeRefinement>> rd = compute_refinement_data(balanced.hierarchy, input);
        if (!rd.is_ok()) {
          failed = true;
          return;
        }
        refinement = std::move(rd).value();
      }));
      if (!failed && r == 0) {
        shape = hierarchy_shape(balanced.hierarchy);
        balanced_bytes = encode_vhie(balanced.hierarchy).value().size() +
                         encode_rfin(balanced.hierarchy, refinement).value().size();
      }
    }
    if (failed) {
      std::fprintf(stderr, "bench_fan: error: %s: the balanced hierarchy failed\n", file.c_str());
      status = 3;
      continue;
    }
    const Timing balanced_t = median(balanced_times);
    const uint64_t balanced_depth = shape.depth > 0 ? shape.depth - 1 : 0;
    const double balanced_node_ratio =
        static_cast<double>(shape.splits) /
        static_cast<double>(std::max<uint64_t>(1, stats.internal_nodes));
    const double balanced_size_ratio =
        static_cast<double>(balanced_bytes) / static_cast<double>(std::max<size_t>(1, fanh_bytes));

    const Timing fan_t = median(fan_times), pm_t = median(pm_times);
    const double node_ratio = static_cast<double>(pm_nodes) /
                              static_cast<double>(std::max<uint64_t>(1, stats.internal_nodes));
    const double size_ratio =
        static_cast<double>(vspl_bytes) / static_cast<double>(std::max<size_t>(1, fanh_bytes));
    if (markdown) {
      std::printf(
          "| %s | %zu | %.3f (%.3f) | %llu | %llu | %.2f | %zu | %.3f (%.3f) | %llu | %zu | %.2f | "
          "%.2f | %.3f (%llu) | %.3f (%llu) | %.3f (%.3f) | %llu | %llu | %zu | %.2f | %.2f |\n",
          name.c_str(), input.triangle_count(), fan_t.wall, fan_t.cpu,
          static_cast<unsigned long long>(stats.internal_nodes),
          static_cast<unsigned long long>(stats.depth), stats.average_children, fanh_bytes,
          pm_t.wall, pm_t.cpu, static_cast<unsigned long long>(pm_nodes), vspl_bytes, node_ratio,
          size_ratio, coarse.wall, static_cast<unsigned long long>(stats.internal_nodes), fine.wall,
          static_cast<unsigned long long>(fine_ops), balanced_t.wall, balanced_t.cpu,
          static_cast<unsigned long long>(shape.splits),
          static_cast<unsigned long long>(balanced_depth), balanced_bytes, balanced_node_ratio,
          balanced_size_ratio);
    } else {
      std::printf("%s: %zu triangles -> %llu vertices, %llu triangles\n", name.c_str(),
                  input.triangle_count(),
                  static_cast<unsigned long long>(fan.stats.output_vertices),
                  static_cast<unsigned long long>(fan.stats.output_triangles));
      std::printf(
          "  fan hierarchy  build %.3f s (cpu %.3f s), %llu internal nodes, depth %llu, %.2f "
          "children on average, FANH %zu bytes\n",
          fan_t.wall, fan_t.cpu, static_cast<unsigned long long>(stats.internal_nodes),
          static_cast<unsigned long long>(stats.depth), stats.average_children, fanh_bytes);
      std::printf(
          "  edge collapses build %.3f s (cpu %.3f s), %llu internal nodes, VSPL %zu bytes: "
          "%.2fx the nodes, %.2fx the bytes of the fan hierarchy\n",
          pm_t.wall, pm_t.cpu, static_cast<unsigned long long>(pm_nodes), vspl_bytes, node_ratio,
          size_ratio);
      std::printf(
          "  balanced       build %.3f s (cpu %.3f s), %llu internal nodes, depth %llu, VHIE+RFIN "
          "%zu bytes: %.2fx the nodes, %.2fx the bytes of the fan hierarchy\n",
          balanced_t.wall, balanced_t.cpu, static_cast<unsigned long long>(shape.splits),
          static_cast<unsigned long long>(balanced_depth), balanced_bytes, balanced_node_ratio,
          balanced_size_ratio);
      std::printf(
          "  runtime        coarse path %.3f s (%llu fan-merges), fine path %.3f s (%llu edge "
          "collapses)\n",
          coarse.wall, static_cast<unsigned long long>(stats.internal_nodes), fine.wall,
          static_cast<unsigned long long>(fine_ops));
    }
    std::fflush(stdout);
  }
  return status;
}
