// lodbake-replay's pieces shared by the streaming modes (streaming_support.h).
#include "tools/replay/streaming_support.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

namespace lodbake::cli::replay {

std::string address_text(const LoopbackAddress& a) {
  return a.host + ":" + std::to_string(a.port);
}

std::string client_label(size_t k) {
  char label[32];
  std::snprintf(label, sizeof label, "client %-6zu", k);
  return label;
}

bool sent_twice(std::vector<uint32_t> ids) {
  std::sort(ids.begin(), ids.end());
  return std::adjacent_find(ids.begin(), ids.end()) != ids.end();
}

std::optional<int> start_serving(const Tool& tool, const Request& request, Serving* out) {
  Result<TcpListener> listener = TcpListener::listen(*request.serve);
  if (!listener.is_ok()) return tool.fail(address_text(*request.serve), listener.status());
  out->listener.emplace(std::move(listener).value());
  out->address = out->listener->host() + ":" + std::to_string(out->listener->port());
  std::cout << out->address << std::endl;
  out->tcp.connect_timeout_ms = 60000;
  out->tcp.io_timeout_ms = 60000;
  out->start = std::chrono::steady_clock::now();
  return std::nullopt;
}

}  // namespace lodbake::cli::replay
