// Size and build time of the split DAG (DAGE) and the vertex trees (VTRE)
// built from the progressive mesh lodbake-simplify records (half-edge
// placement, simplified as far as legal), or with --balanced from the
// balanced vertex hierarchy's PM (hierarchy_to_progressive_mesh, what
// lodbake-hierarchy stores DAGE and VTRE for). Per mesh: nodes, edges, roots and
// leaves of the DAG, bytes per node of each section, the average stored size
// of each kind of vertex-tree record, and build times (median of --runs,
// wall clock; other processes share the cores, so compare ratios within one
// run). The PM recording (or the hierarchy build and conversion) is timed
// once for scale.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "formats/sections/dage.h"
#include "formats/sections/vtre.h"
#include "lib/core/unreferenced_vertices.h"
#include "lib/dag/vsplit_dag_builder.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/hierarchy_to_pm.h"
#include "lib/meshio/mesh_import.h"
#include "lib/simplify/simplify.h"
#include "lib/vtrees/vertex_tree_builder.h"
#include "tests/bench/bench_support.h"

namespace {

using lodbake::bench::Clock;
using lodbake::bench::median;
using lodbake::bench::seconds_since;

double per(uint64_t bits, uint64_t count) {
  return count == 0 ? 0 : static_cast<double>(bits) / 8.0 / static_cast<double>(count);
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  bool balanced = false;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--balanced") {
      balanced = true;
    } else if (arg == "--help") {
      std::printf("usage: bench_dag [--runs N] [--balanced] MESH...\n");
      return 0;
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "bench_dag: error: no mesh given. See 'bench_dag --help'.\n");
    return 1;
  }
  int status = 0;
  std::printf(
      "| mesh | splits | DAG edges | edges/node | roots | leaves | DAGE B/node | VTRE B/node | "
      "base rec B | left rec B | right rec B | %s | DAG build s | VTRE build s | DAG validate s "
      "|\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
      balanced ? "hierarchy + PM s" : "PM s");
  for (const std::string& file : files) {
    lodbake::ImportReport report;
    auto loaded = lodbake::import_mesh_file(file, &report);
    if (!loaded.is_ok()) {
      std::fprintf(stderr, "bench_dag: error: %s: %s\n", file.c_str(),
                   loaded.status().message().c_str());
      status = 2;
      continue;
    }
    lodbake::TriangleMesh input = std::move(loaded).value();
    lodbake::remove_unreferenced_vertices(input);
    input.normals = {};
    input.texcoords = {};
    lodbake::ProgressiveMesh pm;
    const Clock::time_point pm_start = Clock::now();
    if (balanced) {
      auto built = lodbake::build_balanced_hierarchy(input, lodbake::BalancedBuildOptions());
      auto converted = built.is_ok()
                           ? lodbake::hierarchy_to_progressive_mesh(built.value().hierarchy)
                           : lodbake::Result<lodbake::ProgressiveMesh>(built.status());
      if (!converted.is_ok()) {
        std::fprintf(stderr, "bench_dag: error: %s: %s\n", file.c_str(),
                     converted.status().message().c_str());
        status = 4;
        continue;
      }
      pm = std::move(converted).value();
    } else {
      lodbake::SimplifyOptions options;
      options.record_pm = true;
      auto simplified = lodbake::simplify(input, options);
      if (!simplified.is_ok()) {
        std::fprintf(stderr, "bench_dag: error: %s: %s\n", file.c_str(),
                     simplified.status().message().c_str());
        status = 4;
        continue;
      }
      pm = std::move(*simplified.value().pm);
    }
    const double pm_seconds = seconds_since(pm_start);
    std::vector<double> dag_times, vtre_times, validate_times;
    lodbake::VsplitDag dag;
    lodbake::VertexTrees trees;
    bool ok = true;
    for (int r = 0; r < runs && ok; ++r) {
      Clock::time_point start = Clock::now();
      auto built = lodbake::build_vsplit_dag(pm);
      dag_times.push_back(seconds_since(start));
      start = Clock::now();
      auto built_trees = lodbake::build_vertex_trees(pm);
      vtre_times.push_back(seconds_since(start));
      if (!built.is_ok() || !built_trees.is_ok()) {
        std::fprintf(stderr, "bench_dag: error: %s: %s\n", file.c_str(),
                     (built.is_ok() ? built_trees.status() : built.status()).message().c_str());
        ok = false;
        break;
      }
      dag = std::move(built).value();
      trees = std::move(built_trees).value();
      start = Clock::now();
      const std::vector<std::string> findings = lodbake::validate_dage(dag);
      validate_times.push_back(seconds_since(start));
      if (!findings.empty()) {
        std::fprintf(stderr, "bench_dag: error: %s: %s\n", file.c_str(), findings[0].c_str());
        ok = false;
      }
    }
    if (!ok) {
      status = 4;
      continue;
    }
    auto dage = lodbake::encode_dage(dag);
    auto vtre = lodbake::encode_vtre(trees);
    if (!dage.is_ok() || !vtre.is_ok()) {
      std::fprintf(stderr, "bench_dag: error: %s: cannot encode\n", file.c_str());
      status = 4;
      continue;
    }
    auto summary = lodbake::read_dage_summary(dage.value().data(), dage.value().size());
    const lodbake::VtreRecordSizes sizes = lodbake::vtre_record_sizes(trees);
    const size_t nodes = dag.node_count();
    const std::string name = file.substr(file.find_last_of('/') + 1);
    std::printf(
        "| %s | %zu | %zu | %.2f | %u | %u | %.2f | %.2f | %.2f | %.2f | %.2f | %.3f | %.3f | "
        "%.3f | %.3f |\n",
        name.c_str(), nodes, dag.edge_count(),
        nodes ? static_cast<double>(dag.edge_count()) / nodes : 0.0, summary.value().root_count,
        summary.value().leaf_count, nodes ? static_cast<double>(dage.value().size()) / nodes : 0.0,
        static_cast<double>(vtre.value().size()) / static_cast<double>(trees.node_count()),
        per(sizes.base_bits, sizes.base_records), per(sizes.left_bits, sizes.left_records),
        per(sizes.right_bits, sizes.right_records), pm_seconds, median(dag_times),
        median(vtre_times), median(validate_times));
    std::fflush(stdout);
  }
  return status;
}
