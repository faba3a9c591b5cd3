// lodbake-replay's mode vtrees: BASE + VHIE + RFIN + VTRE, vertex-tree
// transmission (To, Lau and Green 2001, section 5;
// lib/replay/vtrees_session.h): the server's visible vertex list moves along
// the camera path, the client rebuilds the trees from the node records and
// selects its triangles. In one process over an in-memory channel, or over
// TCP on loopback: --serve (serve_vtrees_clients, a visible vertex list per
// connection) and --connect (a client that needs no FILE).
#include <algorithm>
#include <array>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/open_container.h"
#include "formats/sections/rfin.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vtre.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/replay_check.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_transport.h"
#include "lib/replay/structure_loading.h"
#include "lib/replay/vtrees_session.h"
#include "lib/replay/vtrees_wedge_check.h"
#include "tools/replay/frame_support.h"
#include "tools/replay/replay_request.h"
#include "tools/replay/report_support.h"
#include "tools/replay/streaming_support.h"

namespace lodbake::cli::replay {
namespace {

// Mode vtrees' database: the container's hierarchy, refinement data and
// vertex trees.
using VtreesDb = VtreesStructure;

Result<VtreesDb> load_vtrees_db(const Bytes& bytes) {
  LODBAKE_ASSIGN_OR_RETURN(OpenedContainer file, open_container(bytes));
  LODBAKE_ASSIGN_OR_RETURN(uint32_t group, structure_group(file, ReplayStructure::kVtrees));
  return load_vtrees_structure(file.decoded(), group);
}

VtreesReplayOptions vtrees_options(const Request& request) {
  VtreesReplayOptions options;
  options.viewport = request.options.viewport;
  options.tolerance_pixels = request.options.tolerance_pixels;
  return options;
}

// --csv rows of mode vtrees, in process or over TCP.
Status write_vtrees_csv(const std::string& file, const std::vector<VtreesFrameStats>& frames) {
  std::ostringstream csv;
  csv << "frame,uplink_bytes,downlink_bytes,left_records,right_records,traces,trace_updates,"
         "downs,ups,visible,triangles,reconstruct_ms,select_ms\n";
  for (size_t i = 0; i < frames.size(); ++i) {
    const VtreesFrameStats& f = frames[i];
    csv << i << ',' << f.uplink_bytes << ',' << f.downlink_bytes << ',' << f.left_records << ','
        << f.right_records << ',' << f.traces << ',' << f.trace_updates << ',' << f.downs << ','
        << f.ups << ',' << f.visible << ',' << f.triangles << ',' << f.reconstruct_ms << ','
        << f.select_ms << '\n';
  }
  return write_file_atomic(file, csv.str());
}

// One vtrees client's frames and records added up (the opening included):
// what the in-process report and the --connect report share.
struct VtreesTotals {
  uint64_t up = 0, down = 0;
  size_t max_triangles = 0;
  double triangles = 0, reconstruct_ms = 0, select_ms = 0;
  double base_b = 0, left_b = 0, right_b = 0, child_b = 0;  // mean record bytes
  uint64_t record_bits = 0;
  double per_node_us = 0;
};

VtreesTotals vtrees_totals(const VtreesReceived& got, const std::vector<VtreesFrameStats>& frames,
                           uint64_t start_down, double start_ms) {
  VtreesTotals t;
  t.down = start_down;
  t.reconstruct_ms = start_ms;
  for (const VtreesFrameStats& f : frames) {
    t.up += f.uplink_bytes;
    t.down += f.downlink_bytes;
    t.triangles += static_cast<double>(f.triangles);
    t.max_triangles = std::max(t.max_triangles, f.triangles);
    t.reconstruct_ms += f.reconstruct_ms;
    t.select_ms += f.select_ms;
  }
  t.triangles /= static_cast<double>(std::max<size_t>(frames.size(), 1));
  auto mean_bytes = [](uint64_t bits, size_t count) {
    return count == 0 ? 0.0 : static_cast<double>(bits) / 8 / static_cast<double>(count);
  };
  t.base_b = mean_bytes(got.base_bits, got.base_records);
  t.left_b = mean_bytes(got.left_bits, got.left_records);
  t.right_b = mean_bytes(got.right_bits, got.right_records);
  t.child_b = mean_bytes(got.left_bits + got.right_bits, got.left_records + got.right_records);
  t.record_bits = got.base_bits + got.left_bits + got.right_bits;
  t.per_node_us =
      got.left_records == 0
          ? 0.0
          : 1000 * t.reconstruct_ms / static_cast<double>(got.base_records + 2 * got.left_records);
  return t;
}

// The report's "records", "moves" and "client" parts (JSON and text).
nlohmann::json vtrees_records_json(const VtreesReceived& got, const VtreesTotals& t) {
  return {{"base", {{"count", got.base_records}, {"mean_bytes", t.base_b}, {"paper_bytes", 22}}},
          {"left", {{"count", got.left_records}, {"mean_bytes", t.left_b}}},
          {"right", {{"count", got.right_records}, {"mean_bytes", t.right_b}}},
          {"child_mean_bytes", t.child_b},
          {"paper_child_bytes", 20},
          {"traces", got.traces},
          {"trace_bytes", static_cast<double>(got.trace_bits) / 8},
          {"trace_updates", got.trace_updates}};
}

nlohmann::json vtrees_client_json(const VtreesClient& client, const VtreesTotals& t) {
  return {{"nodes_held", client.nodes_held()},
          {"triangles", {{"mean", t.triangles}, {"max", t.max_triangles}}},
          {"reconstruct_ms", t.reconstruct_ms},
          {"reconstruct_us_per_node", t.per_node_us},
          {"select_ms", t.select_ms}};
}

// An asset's trees: what the wedge data add to the records received (null
// for a mesh's).
double wedge_bytes_per_split(const VtreesReceived& got) {
  return got.left_records == 0 ? 0.0
                               : static_cast<double>(got.split_wedge_bits) / 8 /
                                     static_cast<double>(got.left_records);
}

nlohmann::json vtrees_wedges_json(const Request& request, const VtreesClient& client) {
  if (!client.has_wedges()) return nlohmann::json();
  const VtreesReceived& got = client.received();
  return {{"count", client.widths().wedge_count},
          {"face_slots", client.widths().slot_count},
          {"base_bytes", static_cast<double>(got.base_wedge_bits) / 8},
          {"split_bytes", static_cast<double>(got.split_wedge_bits) / 8},
          {"mean_split_bytes", wedge_bytes_per_split(got)},
          {"validated", request.validate}};
}

// The trees a vtrees report describes: the in-process run has them whole,
// a --connect client only their widths.
struct TreesShape {
  uint64_t nodes = 0, base = 0, splits = 0;
  int id_bits = 0;
};

void print_trees_line(const TreesShape& s) {
  std::cout << "trees         " << s.nodes << " nodes: " << s.base << " base, " << s.splits
            << " splits, " << s.id_bits << "-bit ids\n";
}

// The report's parts from "trees" to "overlap_frames", in process and over
// --connect alike.
nlohmann::json vtrees_report_json(const Request& request, const TreesShape& s,
                                  const VtreesClient& client, const VtreesTotals& t, size_t frames,
                                  uint64_t trees_bytes, size_t overlap_frames) {
  const VtreesReceived& got = client.received();
  return {
      {"trees",
       {{"nodes", s.nodes}, {"base_nodes", s.base}, {"splits", s.splits}, {"id_bits", s.id_bits}}},
      {"uplink", {{"bytes", t.up}, {"views", frames}}},
      {"downlink",
       {{"bytes", t.down},
        {"trees_message_bytes", trees_bytes},
        {"record_bytes", (t.record_bits + 7) / 8},
        {"messages", got.messages}}},
      {"records", vtrees_records_json(got, t)},
      {"moves", {{"down", got.downs}, {"up", got.ups}}},
      {"client", vtrees_client_json(client, t)},
      {"overlap_frames", request.validate ? nlohmann::json(overlap_frames) : nlohmann::json()},
      {"wedges", vtrees_wedges_json(request, client)}};
}

// From "downlink" to "reconstruct".
void print_vtrees_lines(const VtreesClient& client, const VtreesTotals& t, size_t node_count) {
  const VtreesReceived& got = client.received();
  std::cout << "uplink        " << t.up << " bytes, one view per frame\n";
  std::cout << "downlink      " << t.down << " bytes in " << got.messages << " messages, "
            << (t.record_bits + 7) / 8 << " of them node records\n";
  std::cout << "records       base " << got.base_records << " x " << t.base_b
            << " B (the paper 22), "
            << "left " << got.left_records << " x " << t.left_b << " B, right " << got.right_records
            << " x " << t.right_b << " B: child mean " << t.child_b << " B (the paper 20)\n";
  std::cout << "trace-up      " << got.traces << " first transmitted parents in records ("
            << static_cast<double>(got.trace_bits) / 8 << " B), " << got.trace_updates
            << " updates\n";
  std::cout << "list moves    " << got.left_records << " down at new nodes, " << got.downs
            << " down and " << got.ups << " up over held nodes\n";
  std::cout << "client        " << client.nodes_held() << " of " << node_count
            << " nodes held, triangles mean " << t.triangles << ", max " << t.max_triangles << "\n";
  std::cout << "reconstruct   " << t.reconstruct_ms << " ms in all (" << t.per_node_us
            << " us per node), triangle selection " << t.select_ms << " ms in all\n";
  if (client.has_wedges()) {
    std::cout << "wedges        " << client.widths().wedge_count << " wedges over "
              << client.widths().slot_count
              << " face slots: " << static_cast<double>(got.base_wedge_bits) / 8
              << " B in the base records, " << wedge_bytes_per_split(got)
              << " B per split received (its records' fan pairs "
              << "and wings)\n";
  }
}

// Whether the client's triangles over its own positions overlap or leave
// holes (fronts the trees allow and the split DAG does not).
bool vtrees_overlap(const VtreesClient& client, const std::vector<Triangle>& triangles) {
  TriangleMesh mesh;
  mesh.positions = client.positions();
  mesh.triangles = triangles;
  return !triangulation_problems(mesh).empty();
}

// --serve: a TCP server on loopback for --clients connections, each on its
// own thread with its own session (visible vertex list); the address on
// stdout's first line. A record sent twice to one client is a validation
// failure (exit 7).
int run_vtrees_serve(const Tool& tool, const Request& request, const VtreesDb& loaded) {
  Serving serving;
  if (std::optional<int> failed = start_serving(tool, request, &serving)) return *failed;
  const std::string& address = serving.address;
  Result<std::vector<VtreesServedClient>> served = serve_vtrees_clients(
      *loaded.db, &*serving.listener, request.clients, kMaxVtreesItems, serving.tcp);
  const double seconds = serving.seconds();
  if (!served.is_ok()) return tool.fail(address, served.status());
  uint64_t up = 0, down = 0;
  size_t records = 0, state = 0;
  bool any_twice = false;
  Status failed;
  nlohmann::json lanes = nlohmann::json::array();
  std::ostringstream text;
  for (size_t k = 0; k < served.value().size(); ++k) {
    const VtreesServedClient& c = served.value()[k];
    const bool twice = sent_twice(c.sent_nodes);
    any_twice = any_twice || twice;
    up += c.uplink_bytes;
    down += c.downlink_bytes;
    records += c.sent_nodes.size();
    state += c.state_bytes;
    if (failed.is_ok() && !c.status.is_ok()) failed = c.status;
    if (failed.is_ok() && twice) {
      failed = Status(ErrorKind::kValidation,
                      "client " + std::to_string(k) + ": a node record was sent twice");
    }
    lanes.push_back({{"client", k},
                     {"ok", c.status.is_ok()},
                     {"error", c.status.message()},
                     {"uplink_bytes", c.uplink_bytes},
                     {"downlink_bytes", c.downlink_bytes},
                     {"views", c.requests},
                     {"messages", c.messages},
                     {"records", c.sent_nodes.size()},
                     {"visible", c.visible},
                     {"server_state_bytes", c.state_bytes}});
    text << client_label(k) << " uplink " << c.uplink_bytes << " bytes (" << c.requests
         << " views), downlink " << c.downlink_bytes << " bytes (" << c.messages
         << " frame messages, " << c.sent_nodes.size() << " node records); server state "
         << c.state_bytes << " bytes, " << c.visible << " visible vertices"
         << (c.status.is_ok() ? "" : "; ended: " + c.status.message()) << "\n";
  }
  if (tool.json()) {
    tool.print_json(served_report(request, address, seconds, lanes,
                                  {{"uplink_bytes", up},
                                   {"downlink_bytes", down},
                                   {"records", records},
                                   {"server_state_bytes", state}}));
  } else {
    std::cout << "served        " << request.input << ": mode vtrees on " << address << ", "
              << served.value().size() << " clients in " << seconds << " s\n";
    std::cout << text.str();
    std::cout << "total         uplink " << up << " bytes, downlink " << down << " bytes, "
              << records << " node records, "
              << (any_twice ? "some sent twice" : "none sent twice to a client")
              << "; server state " << state << " bytes\n";
  }
  if (!failed.is_ok()) return tool.fail(address, failed);
  return 0;
}

}  // namespace

// --connect: a vtrees client on its camera path against a server; the
// trees and scene messages give it everything, so no FILE. --validate
// checks what a client can alone: every answer complete and applied (the
// client refuses a record twice or a move it cannot make) and counts the
// frames whose triangles overlap.
int run_vtrees_connect(const Tool& tool, const Request& request) {
  const std::string address = address_text(*request.connect);
  Result<std::unique_ptr<StreamTransport>> t =
      tcp_connect(*request.connect, TcpOptions(), kVtreesMessages);
  if (!t.is_ok()) return tool.fail(address, t.status());
  Result<VtreesClientSession> started =
      VtreesClientSession::start(t.value().get(), vtrees_options(request));
  if (!started.is_ok()) return tool.fail(address, started.status());
  VtreesClientSession& session = started.value();
  std::string path_file;
  Result<std::vector<CameraFrame>> read = read_path(request, session.sphere(), &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();
  std::vector<VtreesFrameStats> frames;
  size_t overlap_frames = 0;
  Progress progress(tool, "transmitting");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<VtreesFrameStats> f = session.frame(path[i]);
    if (!f.is_ok()) return tool.fail(address, frame_failure(i, f.status()));
    frames.push_back(f.value());
    if (request.validate && session.client().has_wedges()) {
      Result<std::vector<std::array<uint32_t, 3>>> corners = session.client().corner_wedges();
      if (!corners.is_ok()) {
        return tool.fail(
            address, frame_failure(i, Status(ErrorKind::kValidation, corners.status().message())));
      }
    }
    if (request.validate && vtrees_overlap(session.client(), session.triangles())) ++overlap_frames;
    progress.update(static_cast<double>(i + 1) / static_cast<double>(path.size()));
  }
  t.value()->close();
  if (!request.csv.empty()) {
    Status written = write_vtrees_csv(request.csv, frames);
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }
  const VtreesClient& client = session.client();
  const VtreesWidths& w = client.widths();
  const size_t node_count = size_t{w.base_count} + 2 * size_t{w.split_count};
  const TreesShape shape{node_count, w.base_count, w.split_count, w.id_bits()};
  const VtreesTotals tot = vtrees_totals(client.received(), frames, session.start_downlink_bytes(),
                                         session.trees_reconstruct_ms());
  if (tool.json()) {
    nlohmann::json report = connect_report(request, address, frames.size());
    report.update(vtrees_report_json(request, shape, client, tot, frames.size(),
                                     session.trees_bytes(), overlap_frames));
    tool.print_json(report);
    return 0;
  }
  std::cout << "replay        " << address << ": mode vtrees over TCP, path " << request.path
            << ", " << frames.size() << " frames"
            << (request.validate ? ", every answer validated" : "") << "\n";
  print_trees_line(shape);
  print_vtrees_lines(client, tot, node_count);
  if (request.validate) {
    std::cout << "validate      every answer complete and applied, no record received twice"
              << (client.has_wedges() ? ", a wedge at every corner" : "") << "; " << overlap_frames
              << " of " << frames.size()
              << " frames had overlapping or missing triangles (the server's list is checked "
                 "in process only)\n";
  }
  return 0;
}

// Mode vtrees: vertex-tree transmission (To, Lau & Green 2001, section 5):
// the server's visible vertex list moves along the camera path, the client
// rebuilds the trees from the node records and selects its triangles.
int run_vtrees(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<VtreesDb> loaded = load_vtrees_db(bytes);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  if (request.serve) return run_vtrees_serve(tool, request, loaded.value());
  const VertexTrees& trees = *loaded.value().trees;
  const VtreesDatabase& db = *loaded.value().db;
  Result<VtreesSession> created = VtreesSession::create(db, vtrees_options(request));
  if (!created.is_ok()) return tool.fail(request.input, created.status());
  VtreesSession& session = created.value();

  std::string path_file;
  Result<std::vector<CameraFrame>> read = read_path(request, db.sphere, &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();

  std::vector<VtreesFrameStats> frames;
  size_t overlap_frames = 0;  // --validate: lists whose triangles are no clean triangulation
  Progress progress(tool, "transmitting");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<VtreesFrameStats> f = session.frame(path[i], db.sphere);
    if (!f.is_ok()) return tool.fail(request.input, frame_failure(i, f.status()));
    frames.push_back(f.value());
    if (request.validate) {
      // The client's reconstruction must be exact: its list is the server's
      // and its triangles are VisibleVertexList's on the full trees.
      const VisibleVertexList& list = session.server().list();
      std::string problem;
      for (uint32_t v = 0; problem.empty() && v < trees.positions.size(); ++v) {
        if (session.client().visible_node(v) != list.visible_node(v))
          problem =
              "the client's visible node of vertex " + std::to_string(v) + " is not the server's";
      }
      if (problem.empty() &&
          sorted_canonical(session.triangles()) != sorted_canonical(list.triangles())) {
        problem = "the client's triangles are not the trees' own selection for its list";
      }
      if (problem.empty() && loaded.value().reference) {
        // An asset's trees: every corner has the wedge of the whole
        // hierarchy's front for the same face and node.
        const std::vector<std::string> wedges = check_vtrees_wedges(
            session.client(), *loaded.value().reference, *loaded.value().wedges);
        if (!wedges.empty()) problem = "corner wedges: " + wedges.front();
      }
      if (!problem.empty()) {
        return tool.fail(request.input, frame_failure(i, Status(ErrorKind::kValidation, problem)));
      }
      if (vtrees_overlap(session.client(), session.triangles())) ++overlap_frames;
    }
    progress.update(static_cast<double>(i + 1) / path.size());
  }
  if (request.validate) {
    const std::vector<uint32_t>& sent = session.server().sent_nodes();
    if (sent_twice(sent) || sent.size() != session.client().nodes_held()) {
      return tool.fail(request.input,
                       Status(ErrorKind::kValidation, "a node record was sent twice"));
    }
  }

  if (!request.csv.empty()) {
    Status written = write_vtrees_csv(request.csv, frames);
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  const VtreesReceived& got = session.client().received();
  const VtreesTotals tot =
      vtrees_totals(got, frames, session.trees_bytes(), session.trees_reconstruct_ms());
  const TreesShape shape{trees.node_count(), trees.base_vertex_count, trees.split_count(),
                         db.widths.id_bits()};
  if (tool.json()) {
    nlohmann::json report = camera_report(request, frames.size());
    report.update(vtrees_report_json(request, shape, session.client(), tot, frames.size(),
                                     session.trees_bytes(), overlap_frames));
    report["server_state_bytes"] = session.server().state_bytes();
    tool.print_json(report);
    return 0;
  }
  print_replay_line(request, frames.size());
  print_trees_line(shape);
  print_view(request);
  std::cout << "\n";
  print_vtrees_lines(session.client(), tot, trees.node_count());
  if (request.validate) {
    std::cout << "validate      the client's list and triangles were the server's every frame"
              << (session.client().has_wedges() ? ", every corner's wedge the hierarchy front's"
                                                : "")
              << ", no record sent twice; " << overlap_frames << " of " << frames.size()
              << " frames had overlapping or missing triangles (fronts the trees allow and the "
                 "split DAG does not)\n";
  }
  return 0;
}

}  // namespace lodbake::cli::replay
