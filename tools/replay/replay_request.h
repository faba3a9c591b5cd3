// lodbake-replay's request and its modes' entry points: main.cpp parses and
// validates the options into one Request and dispatches to the mode's run_*
// function; each mode lives in its own file (camera_modes.cpp: vhier, dag,
// fan; sets_mode.cpp; stream_mode.cpp; vtrees_mode.cpp). Every run_* returns
// the tool's exit code, a failure already reported through `tool`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "formats/support/file_io.h"
#include "lib/replay/dag_replay.h"
#include "lib/replay/fan_replay.h"
#include "lib/replay/sets_replay.h"
#include "lib/replay/stream_transport.h"
#include "lib/replay/vhier_replay.h"
#include "tools/common/cli.h"

namespace lodbake::cli::replay {

inline constexpr const char* kReplaySchema = "lodbake.replay/1";

struct Request {
  std::string input;
  std::string mode = "vhier";
  std::string path = "scan";
  std::string csv;
  std::string plot;  // --plot DIR
  std::string tolerance = "1";
  std::string traversal = "priority";
  std::string budget_mode = "auto";
  float fov_degrees = 60;
  bool validate = false;
  VhierReplayOptions options;
  DagReplayOptions dag;
  bool dag_no_back_face = false;         // --no-back-face; sets dag.back_face
  std::vector<DagTraversal> traversals;  // dag: the lanes replayed
  FanReplayOptions fan;
  // Mode sets.
  std::vector<double> percents = paper_recovery_percents();
  std::string spacing = "both";
  // Modes stream and vtrees over TCP: --serve PORT (a server for `clients`
  // connections) or --connect ADDRESS (a client, no FILE); mode stream:
  // --clients K without --serve runs K clients in one process.
  std::optional<LoopbackAddress> serve;
  std::optional<LoopbackAddress> connect;
  size_t clients = 1;
};

/// Modes vhier, dag and fan on the container's bytes (camera_modes.cpp).
int run_camera_path(const Tool& tool, const Request& request, const Bytes& bytes);

/// Mode sets (sets_mode.cpp).
int run_sets(const Tool& tool, const Request& request, const Bytes& bytes);

/// Mode stream in process, with --serve or with --clients K
/// (stream_mode.cpp); --connect: a client with no FILE.
int run_stream(const Tool& tool, const Request& request, const Bytes& bytes);
int run_stream_connect(const Tool& tool, const Request& request);

/// Mode vtrees in process or with --serve (vtrees_mode.cpp); --connect: a
/// client with no FILE.
int run_vtrees(const Tool& tool, const Request& request, const Bytes& bytes);
int run_vtrees_connect(const Tool& tool, const Request& request);

}  // namespace lodbake::cli::replay
