// How replay messages travel (issue 9): one interface with two
// implementations, so the same session code runs over an in-memory pipe
// (the one-process simulation, and tests that cut it on purpose) or a TCP
// socket on loopback (lodbake-replay --serve / --connect). A message is
// framed by its own header (lib/replay/message_family.h): a receiver reads
// the 6 header bytes, checks them against the message family its end was
// built to receive (mode stream's, kStreamMessages, or mode vtrees',
// kVtreesMessages) and the announced length against its limit before it
// allocates anything, then reads the payload. The two ends of a connection
// may receive different families: a vtrees client receives vtrees
// messages, its server mode stream's view requests.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/replay/message_family.h"
#include "lib/replay/stream_packets.h"

namespace lodbake {

/// One end of a message connection, receiving one message family. Not
/// thread-safe: one thread per end.
class StreamTransport {
 public:
  explicit StreamTransport(const MessageFamily& receives = kStreamMessages)
      : receives_(receives), max_payload_(receives.max_payload) {}
  virtual ~StreamTransport() = default;
  /// Sends one whole message (its header included). kIo when the peer is
  /// gone or the send times out.
  virtual Status send(const Bytes& message) = 0;
  /// The next whole message. Sets *closed (and returns an empty message)
  /// when the peer closed the connection cleanly between two messages; kIo
  /// when it closes inside one or nothing arrives within the timeout;
  /// kInvalidInput when the header is malformed, is not of the family
  /// receives() or announces more than max_payload() bytes (nothing is
  /// allocated for it); kUnsupported for a newer version of the family.
  virtual Result<Bytes> receive(bool* closed) = 0;
  /// Closes this end; the peer's next receive() sees a clean close.
  virtual void close() = 0;

  /// The message family receive() takes.
  const MessageFamily& receives() const { return receives_; }
  /// The largest payload receive() takes (at most receives().max_payload,
  /// the default).
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
  /// The payload length of a received header, checked (message_payload_length()).
  Result<uint32_t> checked_length(const uint8_t* header, size_t size) const {
    return message_payload_length(receives_, header, size, max_payload_);
  }

 private:
  MessageFamily receives_;
  uint32_t max_payload_;
  uint64_t bytes_sent_ = 0, bytes_received_ = 0, messages_sent_ = 0, messages_received_ = 0;
};

/// Two connected in-memory ends. `timeout_ms` is how long receive() waits
/// for a message (0: a receive on an empty queue fails at once, which is
/// what a one-thread simulation wants: it only receives what was sent).
/// Messages pass through the same header checks as over a socket: the
/// first end receives `first_receives`, the second `second_receives`.
std::pair<std::unique_ptr<StreamTransport>, std::unique_ptr<StreamTransport>>
make_memory_transport_pair(int timeout_ms = 0,
                           const MessageFamily& first_receives = kStreamMessages,
                           const MessageFamily& second_receives = kStreamMessages);

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

/// A TCP connection to a loopback server, receiving `receives`. kIo naming
/// the address when nobody listens (or the connection times out).
Result<std::unique_ptr<StreamTransport>> tcp_connect(
    const LoopbackAddress& address, const TcpOptions& options = TcpOptions(),
    const MessageFamily& receives = kStreamMessages);

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
  /// The next client, its end receiving `receives`; kIo when none comes
  /// within options.connect_timeout_ms.
  Result<std::unique_ptr<StreamTransport>> accept(const TcpOptions& options = TcpOptions(),
                                                  const MessageFamily& receives = kStreamMessages);

 private:
  TcpListener() = default;
  int fd_ = -1;
  uint16_t port_ = 0;
  std::string host_;
};

/// Runs one connection's server side; it owns the transport.
using ConnectionServer = std::function<void(size_t index, std::unique_ptr<StreamTransport>)>;

/// Accepts `clients` connections on `listener`, their ends receiving
/// `receives`, and runs serve(k, transport) for connection k on its own
/// thread (serve must not throw); returns when every connection has ended.
/// Fails only when a client does not connect within the accept timeout or
/// a thread cannot start (after the connections already accepted ended).
Status serve_connections(TcpListener* listener, size_t clients, const TcpOptions& tcp,
                         const MessageFamily& receives, const ConnectionServer& serve);

}  // namespace lodbake
