// Triangle strips and the SETS strip graph (Belmonte, Aguado, Sancho 2006):
//   1. lodbake's stripifier against meshoptimizer's meshopt_stripify on the
//      same full-resolution mesh (input order, and for meshopt also after
//      meshopt_optimizeVertexCache, which its documentation recommends):
//      indices per triangle with one restart index between strips, swaps,
//      whether every triangle keeps its orientation, time;
//   2. the SETS graph: build time and SETS section bytes next to the
//      paper's in-memory sizes (Table 2);
//   3. the paper's recovery tests (section 4, after Ribelles et al. 1999):
//      recover 1, 3, 6, 10, 15 and 20% of all LoDs, spaced linearly or
//      exponentially (dense near the full mesh), from the finest LoD to the
//      coarsest and back (the sequences of lib/replay/sets_replay.h, which
//      lodbake-replay --mode sets runs too); average time per recovered LoD in microseconds,
//      recovery only (no rendering), for coherent recovery (the paper's) and
//      for fresh recovery of every strip (on at most 100 of the test's LoDs,
//      evenly picked); and the walk throughput in strip indices per second
//      (indices written by the fresh walks / their time; the target is at
//      least 50 M/s).
// Times are the thread's CPU time (other processes share the machine's two
// cores; wall time would count their turns), medians over --runs runs.
//
//   bench_strips [--runs N] FILE...
#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "formats/sections/sets.h"
#include "formats/sections/strp.h"
#include "lib/ingest/load_mesh.h"
#include "lib/replay/sets_replay.h"
#include "lib/simplify/pm_replay.h"
#include "lib/simplify/simplify.h"
#include "lib/strips/sets_build.h"
#include "lib/strips/sets_recovery.h"
#include "lib/strips/stripify.h"

