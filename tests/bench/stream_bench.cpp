// Mode stream's server throughput (issue 9, docs/benchmarks.md "Streaming
// server"): one server, --clients simultaneous clients (16 by default, the
// issue's figure), each on its own path (scan or orbit, turned by 360 k / K
// degrees about the model), every one a thread with its own TCP connection
// on loopback and its own server session and thread; against the same K
// sessions run one after the other over the in-memory transport in one
// thread (what the protocol costs without sockets and threads). Reported:
// wall and process CPU seconds (medians over --runs), total bytes both
// ways, view requests, vsplit packets, and the server's throughput in
// packets, requests and downlink MB per wall second. The hierarchy is
// lib/hierarchy's balanced build with its refinement data (what
// lodbake-hierarchy --sections vhie stores). No timing is asserted
// anywhere; the smoke test only checks that it runs.
//   bench_stream [--runs N] [--clients K] [--tolerance PX] FILE...
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "lib/hierarchy/balanced_build.h"
#include "lib/hierarchy/refinement_data.h"
#include "lib/ingest/load_mesh.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_transport.h"
#include "tests/bench/bench_support.h"

namespace lodbake::bench {
namespace {

struct Totals {
  uint64_t up = 0, down = 0;
  size_t requests = 0, packets = 0, frames = 0;
  bool ok = true;
  std::string error;
};

std::vector<CameraFrame> client_path(size_t k, size_t clients, const BoundingSphere& sphere) {
  // The turn of `lodbake-replay --mode stream --clients K`, to the bit.
  const float degrees = 360.0f * static_cast<float>(k) / static_cast<float>(clients);
  return turned_about_vertical(k % 2 == 0 ? scan_path(sphere, 60) : orbit_path(sphere, 60), sphere,
                               degrees);
}

void add_frames(StreamClientSession& session, const std::vector<CameraFrame>& path, Totals* t) {
  t->up += session.start_uplink_bytes();
  t->down += session.start_downlink_bytes();
  for (const CameraFrame& f : path) {
    Result<StreamFrameStats> r = session.frame(f);
    if (!r.is_ok()) {
      t->ok = false;
      t->error = r.status().message();
      return;
    }
    t->up += r.value().uplink_bytes;
    t->down += r.value().downlink_bytes;
    t->requests += r.value().requests;
    t->packets += r.value().packets;
    ++t->frames;
  }
}

// K clients at once over TCP on loopback.
Totals run_tcp(const StreamHierarchy& db, size_t clients, const StreamReplayOptions& options) {
  Totals total;
  Result<TcpListener> listener = TcpListener::listen(LoopbackAddress());
  if (!listener.is_ok()) {
    total.ok = false;
    total.error = listener.status().message();
    return total;
  }
  Result<std::vector<StreamServedClient>> served = runtime_error("not run");
  std::thread server(
      [&] { served = serve_stream_clients(db, &listener.value(), clients, options.server); });
  LoopbackAddress to;
  to.port = listener.value().port();
  std::vector<Totals> each(clients);
  std::vector<std::thread> threads;
  for (size_t k = 0; k < clients; ++k) {
    threads.emplace_back([&, k] {
      Result<std::unique_ptr<StreamTransport>> t = tcp_connect(to);
      if (!t.is_ok()) {
        each[k].ok = false;
        each[k].error = t.status().message();
        return;
      }
      Result<StreamClientSession> s = StreamClientSession::start(t.value().get(), options);
      if (!s.is_ok()) {
        each[k].ok = false;
        each[k].error = s.status().message();
        return;
      }
      add_frames(s.value(), client_path(k, clients, s.value().sphere()), &each[k]);
      t.value()->close();
    });
  }
  for (std::thread& t : threads)
    t.join();
  server.join();
  for (const Totals& t : each) {
    total.up += t.up;
    total.down += t.down;
    total.requests += t.requests;
    total.packets += t.packets;
    total.frames += t.frames;
    if (!t.ok && total.ok) {
      total.ok = false;
      total.error = t.error;
    }
  }
  if (!served.is_ok() && total.ok) {
    total.ok = false;
    total.error = served.status().message();
  }
  return total;
}

// The same K sessions one after the other, in memory, one thread.
Totals run_memory(const StreamHierarchy& db, size_t clients, const StreamReplayOptions& options) {
  Totals total;
  for (size_t k = 0; k < clients; ++k) {
    auto [client_end, server_end] = make_memory_transport_pair(0);
    StreamServerConnection server(db, options.server);
    StreamTransport* s = server_end.get();
    StreamPump pump = [&server, s]() -> Status {
      bool closed = false;
      LODBAKE_ASSIGN_OR_RETURN(Bytes up, s->receive(&closed));
      return server.handle(up, s);
    };
    Result<StreamClientSession> c = StreamClientSession::start(client_end.get(), options, pump);
    if (!c.is_ok()) {
      total.ok = false;
      total.error = c.status().message();
      return total;
    }
    add_frames(c.value(), client_path(k, clients, db.sphere), &total);
  }
  return total;
}

int run(const std::string& file, int runs, size_t clients, float tolerance) {
  LoadOptions load;
  load.drop_unreferenced = true;
  LoadedMesh loaded;
  Status st = load_mesh(file, load, &loaded);
  if (!st.is_ok()) {
    std::fprintf(stderr, "Error: %s: %s\n", file.c_str(), st.message().c_str());
    return 3;
  }
  TriangleMesh mesh = std::move(loaded.mesh);
  mesh.normals = MeshAttribute();
  mesh.texcoords = MeshAttribute();
  Result<BalancedHierarchy> built = build_balanced_hierarchy(mesh, BalancedBuildOptions());
  if (!built.is_ok()) {
    std::fprintf(stderr, "Error: %s: %s\n", file.c_str(), built.status().message().c_str());
    return 4;
  }
  const VertexHierarchy h = std::move(built).value().hierarchy;
  Result<std::vector<NodeRefinement>> data = compute_refinement_data(h, mesh);
  if (!data.is_ok()) {
    std::fprintf(stderr, "Error: %s: %s\n", file.c_str(), data.status().message().c_str());
    return 4;
  }
  Result<StreamHierarchy> db = StreamHierarchy::create(h, data.value());
  if (!db.is_ok()) {
    std::fprintf(stderr, "Error: %s: %s\n", file.c_str(), db.status().message().c_str());
    return 4;
  }
  StreamReplayOptions options;
  options.tolerance_pixels = tolerance;
  std::printf("%s: %zu vertices, %zu nodes, %zu roots; %zu clients, tolerance %g px, %u cores\n",
              file.c_str(), mesh.positions.size(), h.node_count(), h.root_count(), clients,
              tolerance, std::thread::hardware_concurrency());
  std::printf("%-22s %9s %9s %12s %12s %9s %10s %11s %11s %9s\n", "transport", "wall s", "cpu s",
              "uplink B", "downlink B", "requests", "packets", "packets/s", "requests/s",
              "down MB/s");
  for (int lane = 0; lane < 2; ++lane) {
    Totals t;
    std::vector<double> walls, cpus;
    for (int r = 0; r < runs; ++r) {
      const double cpu0 = cpu_seconds(RUSAGE_SELF);
      const Clock::time_point start = Clock::now();
      t = lane == 0 ? run_tcp(db.value(), clients, options)
                    : run_memory(db.value(), clients, options);
      walls.push_back(seconds_since(start));
      cpus.push_back(cpu_seconds(RUSAGE_SELF) - cpu0);
      if (!t.ok) {
        std::fprintf(stderr, "Error: %s: %s\n", file.c_str(), t.error.c_str());
        return 4;
      }
    }
    const double wall = median(walls), cpu = median(cpus);
    std::printf("%-22s %9.3f %9.3f %12llu %12llu %9zu %10zu %11.0f %11.0f %9.2f\n",
                lane == 0 ? "tcp loopback, at once" : "memory, one by one", wall, cpu,
                static_cast<unsigned long long>(t.up), static_cast<unsigned long long>(t.down),
                t.requests, t.packets, static_cast<double>(t.packets) / wall,
                static_cast<double>(t.requests) / wall, static_cast<double>(t.down) / wall / 1e6);
  }
  return 0;
}

}  // namespace
}  // namespace lodbake::bench

int main(int argc, char** argv) {
  int runs = 3;
  size_t clients = 16;
  float tolerance = 1;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--clients" && i + 1 < argc) {
      clients = static_cast<size_t>(std::max(1, std::atoi(argv[++i])));
    } else if (a == "--tolerance" && i + 1 < argc) {
      tolerance = static_cast<float>(std::atof(argv[++i]));
    } else if (a.rfind("--", 0) == 0) {
      std::fprintf(stderr,
                   "usage: bench_stream [--runs N] [--clients K] [--tolerance PX] FILE...\n");
      return 1;
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: bench_stream [--runs N] [--clients K] [--tolerance PX] FILE...\n");
    return 1;
  }
  for (const std::string& f : files) {
    const int rc = lodbake::bench::run(f, runs, clients, tolerance);
    if (rc != 0) return rc;
  }
  return 0;
}
