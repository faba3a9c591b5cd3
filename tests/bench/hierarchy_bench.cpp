// Balanced vertex hierarchy against OpenMesh's mkbalancedpm (Debian
// libopenmesh-apps, /usr/bin/OpenMesh-mkbalancedpm: the VDPM reference of
// Kim, Lee and Kobbelt's streaming paper), side by side in one run on the
// same inputs:
//   - lodbake: build_balanced_hierarchy() + compute_refinement_data(), timed
//     from the TriangleMesh to the hierarchy; output bytes = the container
//     lodbake-hierarchy writes (META + BASE + VHIE + RFIN);
//   - mkbalancedpm: run as a subprocess on the same TriangleMesh written as
//     OFF (unreferenced vertices dropped, so neither side counts them as
//     roots); its wall time includes reading the OFF file, which is a small
//     part of it; depth and bits are the "<tree-id, node-id>" line it prints,
//     output bytes the size of its .pm file (which holds no refinement data
//     and no cut vertices: the VDPM data is built from it later).
// Wall and CPU times are medians of --runs runs (mkbalancedpm's CPU time is
// its child-process usage); other work shares the machine, so the speed-up
// is computed from CPU time.
//
//   bench_hierarchy [--runs N] [--markdown] [--peer PATH] FILE...
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/support/file_io.h"
#include "lib/core/unreferenced_vertices.h"
#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/meshio/mesh_import.h"
#include "lib/meshio/mesh_writers.h"
#include "tests/bench/bench_support.h"

