// lodbake-replay's mode stream: BASE + VHIE + RFIN served frame by frame to
// a client that starts from the base mesh (Kim, Lee and Kobbelt 2005;
// lib/replay/stream_session.h), bytes counted both ways, against the
// view-independent baseline of the paper's section 8. In one process over
// an in-memory channel (one client, or --clients K on turned paths), or over
// TCP on loopback: --serve (serve_stream_clients) and --connect (a client
// that needs no FILE).
#include <algorithm>
#include <cmath>
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
#include "lib/replay/camera_path.h"
#include "lib/replay/replay_check.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_transport.h"
#include "lib/replay/stream_wedge_check.h"
#include "lib/replay/structure_loading.h"
#include "tools/replay/frame_support.h"
#include "tools/replay/replay_request.h"
#include "tools/replay/report_support.h"
#include "tools/replay/streaming_support.h"

namespace lodbake::cli::replay {
namespace {

// Mode stream's database: the container's hierarchy and RFIN records.
using StreamDb = StreamStructure;

Result<StreamDb> load_stream_db(const Bytes& bytes) {
  LODBAKE_ASSIGN_OR_RETURN(OpenedContainer file, open_container(bytes));
  LODBAKE_ASSIGN_OR_RETURN(uint32_t group, structure_group(file, ReplayStructure::kStream));
  return load_stream_structure(file.decoded(), group);
}

StreamReplayOptions stream_options(const Request& request) {
  StreamReplayOptions options;
  options.viewport = request.options.viewport;
  options.tolerance_pixels = request.options.tolerance_pixels;
  options.max_passes = request.options.max_passes;
  return options;
}

// --validate's check of one streamed frame: a valid mesh, one request at
// most and nothing missing; on an asset's stream a wedge at every corner,
// the server's front's own when `loaded` (in process) has them.
Status stream_frame_check(const StreamClient& client, const StreamFrameStats& f, size_t i,
                          const StreamDb* loaded = nullptr) {
  std::vector<std::string> problems = check_vhier_mesh(client.refiner());
  if (loaded != nullptr && loaded->front) {
    for (std::string& p : check_stream_wedges(client, *loaded->db, *loaded->front, *loaded->wedges))
      problems.push_back(std::move(p));
  } else if (client.has_wedges()) {
    Result<std::vector<std::array<uint32_t, 3>>> corners = client.corner_wedges();
    if (!corners.is_ok()) problems.push_back(corners.status().message());
  }
  if (f.missing != 0 || f.requests > 1) {
    problems.push_back(std::to_string(f.missing) + " needed splits missing after " +
                       std::to_string(f.requests) + " requests");
  }
  return invalid_mesh(i, problems);
}

// One client's frames added up (the opening exchange included).
struct StreamTotals {
  uint64_t up = 0, down = 0;
  size_t frames = 0, requests = 0, request_frames = 0, packets = 0, splits = 0, collapses = 0;
  size_t max_triangles = 0;
  double mean_triangles = 0;
};

StreamTotals stream_totals(const std::vector<StreamFrameStats>& frames, uint64_t start_up,
                           uint64_t start_down) {
  StreamTotals t;
  t.up = start_up;
  t.down = start_down;
  t.frames = frames.size();
  for (const StreamFrameStats& f : frames) {
    t.up += f.uplink_bytes;
    t.down += f.downlink_bytes;
    t.requests += f.requests;
    t.request_frames += f.requests != 0;
    t.packets += f.packets;
    t.splits += f.splits;
    t.collapses += f.collapses;
    t.mean_triangles += static_cast<double>(f.triangles);
    t.max_triangles = std::max(t.max_triangles, f.triangles);
  }
  t.mean_triangles /= static_cast<double>(std::max<size_t>(frames.size(), 1));
  return t;
}

// --csv rows of mode stream; the server's memory columns in process only.
Status write_stream_csv(const std::string& file, const std::vector<StreamFrameStats>& frames,
                        bool server_columns) {
  std::ostringstream csv;
  csv << "frame,uplink_bytes,downlink_bytes,requests,packets,splits,collapses,triangles,front"
      << (server_columns ? ",window_bytes,buffer_bytes,front_bytes\n" : "\n");
  for (size_t i = 0; i < frames.size(); ++i) {
    const StreamFrameStats& f = frames[i];
    csv << i << ',' << f.uplink_bytes << ',' << f.downlink_bytes << ',' << f.requests << ','
        << f.packets << ',' << f.splits << ',' << f.collapses << ',' << f.triangles << ','
        << f.front_size;
    if (server_columns) {
      csv << ',' << f.server.window_bytes << ',' << f.server.buffer_bytes << ','
          << f.server.front_bytes;
    }
    csv << '\n';
  }
  return write_file_atomic(file, csv.str());
}

// A camera path turned about the vertical axis through the sphere's centre.
// --clients K (K > 1) in one process: K sessions on one database, client k
// on the scan (even k) or orbit (odd k) path, or on --path, turned by
// 360 k / K degrees; their frames interleaved, as simultaneous clients.
int run_stream_clients(const Tool& tool, const Request& request, const StreamDb& loaded) {
  const StreamHierarchy& db = *loaded.db;
  const StreamReplayOptions options = stream_options(request);
  const size_t k_count = request.clients;
  std::vector<StreamSession> sessions;
  std::vector<std::vector<CameraFrame>> paths;
  std::vector<std::string> names;
  std::vector<float> degrees;
  for (size_t k = 0; k < k_count; ++k) {
    Result<StreamSession> created = StreamSession::create(db, options);
    if (!created.is_ok()) return tool.fail(request.input, created.status());
    sessions.push_back(std::move(created).value());
    Request lane = request;
    if (!tool.has("path")) lane.path = k % 2 == 0 ? "scan" : "orbit";
    std::string path_file;
    Result<std::vector<CameraFrame>> read = read_path(lane, db.sphere, &path_file);
    if (!read.is_ok()) return tool.fail(path_file, read.status());
    degrees.push_back(360.0f * static_cast<float>(k) / static_cast<float>(k_count));
    paths.push_back(turned_about_vertical(std::move(read).value(), db.sphere, degrees.back()));
    names.push_back(lane.path);
  }
  std::vector<std::vector<StreamFrameStats>> frames(k_count);
  size_t longest = 0;
  for (const std::vector<CameraFrame>& p : paths)
    longest = std::max(longest, p.size());
  Progress progress(tool, "streaming");
  for (size_t i = 0; i < longest; ++i) {
    for (size_t k = 0; k < k_count; ++k) {
      if (i >= paths[k].size()) continue;
      Result<StreamFrameStats> f = sessions[k].frame(paths[k][i], db.sphere);
      if (!f.is_ok()) {
        return tool.fail(
            request.input,
            Status(f.status().kind(), "client " + std::to_string(k) + ", frame " +
                                          std::to_string(i) + ": " + f.status().message()));
      }
      if (request.validate) {
        Status checked = stream_frame_check(sessions[k].client(), f.value(), i, &loaded);
        if (!checked.is_ok()) {
          return tool.fail(request.input, Status(checked.kind(), "client " + std::to_string(k) +
                                                                     ", " + checked.message()));
        }
      }
      frames[k].push_back(f.value());
    }
    progress.update(static_cast<double>(i + 1) / static_cast<double>(longest));
  }
  if (request.validate) {
    for (size_t k = 0; k < k_count; ++k) {
      if (sent_twice(sessions[k].server().sent())) {
        return tool.fail(request.input,
                         Status(ErrorKind::kValidation, "client " + std::to_string(k) +
                                                            ": a vsplit packet was sent twice"));
      }
    }
  }
  StreamTotals all;
  size_t window = 0, buffer = 0, front = 0;
  nlohmann::json lanes = nlohmann::json::array();
  std::ostringstream text;
  for (size_t k = 0; k < k_count; ++k) {
    const StreamTotals t = stream_totals(frames[k], sessions[k].start_uplink_bytes(),
                                         sessions[k].start_downlink_bytes());
    const StreamServerMemory m = sessions[k].server().memory();
    all.up += t.up;
    all.down += t.down;
    all.requests += t.requests;
    all.packets += t.packets;
    all.frames += t.frames;
    window += m.window_bytes;
    buffer += m.buffer_bytes;
    front += m.front_bytes;
    lanes.push_back({{"client", k},
                     {"path", names[k]},
                     {"turned_degrees", degrees[k]},
                     {"frames", t.frames},
                     {"uplink_bytes", t.up},
                     {"requests", t.requests},
                     {"downlink_bytes", t.down},
                     {"packets", t.packets},
                     {"triangles", {{"mean", t.mean_triangles}, {"max", t.max_triangles}}},
                     {"server_memory",
                      {{"window_bytes", m.window_bytes},
                       {"buffer_bytes", m.buffer_bytes},
                       {"front_nodes", m.front_nodes},
                       {"front_bytes", m.front_bytes}}}});
    text << client_label(k) << " path " << names[k] << " turned " << degrees[k] << " deg, "
         << t.frames << " frames: uplink " << t.up << " bytes (" << t.requests
         << " requests), downlink " << t.down << " bytes (" << t.packets
         << " packets); server window " << m.window_bytes << " bytes (buffer " << m.buffer_bytes
         << ") vs a stored front " << m.front_bytes << " bytes\n";
  }
  if (tool.json()) {
    tool.print_json({{"schema", kReplaySchema},
                     {"input", request.input},
                     {"mode", request.mode},
                     {"clients", lanes},
                     {"validated", request.validate},
                     {"tolerance_pixels", request.options.tolerance_pixels},
                     {"total",
                      {{"uplink_bytes", all.up},
                       {"downlink_bytes", all.down},
                       {"requests", all.requests},
                       {"packets", all.packets},
                       {"server_window_bytes", window},
                       {"server_buffer_bytes", buffer},
                       {"stored_front_bytes", front}}}});
    return 0;
  }
  std::cout << "replay        " << request.input << ": mode stream, " << k_count
            << " clients on one server in one process, " << all.frames << " frames"
            << (request.validate ? ", every frame validated" : "") << "\n";
  std::cout << "hierarchy     " << db.h->node_count() << " nodes, " << db.h->root_count()
            << " roots, <tree-id, node-id> <" << db.widths.tree_bits << ", " << db.widths.node_bits
            << ">\n";
  std::cout << text.str();
  std::cout << "total         uplink " << all.up << " bytes, downlink " << all.down << " bytes, "
            << all.packets << " packets; server memory " << window << " bytes of windows ("
            << window / k_count << " per client, buffers " << buffer << ") vs stored fronts "
            << front << " bytes\n";
  return 0;
}

// --serve: a TCP server on loopback for --clients connections, each on its
// own thread with its own session; the address on stdout's first line.
int run_stream_serve(const Tool& tool, const Request& request, const StreamDb& loaded) {
  const StreamHierarchy& db = *loaded.db;
  Serving serving;
  if (std::optional<int> failed = start_serving(tool, request, &serving)) return *failed;
  const std::string& address = serving.address;
  Result<std::vector<StreamServedClient>> served = serve_stream_clients(
      db, &*serving.listener, request.clients, StreamServerOptions(), serving.tcp);
  const double seconds = serving.seconds();
  if (!served.is_ok()) return tool.fail(address, served.status());
  uint64_t up = 0, down = 0;
  size_t packets = 0, window = 0, front = 0;
  const StreamServedClient* failed = nullptr;
  nlohmann::json lanes = nlohmann::json::array();
  std::ostringstream text;
  for (size_t k = 0; k < served.value().size(); ++k) {
    const StreamServedClient& c = served.value()[k];
    up += c.uplink_bytes;
    down += c.downlink_bytes;
    packets += c.packets;
    window += c.memory.window_bytes;
    front += c.memory.front_bytes;
    if (!c.status.is_ok() && failed == nullptr) failed = &c;
    lanes.push_back({{"client", k},
                     {"ok", c.status.is_ok()},
                     {"error", c.status.message()},
                     {"uplink_bytes", c.uplink_bytes},
                     {"downlink_bytes", c.downlink_bytes},
                     {"requests", c.requests},
                     {"packets", c.packets},
                     {"resumed_splits", c.resumed},
                     {"server_memory",
                      {{"window_bytes", c.memory.window_bytes},
                       {"buffer_bytes", c.memory.buffer_bytes},
                       {"front_nodes", c.memory.front_nodes},
                       {"front_bytes", c.memory.front_bytes}}}});
    text << client_label(k) << " uplink " << c.uplink_bytes << " bytes (" << c.requests
         << " requests), downlink " << c.downlink_bytes << " bytes (" << c.packets << " packets"
         << (c.resumed != 0 ? ", resumed holding " + std::to_string(c.resumed) + " splits" : "")
         << "); server window " << c.memory.window_bytes << " bytes (buffer "
         << c.memory.buffer_bytes << ") vs a stored front " << c.memory.front_bytes << " bytes"
         << (c.status.is_ok() ? "" : "; ended: " + c.status.message()) << "\n";
  }
  if (tool.json()) {
    tool.print_json(served_report(request, address, seconds, lanes,
                                  {{"uplink_bytes", up},
                                   {"downlink_bytes", down},
                                   {"packets", packets},
                                   {"server_window_bytes", window},
                                   {"stored_front_bytes", front}}));
  } else {
    std::cout << "served        " << request.input << ": mode stream on " << address << ", "
              << served.value().size() << " clients in " << seconds << " s\n";
    std::cout << text.str();
    std::cout << "total         uplink " << up << " bytes, downlink " << down << " bytes, "
              << packets << " packets; server memory " << window
              << " bytes of windows vs stored fronts " << front << " bytes\n";
  }
  if (failed != nullptr) return tool.fail(address, failed->status);
  return 0;
}
}  // namespace

// --connect: a client on its camera path against a server; the base and
// scene messages give it everything, so no FILE.
int run_stream_connect(const Tool& tool, const Request& request) {
  const std::string address = address_text(*request.connect);
  Result<std::unique_ptr<StreamTransport>> t = tcp_connect(*request.connect);
  if (!t.is_ok()) return tool.fail(address, t.status());
  Result<StreamClientSession> started =
      StreamClientSession::start(t.value().get(), stream_options(request));
  if (!started.is_ok()) return tool.fail(address, started.status());
  StreamClientSession& session = started.value();
  std::string path_file;
  Result<std::vector<CameraFrame>> read = read_path(request, session.sphere(), &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();
  std::vector<StreamFrameStats> frames;
  Progress progress(tool, "streaming");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<StreamFrameStats> f = session.frame(path[i]);
    if (!f.is_ok()) return tool.fail(address, frame_failure(i, f.status()));
    if (request.validate) {
      Status checked = stream_frame_check(session.client(), f.value(), i);
      if (!checked.is_ok()) return tool.fail(address, checked);
    }
    frames.push_back(f.value());
    progress.update(static_cast<double>(i + 1) / static_cast<double>(path.size()));
  }
  t.value()->close();
  if (!request.csv.empty()) {
    Status written = write_stream_csv(request.csv, frames, false);
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }
  const StreamTotals tot =
      stream_totals(frames, session.start_uplink_bytes(), session.start_downlink_bytes());
  const StreamIdWidths& widths = session.client().widths();
  if (tool.json()) {
    nlohmann::json report = connect_report(request, address, tot.frames);
    report.update(nlohmann::json{
        {"uplink", {{"bytes", tot.up}, {"requests", tot.requests}}},
        {"downlink",
         {{"bytes", tot.down}, {"base_bytes", session.base_bytes()}, {"packets", tot.packets}}},
        {"packet", {{"topology_bits", 3 * widths.id_bits()}}},
        {"client",
         {{"splits", tot.splits},
          {"collapses", tot.collapses},
          {"triangles", {{"mean", tot.mean_triangles}, {"max", tot.max_triangles}}}}}});
    if (session.client().has_wedges()) report["wedges"] = {{"count", widths.wedges}};
    tool.print_json(report);
    return 0;
  }
  std::cout << "replay        " << address << ": mode stream over TCP, path " << request.path
            << ", " << tot.frames << " frames"
            << (request.validate ? ", every frame validated" : "") << "\n";
  std::cout << "uplink        " << tot.up << " bytes, " << tot.requests << " view requests in "
            << tot.request_frames << " of " << tot.frames << " frames\n";
  std::cout << "downlink      " << tot.down << " bytes: base " << session.base_bytes() << ", "
            << tot.packets << " vsplit packets\n";
  std::cout << "packet        topology " << 3 * widths.id_bits() << " bits (3 x "
            << widths.id_bits() << "; the paper 96)\n";
  if (session.client().has_wedges()) {
    std::cout << "wedges        " << widths.wedges << " wedges"
              << (request.validate ? ", one at every corner of every frame" : "") << "\n";
  }
  std::cout << "client        " << tot.splits << " splits, " << tot.collapses
            << " collapses, triangles mean " << tot.mean_triangles << ", max " << tot.max_triangles
            << "\n";
  return 0;
}

// Mode stream: the hierarchy served frame by frame to a client that starts
// from the base mesh (Kim, Lee and Kobbelt 2005), bytes counted both ways,
// and the view-independent baseline of section 8.
int run_stream(const Tool& tool, const Request& request, const Bytes& bytes) {
  Result<StreamDb> loaded = load_stream_db(bytes);
  if (!loaded.is_ok()) return tool.fail(request.input, loaded.status());
  if (request.serve) return run_stream_serve(tool, request, loaded.value());
  if (request.clients > 1) return run_stream_clients(tool, request, loaded.value());
  const StreamHierarchy& stream_db = *loaded.value().db;
  const VertexHierarchy& hierarchy = *loaded.value().h;
  Result<StreamSession> created = StreamSession::create(stream_db, stream_options(request));
  if (!created.is_ok()) return tool.fail(request.input, created.status());
  StreamSession& session = created.value();

  const BoundingSphere& sphere = stream_db.sphere;
  std::string path_file;
  Result<std::vector<CameraFrame>> read = read_path(request, sphere, &path_file);
  if (!read.is_ok()) return tool.fail(path_file, read.status());
  const std::vector<CameraFrame> path = std::move(read).value();

  std::vector<StreamFrameStats> frames;
  Progress progress(tool, "streaming");
  for (size_t i = 0; i < path.size(); ++i) {
    Result<StreamFrameStats> f = session.frame(path[i], sphere);
    if (!f.is_ok()) return tool.fail(request.input, frame_failure(i, f.status()));
    frames.push_back(f.value());
    if (request.validate) {
      Status checked = stream_frame_check(session.client(), f.value(), i, &loaded.value());
      if (!checked.is_ok()) return tool.fail(request.input, checked);
    }
    progress.update(static_cast<double>(i + 1) / path.size());
  }
  if (request.validate && sent_twice(session.server().sent())) {
    return tool.fail(request.input,
                     Status(ErrorKind::kValidation, "a vsplit packet was sent twice"));
  }
  Result<StreamBaseline> baseline =
      view_independent_baseline(stream_db, session.server().sent(), session.start_downlink_bytes());
  if (!baseline.is_ok()) return tool.fail(request.input, baseline.status());
  const StreamBaseline& vi = baseline.value();

  if (!request.csv.empty()) {
    Status written = write_stream_csv(request.csv, frames, true);
    if (!written.is_ok()) return tool.fail(request.csv, written);
  }

  const StreamTotals tot =
      stream_totals(frames, session.start_uplink_bytes(), session.start_downlink_bytes());
  const uint64_t up = tot.up, down = tot.down;
  const size_t requests = tot.requests, request_frames = tot.request_frames;
  const size_t packets = tot.packets, splits = tot.splits, collapses = tot.collapses;
  const size_t max_triangles = tot.max_triangles;
  const double triangles = tot.mean_triangles;
  size_t max_window = 0, max_buffer = 0, max_front_bytes = 0;
  for (const StreamFrameStats& f : frames) {
    max_window = std::max(max_window, f.server.window_bytes);
    max_buffer = std::max(max_buffer, f.server.buffer_bytes);
    max_front_bytes = std::max(max_front_bytes, f.server.front_bytes);
  }
  const StreamServerMemory memory = session.server().memory();
  const StreamIdWidths widths = stream_db.widths;
  const int topology_bits = 3 * widths.id_bits();
  const double ratio = static_cast<double>(down) / static_cast<double>(vi.bytes);
  const double window_share =
      static_cast<double>(memory.window_bytes) / static_cast<double>(memory.front_bytes);
  const double buffer_share =
      static_cast<double>(memory.buffer_bytes) / static_cast<double>(memory.front_bytes);
  // An asset's stream: what the wedge data adds to the packets sent.
  uint64_t wedge_bits = 0;
  for (uint32_t s : session.server().sent())
    wedge_bits += vsplit_wedge_bits(stream_db.packet(s), widths);
  const double mean_packet_bits =
      packets == 0 ? 0.0 : static_cast<double>(vi.sent_bits) / static_cast<double>(packets);
  const double mean_wedge_bits =
      packets == 0 ? 0.0 : static_cast<double>(wedge_bits) / static_cast<double>(packets);
  if (tool.json()) {
    nlohmann::json report = camera_report(request, frames.size());
    report.update(nlohmann::json{
        {"hierarchy",
         {{"nodes", hierarchy.node_count()},
          {"roots", hierarchy.root_count()},
          {"splits", vi.pm_splits},
          {"tree_bits", widths.tree_bits},
          {"node_bits", widths.node_bits}}},
        {"uplink",
         {{"bytes", up}, {"requests", requests}, {"frames_with_requests", request_frames}}},
        {"downlink", {{"bytes", down}, {"base_bytes", session.base_bytes()}, {"packets", packets}}},
        {"packet",
         {{"topology_bits", topology_bits},
          {"paper_topology_bits", 96},
          {"earlier_topology_bits", {192, 256}},
          {"mean_bits", mean_packet_bits}}},
        {"client",
         {{"splits", splits},
          {"collapses", collapses},
          {"triangles", {{"mean", triangles}, {"max", max_triangles}}}}},
        {"server_memory",
         {{"window_bytes", memory.window_bytes},
          {"buffer_bytes", memory.buffer_bytes},
          {"front_nodes", memory.front_nodes},
          {"front_bytes", memory.front_bytes},
          {"max_window_bytes", max_window},
          {"max_buffer_bytes", max_buffer},
          {"max_front_bytes", max_front_bytes}}},
        {"view_independent",
         {{"prefix_splits", vi.prefix},
          {"pm_splits", vi.pm_splits},
          {"bytes", vi.bytes},
          {"full_bytes", vi.full_bytes},
          {"view_dependent_share", ratio}}}});
    if (widths.wedges != 0) {
      report["packet"]["mean_wedge_bits"] = mean_wedge_bits;
      report["packet"]["mean_bits_without_wedges"] = mean_packet_bits - mean_wedge_bits;
      report["wedges"] = {{"count", widths.wedges}, {"validated", request.validate}};
    }
    tool.print_json(report);
    return 0;
  }
  print_replay_line(request, frames.size());
  std::cout << "hierarchy     " << hierarchy.node_count() << " nodes, " << hierarchy.root_count()
            << " roots, " << vi.pm_splits << " splits, <tree-id, node-id> <" << widths.tree_bits
            << ", " << widths.node_bits << ">\n";
  print_view(request);
  std::cout << "\n";
  std::cout << "uplink        " << up << " bytes, " << requests << " view requests in "
            << request_frames << " of " << frames.size() << " frames\n";
  std::cout << "downlink      " << down << " bytes: base " << session.base_bytes() << ", "
            << packets << " vsplit packets of " << vi.pm_splits << "\n";
  std::cout << "packet        topology " << topology_bits << " bits (3 x " << widths.id_bits()
            << "; the paper 96, earlier schemes 192-256), mean "
            << (packets == 0 ? 0.0
                             : static_cast<double>(vi.sent_bits) / static_cast<double>(packets))
            << " bits with geometry and refinement data\n";
  if (widths.wedges != 0) {
    std::cout << "wedges        " << widths.wedges << " wedges"
              << (request.validate ? " (every corner's checked against the server's front)" : "")
              << ": " << mean_wedge_bits << " bits per split of the mean " << mean_packet_bits
              << " (" << mean_packet_bits - mean_wedge_bits << " without them)\n";
  }
  std::cout << "client        " << splits << " splits, " << collapses
            << " collapses, triangles mean " << triangles << ", max " << max_triangles << "\n";
  std::cout << "server memory window " << memory.window_bytes << " bytes (buffer "
            << memory.buffer_bytes << ") vs a stored vertex front " << memory.front_bytes
            << " bytes (" << memory.front_nodes << " nodes): " << 100 * window_share << "% ("
            << 100 * buffer_share << "%)\n";
  std::cout << "vs view-indep " << down << " vs " << vi.bytes << " bytes (" << 100 * ratio
            << "%): the PM's fixed order needs a prefix of " << vi.prefix << " of " << vi.pm_splits
            << " splits to hold the " << packets << " sent; the whole PM is " << vi.full_bytes
            << " bytes (the paper: bunny 177,120 vs 827,688, dragon 946,400 vs 3,816,384)\n";
  return 0;
}

}  // namespace lodbake::cli::replay