namespace {

using namespace lodbake;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double thread_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

TriangleMesh with_triangles(size_t vertices, std::vector<Triangle> triangles) {
  TriangleMesh mesh;
  mesh.positions.assign(vertices, Vec3f{0, 0, 0});
  mesh.triangles = std::move(triangles);
  return mesh;
}

// meshopt's strip buffer (restart index ~0u) as triangles with the window
// rule, restarting the parity after each restart.
std::vector<Triangle> meshopt_triangles(const std::vector<unsigned>& strip) {
  std::vector<Triangle> out;
  size_t begin = 0;
  for (size_t i = 0; i <= strip.size(); ++i) {
    if (i == strip.size() || strip[i] == ~0u) {
      append_strip_triangles(strip.data() + begin, i - begin, &out);
      begin = i + 1;
    }
  }
  return out;
}

struct StripRow {
  const char* method;
  double indices_per_triangle = 0;
  uint64_t strips = 0;
  double seconds = 0;
  bool oriented = false;
};

std::vector<StripRow> compare_stripifiers(const TriangleMesh& mesh, int runs) {
  std::vector<StripRow> rows;
  const double triangles = static_cast<double>(mesh.triangle_count());
  {
    StripRow row{"lodbake stripify"};
    std::vector<double> times;
    StripifyStats stats;
    Result<TriangleStrips> strips = runtime_error("not run");
    for (int r = 0; r < runs; ++r) {
      const auto start = Clock::now();
      strips = stripify(mesh, &stats);
      times.push_back(seconds_since(start));
    }
    row.seconds = median(times);
    row.indices_per_triangle = stats.indices_per_triangle();
    row.strips = stats.strips;
    row.oriented = same_oriented_triangles(
        mesh, with_triangles(mesh.vertex_count(), strip_triangles(strips.value())));
    rows.push_back(row);
  }
  std::vector<unsigned> list;
  for (const Triangle& t : mesh.triangles)
    list.insert(list.end(), t.begin(), t.end());
  std::vector<unsigned> optimized(list.size());
  meshopt_optimizeVertexCache(optimized.data(), list.data(), list.size(), mesh.vertex_count());
  for (int variant = 0; variant < 2; ++variant) {
    StripRow row{variant == 0 ? "meshopt_stripify" : "meshopt_stripify (cache-optimized)"};
    const std::vector<unsigned>& in = variant == 0 ? list : optimized;
    std::vector<unsigned> strip(meshopt_stripifyBound(in.size()));
    size_t size = 0;
    std::vector<double> times;
    for (int r = 0; r < runs; ++r) {
      const auto start = Clock::now();
      size = meshopt_stripify(strip.data(), in.data(), in.size(), mesh.vertex_count(), ~0u);
      times.push_back(seconds_since(start));
    }
    strip.resize(size);
    row.seconds = median(times);
    row.indices_per_triangle = static_cast<double>(size) / triangles;
    row.strips = 1 + std::count(strip.begin(), strip.end(), ~0u);
    row.oriented = same_oriented_triangles(
        mesh, with_triangles(mesh.vertex_count(), meshopt_triangles(strip)));
    rows.push_back(row);
  }
  return rows;
}

struct RecoveryRow {
  double coherent_us = 0;  // per recovered LoD
  double fresh_us = 0;
  double walk_rate = 0;    // indices written per second of walking (fresh)
  double output_rate = 0;  // indices of the recovered LoDs per second (coherent)
  size_t lods = 0;
};

RecoveryRow run_test(const SetsGraph& graph, const std::vector<uint32_t>& lods, int runs) {
  RecoveryRow row;
  row.lods = lods.size();
  std::vector<uint32_t> sample;
  const size_t stride = lods.size() / 100 + 1;
  for (size_t i = 0; i < lods.size(); i += stride)
    sample.push_back(lods[i]);
  std::vector<double> coherent_times, fresh_times;
  uint64_t fresh_indices = 0, output_indices = 0;
  for (int r = 0; r < runs; ++r) {
    StripRecovery coherent = StripRecovery::create(graph).value();
    StripRecovery fresh = StripRecovery::create(graph).value();
    uint64_t walked = 0, output = 0;
    double start = thread_seconds();
    for (uint32_t lod : lods) {
      if (!coherent.recover_coherent(lod).is_ok()) std::abort();
      output += coherent.index_count();
    }
    coherent_times.push_back(thread_seconds() - start);
    start = thread_seconds();
    for (uint32_t lod : sample) {
      if (!fresh.recover(lod).is_ok()) std::abort();
      walked += fresh.walked_indices();
    }
    fresh_times.push_back(thread_seconds() - start);
    fresh_indices = walked;
    output_indices = output;
  }
  const double coherent = median(coherent_times), fresh = median(fresh_times);
  row.coherent_us = coherent * 1e6 / lods.size();
  row.fresh_us = fresh * 1e6 / sample.size();
  row.walk_rate = fresh_indices / fresh;
  row.output_rate = output_indices / coherent;
  return row;
}

int bench_file(const std::string& path, int runs) {
  // The tools' import: what lodbake-strips takes, repaired by default as
  // the tool does (the Draco dragon loses its zero-area triangles).
  LoadOptions options;
  options.drop_unreferenced = true;
  LoadedMesh loaded;
  Status status = load_mesh(path, options, &loaded);
  if (!status.is_ok()) {
    std::fprintf(stderr, "bench_strips: %s: %s\n", path.c_str(), status.message().c_str());
    return 1;
  }
  loaded.mesh.normals = MeshAttribute();
  loaded.mesh.texcoords = MeshAttribute();
  SimplifyOptions simplify_options;
  simplify_options.record_pm = true;
  Result<SimplifyResult> simplified = simplify(loaded.mesh, simplify_options);
  if (!simplified.is_ok()) {
    std::fprintf(stderr, "bench_strips: %s: %s\n", path.c_str(),
                 simplified.status().message().c_str());
    return 1;
  }
  const ProgressiveMesh& pm = *simplified.value().pm;
  const TriangleMesh full = mesh_at_lod(pm, pm.full_vertex_count()).value();
  const std::string name = path.substr(path.find_last_of('/') + 1);
  std::printf("\n### %s: %zu vertices, %zu triangles, %zu LoDs\n\n", name.c_str(),
              full.vertex_count(), full.triangle_count(), pm.splits.size() + 1);

  std::printf("| stripifier | indices/triangle | strips | orientation kept | ms |\n");
  std::printf("|---|---:|---:|---|---:|\n");
  for (const StripRow& row : compare_stripifiers(full, runs))
    std::printf("| %s | %.3f | %llu | %s | %.1f |\n", row.method, row.indices_per_triangle,
                static_cast<unsigned long long>(row.strips), row.oriented ? "yes" : "no",
                row.seconds * 1e3);

  const TriangleStrips strips = stripify(full).value();
  SetsBuildStats build_stats;
  auto start = Clock::now();
  const SetsGraph graph = build_sets(strips, pm, &build_stats).value();
  const double build_seconds = seconds_since(start);
  const Bytes bytes = encode_sets(graph).value();
  std::printf(
      "\nSETS: built in %.2f s; %zu strips, %zu nodes, %zu arcs, %zu successors; section %.3f MB "
      "(%.1f bytes per triangle). Paper, in memory: Cow 0.338 MB (5,804 triangles), Bunny 4.150 MB "
      "(69,451), Phone 9.832 MB (165,963), i.e. 58-61 bytes per triangle.\n\n",
      build_seconds, graph.strip_count(), graph.node_count(), graph.arc_count(),
      graph.successors.size(), bytes.size() / 1e6,
      static_cast<double>(bytes.size()) / full.triangle_count());

  std::printf(
      "| LoDs | spacing | recovered | coherent us/LoD | fresh us/LoD | fresh walk M indices/s | "
      "coherent output M indices/s |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---:|\n");
  for (LodSpacing spacing : {LodSpacing::kLinear, LodSpacing::kExponential}) {
    for (double percent : paper_recovery_percents()) {
      const std::vector<uint32_t> lods = recovery_test_lods(graph.lod_count, percent, spacing);
      const RecoveryRow row = run_test(graph, lods, runs);
      std::printf("| %.0f%% | %s | %zu | %.1f | %.1f | %.0f | %.0f |\n", percent,
                  spacing_name(spacing), row.lods, row.coherent_us, row.fresh_us,
                  row.walk_rate / 1e6, row.output_rate / 1e6);
    }
  }
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: bench_strips [--runs N] FILE...\n");
    return 1;
  }
  int failures = 0;
  for (const std::string& file : files)
    failures += bench_file(file, runs);
  return failures == 0 ? 0 : 1;
}
