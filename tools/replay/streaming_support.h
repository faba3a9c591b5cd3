// lodbake-replay's pieces shared by the streaming modes (stream, vtrees):
// the --serve opening (listener, address line, server timeouts), the
// address and per-client labels of their reports, and the check that no
// packet or record went twice to a client.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "lib/replay/stream_transport.h"
#include "tools/replay/replay_request.h"

namespace lodbake::cli::replay {

/// "127.0.0.1:PORT".
std::string address_text(const LoopbackAddress& a);

/// "client 3      ": a client's line label.
std::string client_label(size_t k);

/// Whether an id occurs twice in `ids` (the packets or node records sent).
bool sent_twice(std::vector<uint32_t> ids);

/// --serve's opening: the listener on the requested port, its address as
/// stdout's first line (flushed: a script waits for it), and the server's
/// timeouts (a minute: clients start when they like).
struct Serving {
  std::optional<TcpListener> listener;
  std::string address;
  TcpOptions tcp;
  std::chrono::steady_clock::time_point start;
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

/// Empty when listening; else the exit code (the failure reported).
std::optional<int> start_serving(const Tool& tool, const Request& request, Serving* out);

}  // namespace lodbake::cli::replay
