// How stream messages travel (issue 9): one interface with two
// implementations, so the same session code runs over an in-memory pipe
// (the one-process simulation, and tests that cut it on purpose) or a TCP
// socket on loopback (lodbake-replay --serve / --connect). A message is
// framed by its own header (lib/replay/stream_packets.h): a receiver reads
// the 6 header bytes, checks them and the announced length against its
// limit before it allocates anything, then reads the payload.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/stream_packets.h"

namespace lodbake {

/// One end of a message connection. Not thread-safe: one thread per end.
class StreamTransport {
 public:
  virtual ~StreamTransport() = default;
  /// Sends one whole message (its header included). kIo when the peer is
  /// gone or the send times out.
  virtual Status send(const Bytes& message) = 0;
  /// The next whole message. Sets *closed (and returns an empty message)
  /// when the peer closed the connection cleanly between two messages; kIo
  /// when it closes inside one or nothing arrives within the timeout;
  /// kInvalidInput when the header is malformed or announces more than
  /// max_payload() bytes (nothing is allocated for it).
  virtual Result<Bytes> receive(bool* closed) = 0;
  /// Closes this end; the peer's next receive() sees a clean close.
  virtual void close() = 0;

  /// The largest payload receive() takes (at most kMaxStreamPayloadBytes).
  void set_max_payload(uint32_t bytes) { max_payload_ = bytes; }
  uint32_t max_payload() const { return max_payload_; }
  uint64_t bytes_sent() const { return bytes_sent_; }
  uint64_t bytes_received() const { return bytes_received_; }
  uint64_t messages_sent() const { return messages_sent_; }
  uint64_t messages_received() const { return messages_received_; }

 protected:
  void count_sent(size_t bytes) {
    bytes_sent_ += bytes;
    ++messages_sent_;
  }
  void count_received(size_t bytes) {
    bytes_received_ += bytes;
    ++messages_received_;
  }

 private:
  uint32_t max_payload_ = kMaxStreamPayloadBytes;
  uint64_t bytes_sent_ = 0, bytes_received_ = 0, messages_sent_ = 0, messages_received_ = 0;
};

/// Two connected in-memory ends. `timeout_ms` is how long receive() waits
/// for a message (0: a receive on an empty queue fails at once, which is
/// what a one-thread simulation wants: it only receives what was sent).
/// Messages pass through the same header checks as over a socket.
std::pair<std::unique_ptr<StreamTransport>, std::unique_ptr<StreamTransport>>
make_memory_transport_pair(int timeout_ms = 0);

struct TcpOptions {
  /// Per send and per receive: a peer silent for this long is dead.
  int io_timeout_ms = 10000;
  /// connect() and accept().
  int connect_timeout_ms = 10000;
};

/// "127.0.0.1:PORT" (any 127.x.y.z, or localhost) -> address and port.
/// kUsage for anything else: a malformed address, a port outside 0..65535,
/// or an address that is not loopback (the transport serves loopback only).
struct LoopbackAddress {
  std::string host = "127.0.0.1";
  uint16_t port = 0;
};
Result<LoopbackAddress> parse_loopback_address(const std::string& text);

/// A TCP connection to a loopback server. kIo naming the address when
/// nobody listens (or the connection times out).
Result<std::unique_ptr<StreamTransport>> tcp_connect(const LoopbackAddress& address,
                                                     const TcpOptions& options = TcpOptions());

/// A listening socket on a loopback address; port 0 picks a free port
/// (port() says which).
class TcpListener {
 public:
  static Result<TcpListener> listen(const LoopbackAddress& address, int backlog = 64);
  TcpListener(TcpListener&& o) noexcept;
  TcpListener& operator=(TcpListener&& o) noexcept;
  TcpListener(const TcpListener&) = delete;
  TcpListener& operator=(const TcpListener&) = delete;
  ~TcpListener();

  uint16_t port() const { return port_; }
  const std::string& host() const { return host_; }
  /// The next client; kIo when none comes within options.connect_timeout_ms.
  Result<std::unique_ptr<StreamTransport>> accept(const TcpOptions& options = TcpOptions());

 private:
  TcpListener() = default;
  int fd_ = -1;
  uint16_t port_ = 0;
  std::string host_;
};

}  // namespace lodbake
