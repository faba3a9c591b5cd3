// Simplification speed and quality: lodbake's engine against the peers from
// Debian's packages, side by side in one run on the same inputs:
//   - lodbake simplify(), half-edge placement, progressive mesh recorded
//     (compiled in when the lodbake_simplify library exists);
//   - meshoptimizer meshopt_simplify (no error limit, no options);
//   - OpenMesh DecimaterT with ModQuadricT (no error limit);
//   - CGAL Surface_mesh_simplification::edge_collapse with
//     GarlandHeckbert_plane_policies (cost and placement) and a face-count stop.
// Every method gets the same TriangleMesh (lodbake's reader, unreferenced
// vertices dropped, nothing welded) and the same triangle target, and is
// timed from that TriangleMesh to a compact TriangleMesh: building the
// peer's own structure and extracting its result are part of the time, as
// they are part of lodbake's simplify(). The library call alone is shown as
// "core s" for the peers. The time is the median of --runs runs, taken in
// turns (run 1 of every method, then run 2, ...) so that a change in the
// load of a shared machine falls on all methods alike. The peers are single
// threaded; lodbake is too, unless --threads N (0: every core) runs the
// parallel steps of its passes on N threads. The throughput and lodbake's
// speed-ups are computed from the wall time ("seconds", what a baking job
// waits for); the process CPU time ("cpu s", the work summed over threads,
// which other jobs on a shared machine disturb far less) gives a second
// speed-up, lodbake's per-core efficiency. The error of the result is
// measured once with lib/metrics (symmetric Hausdorff and mean distance
// relative to the input's bounding-box diagonal).
//
//   bench_simplify [--runs N] [--ratios 0.5,0.1,0.01] [--peers LIST]
//                  [--threads N] [--height-guard] [--height-guard-factor F]
//                  [--placement half|optimal] [--samples N] [--markdown] FILE...
//
// --height-guard runs lodbake with SimplifyOptions::height_guard;
// --height-guard-factor F with that guard and height_guard_factor = F.
// --placement optimal runs lodbake with the quadric's minimiser, as CGAL's
// Garland-Heckbert placement does, to compare the two like for like.
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <meshoptimizer.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "lib/core/unreferenced_vertices.h"
#include "lib/meshio/mesh_import.h"
#include "lib/metrics/surface_distance.h"
#ifdef LODBAKE_BENCH_WITH_SIMPLIFY
#include "lib/simplify/simplify.h"
#endif
#include "tests/bench/bench_support.h"

namespace {

using lodbake::Triangle;
using lodbake::TriangleMesh;
using lodbake::Vec3f;
using lodbake::bench::Clock;
using lodbake::bench::seconds_since;

struct Outcome {
  bool ok = false;
  std::string error;
  TriangleMesh mesh;        // compact: every vertex referenced
  double core_seconds = 0;  // the library call alone (peers); 0 when not separable
};

Outcome failure(std::string message) {
  Outcome o;
  o.error = std::move(message);
  return o;
}

// Builds a compact mesh from triangles that index `positions`.
TriangleMesh compact(const std::vector<Vec3f>& positions, const std::vector<Triangle>& triangles) {
  TriangleMesh out;
  std::vector<uint32_t> remap(positions.size(), UINT32_MAX);
  out.triangles.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    Triangle mapped;
    for (int k = 0; k < 3; ++k) {
      uint32_t& slot = remap[t[k]];
      if (slot == UINT32_MAX) {
        slot = static_cast<uint32_t>(out.positions.size());
        out.positions.push_back(positions[t[k]]);
      }
      mapped[k] = slot;
    }
    out.triangles.push_back(mapped);
  }
  return out;
}

#ifdef LODBAKE_BENCH_WITH_SIMPLIFY
unsigned lodbake_threads = 1;
bool lodbake_height_guard = false;
double lodbake_height_guard_factor = lodbake::kDefaultHeightGuardFactor;
lodbake::Placement lodbake_placement = lodbake::Placement::kHalf;