namespace {

using lodbake::TriangleMesh;
using lodbake::bench::Clock;
using lodbake::bench::cpu_seconds;
using lodbake::bench::median;
using lodbake::bench::seconds_since;

struct Row {
  bool ok = false;
  std::string error;
  double seconds = 0;
  double cpu = 0;
  uint64_t roots = 0;
  int tree_bits = 0;
  int node_bits = 0;
  uint64_t bytes = 0;
};

Row run_lodbake(const TriangleMesh& mesh, int runs) {
  Row row;
  std::vector<double> times;
  std::vector<double> cpu;
  lodbake::Result<lodbake::BalancedHierarchy> built = lodbake::runtime_error("not run");
  lodbake::Result<std::vector<lodbake::NodeRefinement>> rfin = lodbake::runtime_error("not run");
  for (int r = 0; r < runs; ++r) {
    const auto start = Clock::now();
    const double cpu_start = cpu_seconds(RUSAGE_SELF);
    built = lodbake::build_balanced_hierarchy(mesh, lodbake::BalancedBuildOptions());
    if (!built.is_ok()) {
      row.error = built.status().message();
      return row;
    }
    rfin = lodbake::compute_refinement_data(built.value().hierarchy, mesh);
    times.push_back(seconds_since(start));
    cpu.push_back(cpu_seconds(RUSAGE_SELF) - cpu_start);
    if (!rfin.is_ok()) {
      row.error = rfin.status().message();
      return row;
    }
  }
  const lodbake::VertexHierarchy& h = built.value().hierarchy;
  const lodbake::HierarchyShape shape = lodbake::hierarchy_shape(h);
  lodbake::MetaSection meta = lodbake::make_meta("lodbake-hierarchy");
  lodbake::ContainerWriter writer;
  auto add = [&](const char* tag, lodbake::Result<lodbake::Bytes> bytes) {
    return bytes.is_ok() && writer.add_section(tag, std::move(bytes).value(), true).is_ok();
  };
  if (!add(lodbake::kMetaTag, lodbake::encode_meta(meta)) ||
      !add(lodbake::kBaseTag, lodbake::encode_base(h.base, lodbake::BaseEncodeOptions())) ||
      !add(lodbake::kVhieTag, lodbake::encode_vhie(h)) ||
      !add(lodbake::kRfinTag, lodbake::encode_rfin(h, rfin.value()))) {
    row.error = "encoding failed";
    return row;
  }
  lodbake::Result<lodbake::Bytes> file = writer.finish();
  row.ok = file.is_ok();
  row.bytes = file.is_ok() ? file.value().size() : 0;
  row.seconds = median(times);
  row.cpu = median(cpu);
  row.roots = shape.roots;
  row.tree_bits = shape.tree_bits;
  row.node_bits = static_cast<int>(shape.depth);
  return row;
}

Row run_mkbalancedpm(const std::string& peer, const TriangleMesh& mesh, int runs,
                     const std::string& scratch) {
  Row row;
  const std::string off = scratch + ".off";
  const std::string pm = scratch + ".pm";
  const std::string log = scratch + ".log";
  lodbake::Result<lodbake::Bytes> text = lodbake::write_mesh_for_path(off, mesh);
  if (!text.is_ok() || !lodbake::write_file_atomic(off, text.value()).is_ok()) {
    row.error = "cannot write " + off;
    return row;
  }
  const lodbake::bench::ToolRun run = lodbake::bench::run_tool({peer, "-o", pm, off}, log, runs);
  if (run.exit_status != 0) {
    row.error = "mkbalancedpm exited with status " + std::to_string(run.exit_status);
    return row;
  }
  std::ifstream in(log);
  std::stringstream all;
  all << in.rdbuf();
  std::smatch m;
  const std::string out = all.str();
  if (!std::regex_search(out, m, std::regex("<tree-id, node-id>: <([0-9]+), ([0-9]+)>"))) {
    row.error = "no <tree-id, node-id> line in its output";
    return row;
  }
  row.tree_bits = std::atoi(m[1].str().c_str());
  row.node_bits = std::atoi(m[2].str().c_str());
  lodbake::Result<lodbake::Bytes> pm_bytes = lodbake::read_file(pm);
  row.bytes = pm_bytes.is_ok() ? pm_bytes.value().size() : 0;
  if (pm_bytes.is_ok() && pm_bytes.value().size() >= 12) {
    uint32_t base = 0;
    std::memcpy(&base, pm_bytes.value().data() + 8, 4);
    row.roots = base;
  }
  row.seconds = run.wall_seconds;
  row.cpu = run.cpu_seconds;
  row.ok = true;
  std::remove(off.c_str());
  std::remove(pm.c_str());
  std::remove(log.c_str());
  return row;
}

int usage() {
  std::fprintf(stderr, "usage: bench_hierarchy [--runs N] [--markdown] [--peer PATH] FILE...\n");
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  bool markdown = false;
  std::string peer = "/usr/bin/OpenMesh-mkbalancedpm";
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--runs" && has_value) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--peer" && has_value) {
      peer = argv[++i];
    } else if (arg == "--markdown") {
      markdown = true;
    } else if (!arg.empty() && arg[0] == '-') {
      return usage();
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) return usage();
  const bool have_peer = lodbake::bench::tool_installed(peer);
  if (!have_peer)
    std::fprintf(stderr, "bench_hierarchy: %s not found, lodbake only\n", peer.c_str());
  if (markdown) {
    std::printf(
        "| mesh | vertices | method | wall s | CPU s | roots | <tree, node> bits | total bits | "
        "output bytes | lodbake CPU speed-up "
        "|\n|---|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
  } else {
    std::printf("%-26s %9s %-13s %9s %9s %7s %10s %6s %11s %9s\n", "mesh", "vertices", "method",
                "wall s", "CPU s", "roots", "bits", "total", "bytes", "speed-up");
  }
  int status = 0;
  for (const std::string& file : files) {
    lodbake::ImportReport report;
    auto loaded = lodbake::import_mesh_file(file, &report);
    if (!loaded.is_ok()) {
      std::fprintf(stderr, "bench_hierarchy: error: %s: %s\n", file.c_str(),
                   loaded.status().message().c_str());
      status = 2;
      continue;
    }
    TriangleMesh input = std::move(loaded).value();
    lodbake::remove_unreferenced_vertices(input);
    input.normals = {};
    input.texcoords = {};
    const std::string name = file.substr(file.find_last_of('/') + 1);
    std::fprintf(stderr, "bench_hierarchy: %s: %zu vertices, %zu triangles\n", name.c_str(),
                 input.vertex_count(), input.triangle_count());
    std::vector<std::pair<std::string, Row>> rows;
    rows.emplace_back("lodbake", run_lodbake(input, runs));
    if (have_peer) {
      const std::string scratch = "/tmp/bench_hierarchy_" + std::to_string(::getpid());
      rows.emplace_back("mkbalancedpm", run_mkbalancedpm(peer, input, runs, scratch));
    }
    for (const auto& [method, row] : rows) {
      if (!row.ok) {
        std::printf("%-26s %-13s failed: %s\n", name.c_str(), method.c_str(), row.error.c_str());
        status = 3;
        continue;
      }
      // CPU time: robust when other work shares the cores.
      const double speedup = method == "lodbake" || !rows.front().second.ok
                                 ? 1.0
                                 : row.cpu / std::max(1e-9, rows.front().second.cpu);
      char bits[32];
      std::snprintf(bits, sizeof(bits), "<%d, %d>", row.tree_bits, row.node_bits);
      if (markdown) {
        std::printf("| %s | %zu | %s | %.3f | %.3f | %llu | %s | %d | %llu | %.1f |\n",
                    name.c_str(), input.vertex_count(), method.c_str(), row.seconds, row.cpu,
                    static_cast<unsigned long long>(row.roots), bits, row.tree_bits + row.node_bits,
                    static_cast<unsigned long long>(row.bytes), speedup);
      } else {
        std::printf("%-26s %9zu %-13s %9.3f %9.3f %7llu %10s %6d %11llu %9.1f\n", name.c_str(),
                    input.vertex_count(), method.c_str(), row.seconds, row.cpu,
                    static_cast<unsigned long long>(row.roots), bits, row.tree_bits + row.node_bits,
                    static_cast<unsigned long long>(row.bytes), speedup);
      }
    }
  }
  return status;
}
