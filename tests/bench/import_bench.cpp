// Import speed: lodbake's readers against the peers from Debian's packages
// (CGAL IO, OpenMesh IO, Draco IO) on the same files, in one run, with the
// ratio peer/lodbake printed per file. Each reader parses from the file
// system as its users would; the best of N runs is reported.
//
//   bench_import [--runs N] FILE...
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <draco/io/mesh_io.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "lib/meshio/mesh_import.h"

namespace {

struct Outcome {
  bool ok = false;
  size_t vertices = 0;
  size_t faces = 0;
};

using Reader = std::function<Outcome(const std::string&)>;

Outcome read_lodbake(const std::string& path) {
  lodbake::ImportReport report;
  auto mesh = lodbake::import_mesh_file(path, &report);
  if (!mesh.is_ok()) return {};
  return {true, mesh.value().vertex_count(), mesh.value().triangle_count()};
}

Outcome read_cgal(const std::string& path) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons)) return {};
  return {true, points.size(), polygons.size()};
}

Outcome read_openmesh(const std::string& path) {
  OpenMesh::TriMesh_ArrayKernelT<> mesh;
  OpenMesh::IO::Options options;
  if (!OpenMesh::IO::read_mesh(mesh, path, options)) return {};
  return {true, mesh.n_vertices(), mesh.n_faces()};
}

Outcome read_draco(const std::string& path) {
  auto mesh = draco::ReadMeshFromFile(path);
  if (!mesh.ok()) return {};
  return {true, mesh.value()->num_points(), mesh.value()->num_faces()};
}

double best_seconds(const Reader& reader, const std::string& path, int runs, Outcome* outcome) {
  double best = 1e30;
  for (int i = 0; i < runs; ++i) {
    auto start = std::chrono::steady_clock::now();
    *outcome = reader(path);
    auto stop = std::chrono::steady_clock::now();
    if (!outcome->ok) return -1;
    best = std::min(best, std::chrono::duration<double>(stop - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: bench_import [--runs N] FILE...\n");
    return 1;
  }
  // OpenMesh and CGAL print warnings on stderr for some inputs; keep the
  // table on stdout readable.
  struct Peer {
    const char* name;
    Reader reader;
  };
  const std::vector<Peer> peers = {{"lodbake", read_lodbake},
                                   {"CGAL IO", read_cgal},
                                   {"OpenMesh IO", read_openmesh},
                                   {"Draco IO", read_draco}};
  std::printf("%-40s %-12s %10s %10s %10s %9s\n", "file", "reader", "vertices", "faces", "seconds",
              "ratio");
  for (const std::string& file : files) {
    double ours = -1;
    for (size_t p = 0; p < peers.size(); ++p) {
      const Peer& peer = peers[p];
      Outcome outcome;
      double seconds = best_seconds(peer.reader, file, runs, &outcome);
      if (p == 0) ours = seconds;  // peers[0] is lodbake itself
      std::string name = file.substr(file.find_last_of('/') + 1);
      if (seconds < 0) {
        std::printf("%-40s %-12s %10s %10s %10s %9s\n", name.c_str(), peer.name, "-", "-", "failed",
                    "-");
        continue;
      }
      char ratio[32] = "-";
      if (ours > 0) std::snprintf(ratio, sizeof(ratio), "%.2fx", seconds / ours);
      std::printf("%-40s %-12s %10zu %10zu %10.3f %9s\n", name.c_str(), peer.name, outcome.vertices,
                  outcome.faces, seconds, ratio);
    }
  }
  std::printf("ratio = peer seconds / lodbake seconds (above 1: lodbake is faster)\n");
  return 0;
}