Outcome run_lodbake(const TriangleMesh& input, uint64_t target) {
  lodbake::SimplifyOptions options;
  options.threads = lodbake_threads;
  options.height_guard = lodbake_height_guard;
  options.height_guard_factor = lodbake_height_guard_factor;
  options.placement = lodbake_placement;
  options.target_triangles = target;
  options.record_pm = true;
  auto result = lodbake::simplify(input, options);
  if (!result.is_ok()) return failure(result.status().message());
  Outcome o;
  o.ok = true;
  o.mesh = std::move(result).value().mesh;
  return o;
}
#endif

Outcome run_meshopt(const TriangleMesh& input, uint64_t target) {
  static_assert(sizeof(Triangle) == 3 * sizeof(unsigned int), "index buffer layout");
  const auto* indices = reinterpret_cast<const unsigned int*>(input.triangles.data());
  const size_t index_count = input.triangles.size() * 3;
  std::vector<Triangle> out(input.triangles.size());
  auto start = Clock::now();
  // FLT_MAX: no error limit, so only the triangle target stops it (as for the others).
  const size_t n = meshopt_simplify(reinterpret_cast<unsigned int*>(out.data()), indices,
                                    index_count, input.positions[0].data(), input.positions.size(),
                                    sizeof(Vec3f), target * 3, FLT_MAX, 0, nullptr);
  Outcome o;
  o.core_seconds = seconds_since(start);
  out.resize(n / 3);
  o.mesh = compact(input.positions, out);
  o.ok = true;
  return o;
}

Outcome run_openmesh(const TriangleMesh& input, uint64_t target) {
  using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
  using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
  using Quadric = OpenMesh::Decimater::ModQuadricT<Mesh>;
  Mesh mesh;
  mesh.reserve(input.positions.size(), input.triangles.size() * 3 / 2 + 16, input.triangles.size());
  std::vector<Mesh::VertexHandle> handles;
  handles.reserve(input.positions.size());
  for (const Vec3f& p : input.positions)
    handles.push_back(mesh.add_vertex({p[0], p[1], p[2]}));
  size_t refused = 0;
  for (const Triangle& t : input.triangles) {
    if (!mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]).is_valid()) ++refused;
  }
  if (refused > 0) return failure(std::to_string(refused) + " triangles refused by OpenMesh");
  auto start = Clock::now();
  {
    Decimater decimater(mesh);
    Quadric::Handle quadric;
    decimater.add(quadric);
    decimater.module(quadric).unset_max_err();
    if (!decimater.initialize()) return failure("decimater did not initialize");
    decimater.decimate_to_faces(0, target);
    // Before the decimater goes: its destructor releases the status
    // properties that mark the collapsed elements as deleted.
    mesh.garbage_collection();
  }
  Outcome o;
  o.core_seconds = seconds_since(start);
  std::vector<Vec3f> positions;
  positions.reserve(mesh.n_vertices());
  for (Mesh::VertexHandle v : mesh.vertices()) {
    const Mesh::Point& p = mesh.point(v);
    positions.push_back({p[0], p[1], p[2]});
  }
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.n_faces());
  for (Mesh::FaceHandle f : mesh.faces()) {
    Triangle t;
    int k = 0;
    for (Mesh::VertexHandle v : mesh.fv_range(f))
      t[k++] = static_cast<uint32_t>(v.idx());
    triangles.push_back(t);
  }
  o.mesh = compact(positions, triangles);
  o.ok = true;
  return o;
}

// Stops when the mesh has at most `target` faces (CGAL 5.5 only ships edge
// count predicates).
template <typename SurfaceMesh>
struct FaceCountStop {
  const SurfaceMesh* mesh;
  size_t target;
  template <typename Cost, typename Profile>
  bool operator()(const Cost&, const Profile&, std::size_t, std::size_t) const {
    return mesh->number_of_faces() <= target;
  }
};

Outcome run_cgal(const TriangleMesh& input, uint64_t target) {
  namespace sms = CGAL::Surface_mesh_simplification;
  using Kernel = CGAL::Simple_cartesian<double>;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh mesh;
  mesh.reserve(static_cast<Mesh::size_type>(input.positions.size()),
               static_cast<Mesh::size_type>(input.triangles.size() * 3 / 2 + 16),
               static_cast<Mesh::size_type>(input.triangles.size()));
  std::vector<Mesh::Vertex_index> handles;
  handles.reserve(input.positions.size());
  for (const Vec3f& p : input.positions)
    handles.push_back(mesh.add_vertex({p[0], p[1], p[2]}));
  size_t refused = 0;
  for (const Triangle& t : input.triangles) {
    if (mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]) == Mesh::null_face()) ++refused;
  }
  if (refused > 0) return failure(std::to_string(refused) + " triangles refused by Surface_mesh");
  auto start = Clock::now();
  try {
    sms::GarlandHeckbert_plane_policies<Mesh, Kernel> policies(mesh);
    FaceCountStop<Mesh> stop{&mesh, static_cast<size_t>(target)};
    sms::edge_collapse(
        mesh, stop,
        CGAL::parameters::get_cost(policies.get_cost()).get_placement(policies.get_placement()));
  } catch (const std::exception& e) {
    return failure(std::string("edge_collapse threw: ") + e.what());
  }
  mesh.collect_garbage();
  Outcome o;
  o.core_seconds = seconds_since(start);
  std::vector<Vec3f> positions;
  positions.reserve(mesh.number_of_vertices());
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Kernel::Point_3& p = mesh.point(v);
    positions.push_back(
        {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  }
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.number_of_faces());
  for (Mesh::Face_index f : mesh.faces()) {
    Triangle t;
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k < 3) t[k] = static_cast<uint32_t>(v.idx());
      ++k;
    }
    if (k != 3) return failure("edge_collapse left a face that is not a triangle");
    triangles.push_back(t);
  }
  o.mesh = compact(positions, triangles);
  o.ok = true;
  return o;
}

struct Method {
  std::string name;
  std::function<Outcome(const TriangleMesh&, uint64_t)> run;
};

struct Row {
  bool ok = false;
  std::string error;
  double seconds = 0;      // median total
  double cpu_seconds = 0;  // median process CPU time of the total
  double core_seconds = 0;
  uint64_t output_triangles = 0;
  double hausdorff = 0;  // relative to the input's diagonal
  double mean = 0;
};

// The interpolated median (mean of the two middle runs for an even count),
// unlike bench::median, so that this table's figures stay comparable with
// the earlier rounds in docs/benchmarks.md.
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The runs of all methods in turns, then each result's error.
std::vector<Row> measure_methods(const std::vector<Method>& methods, const TriangleMesh& input,
                                 uint64_t target, int runs, const std::string& label,
                                 const lodbake::DistanceOptions& distance) {
  const size_t count = methods.size();
  std::vector<Row> rows(count);
  std::vector<std::vector<double>> totals(count), cpus(count), cores(count);
  std::vector<Outcome> last(count);
  std::vector<bool> failed(count, false);
  for (int i = 0; i < runs; ++i) {
    for (size_t m = 0; m < count; ++m) {
      if (failed[m]) continue;
      std::fprintf(stderr, "bench_simplify: %s %s run %d\n", label.c_str(), methods[m].name.c_str(),
                   i + 1);
      const std::clock_t cpu_start = std::clock();
      const auto start = Clock::now();
      last[m] = methods[m].run(input, target);
      const double total = seconds_since(start);
      const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      if (!last[m].ok) {
        rows[m].error = last[m].error;
        failed[m] = true;
        continue;
      }
      totals[m].push_back(total);
      cpus[m].push_back(cpu);
      cores[m].push_back(last[m].core_seconds);
    }
  }
  for (size_t m = 0; m < count; ++m) {
    Row& row = rows[m];
    if (failed[m]) continue;
    row.seconds = median(totals[m]);
    row.cpu_seconds = median(cpus[m]);
    row.core_seconds = median(cores[m]);
    row.output_triangles = last[m].mesh.triangle_count();
    if (last[m].mesh.triangles.empty()) {
      row.error = "no triangles left";
      continue;
    }
    auto measure_start = Clock::now();
    auto d = lodbake::measure_surface_distance(input, last[m].mesh, distance);
    std::fprintf(stderr, "bench_simplify:   %s: error measured in %.2f s\n",
                 methods[m].name.c_str(), seconds_since(measure_start));
    if (!d.is_ok()) {
      row.error = "metrics: " + d.status().message();
      continue;
    }
    row.hausdorff = d.value().hausdorff_relative;
    row.mean = d.value().mean_relative;
    row.ok = true;
  }
  return rows;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

int usage() {
  std::fprintf(stderr,
               "usage: bench_simplify [--runs N] [--ratios 0.5,0.1,0.01] "
               "[--peers lodbake,meshopt,openmesh,cgal] [--threads N] [--height-guard] "
               "[--height-guard-factor F] [--placement half|optimal] [--samples N] [--markdown] "
               "FILE...\n");
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  std::vector<double> ratios = {0.5, 0.1, 0.01};
  std::vector<std::string> wanted;
  bool markdown = false;
  lodbake::DistanceOptions distance;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--runs" && has_value) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--ratios" && has_value) {
      ratios.clear();
      for (const std::string& r : split_list(argv[++i])) {
        const double value = std::atof(r.c_str());
        if (!(value > 0 && value <= 1)) return usage();
        ratios.push_back(value);
      }
    } else if (arg == "--peers" && has_value) {
      wanted = split_list(argv[++i]);
    } else if (arg == "--threads" && has_value) {
#ifdef LODBAKE_BENCH_WITH_SIMPLIFY
      lodbake_threads = static_cast<unsigned>(std::strtoul(argv[++i], nullptr, 10));
#else
      ++i;
#endif
    } else if (arg == "--height-guard") {
#ifdef LODBAKE_BENCH_WITH_SIMPLIFY
      lodbake_height_guard = true;
#endif
    } else if (arg == "--height-guard-factor" && has_value) {
#ifdef LODBAKE_BENCH_WITH_SIMPLIFY
      lodbake_height_guard_factor = std::atof(argv[++i]);
      if (!lodbake::is_valid_height_guard_factor(lodbake_height_guard_factor)) return usage();
      lodbake_height_guard = true;
#else
      ++i;
#endif
    } else if (arg == "--placement" && has_value) {
      const std::string value = argv[++i];
      if (value != "half" && value != "optimal") return usage();
#ifdef LODBAKE_BENCH_WITH_SIMPLIFY
      lodbake_placement =
          value == "optimal" ? lodbake::Placement::kOptimal : lodbake::Placement::kHalf;
#endif
    } else if (arg == "--samples" && has_value) {
      distance.area_samples = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--markdown") {
      markdown = true;
    } else if (!arg.empty() && arg[0] == '-') {
      return usage();
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty() || ratios.empty()) return usage();

  std::vector<Method> all;
#ifdef LODBAKE_BENCH_WITH_SIMPLIFY
  all.push_back({"lodbake", run_lodbake});
#endif
  all.push_back({"meshopt", run_meshopt});
  all.push_back({"openmesh", run_openmesh});
  all.push_back({"cgal", run_cgal});
  std::vector<Method> methods;
  for (const Method& m : all) {
    if (wanted.empty() || std::find(wanted.begin(), wanted.end(), m.name) != wanted.end()) {
      methods.push_back(m);
    }
  }
  if (methods.empty()) return usage();
  const bool with_lodbake = methods.front().name == "lodbake";

#ifdef LODBAKE_BENCH_WITH_SIMPLIFY
  // Which lodbake ran, so that the guarded runs of `make bench` tell apart.
  if (lodbake_height_guard && with_lodbake)
    std::printf("lodbake: --height-guard-factor %g\n\n", lodbake_height_guard_factor);
  if (lodbake_placement == lodbake::Placement::kOptimal && with_lodbake)
    std::printf("lodbake: --placement optimal\n\n");
#endif
  if (markdown) {
    std::printf(
        "| mesh | target | method | seconds | cpu s | core s | Mtri/s | output tris | "
        "Hausdorff/diag | mean/diag | lodbake speed-up | lodbake cpu speed-up | lodbake "
        "Hausdorff ratio |\n"
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  } else {
    std::printf("%-26s %6s %-9s %9s %9s %9s %8s %10s %12s %12s %9s %9s %9s\n", "mesh", "target",
                "method", "seconds", "cpu s", "core s", "Mtri/s", "out tris", "Hausdorff", "mean",
                "speed-up", "cpu s-up", "H ratio");
  }
  int status = 0;
  for (const std::string& file : files) {
    lodbake::ImportReport report;
    auto loaded = lodbake::import_mesh_file(file, &report);
    if (!loaded.is_ok()) {
      std::fprintf(stderr, "bench_simplify: error: %s: %s\n", file.c_str(),
                   loaded.status().message().c_str());
      status = 2;
      continue;
    }
    TriangleMesh input = std::move(loaded).value();
    const uint64_t dropped = lodbake::remove_unreferenced_vertices(input);
    // Attributes are not compared: every method gets positions only.
    input.normals = {};
    input.texcoords = {};
    const std::string name = file.substr(file.find_last_of('/') + 1);
    if (input.triangles.empty()) {
      std::fprintf(stderr, "bench_simplify: error: %s: no triangles\n", file.c_str());
      status = 2;
      continue;
    }
    const uint64_t triangles = input.triangle_count();
    std::fprintf(
        stderr,
        "bench_simplify: %s: %zu vertices, %llu triangles (%llu unreferenced vertices dropped)\n",
        name.c_str(), input.vertex_count(), static_cast<unsigned long long>(triangles),
        static_cast<unsigned long long>(dropped));
    for (double ratio : ratios) {
      const uint64_t target =
          std::max<uint64_t>(1, static_cast<uint64_t>(std::llround(ratio * triangles)));
      char target_text[32];
      std::snprintf(target_text, sizeof(target_text), "%g%%", ratio * 100);
      const std::vector<Row> rows =
          measure_methods(methods, input, target, runs, name + " " + target_text, distance);
      for (size_t m = 0; m < methods.size(); ++m) {
        const Row& row = rows[m];
        if (!row.ok) {
          std::printf(markdown ? "| %s | %s | %s | failed: %s |\n" : "%-26s %6s %-9s failed: %s\n",
                      name.c_str(), target_text, methods[m].name.c_str(), row.error.c_str());
          status = 3;
          continue;
        }
        // lodbake's ratios to this peer: a speed-up above 1 means lodbake is
        // faster; an H ratio below 1 means lodbake's Hausdorff error is smaller.
        std::string speed_up = "-";
        std::string cpu_speed_up = "-";
        std::string h_ratio = "-";
        if (with_lodbake && m > 0 && rows[0].ok) {
          char buffer[32];
          std::snprintf(buffer, sizeof(buffer), "%.2fx", row.seconds / rows[0].seconds);
          speed_up = buffer;
          std::snprintf(buffer, sizeof(buffer), "%.2fx", row.cpu_seconds / rows[0].cpu_seconds);
          cpu_speed_up = buffer;
          if (row.hausdorff > 0) {
            std::snprintf(buffer, sizeof(buffer), "%.2f", rows[0].hausdorff / row.hausdorff);
            h_ratio = buffer;
          }
        }
        char core[32] = "-";
        if (row.core_seconds > 0) std::snprintf(core, sizeof(core), "%.3f", row.core_seconds);
        const double mtris = static_cast<double>(triangles) / row.seconds / 1e6;
        std::printf(
            markdown
                ? "| %s | %s | %s | %.3f | %.3f | %s | %.2f | %llu | %.3e | %.3e | %s | %s | %s |\n"
                : "%-26s %6s %-9s %9.3f %9.3f %9s %8.2f %10llu %12.3e %12.3e %9s %9s %9s\n",
            name.c_str(), target_text, methods[m].name.c_str(), row.seconds, row.cpu_seconds, core,
            mtris, static_cast<unsigned long long>(row.output_triangles), row.hausdorff, row.mean,
            speed_up.c_str(), cpu_speed_up.c_str(), h_ratio.c_str());
      }
      std::fflush(stdout);
    }
  }
  if (!markdown) {
    std::printf(
        "seconds: median of %d runs (methods in turns), TriangleMesh in to compact TriangleMesh "
        "out; cpu s: its process CPU time; core s: the peer's library call alone (wall)\n"
        "Mtri/s: input triangles / seconds\nHausdorff, mean: symmetric, relative to the input's "
        "bounding-box diagonal (lib/metrics, %llu area samples per direction)\n"
        "speed-up = peer seconds / lodbake seconds; cpu s-up = peer cpu s / lodbake cpu s; "
        "H ratio = lodbake Hausdorff / peer Hausdorff\n",
        runs, static_cast<unsigned long long>(distance.area_samples));
  }
  return status;
}
