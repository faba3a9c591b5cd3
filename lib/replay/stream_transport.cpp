// The message transports (lib/replay/stream_transport.h). Choices:
// - framing is the message header itself (magic/version, type, uint32
//   length), checked against the family an end receives (a descriptor, not
//   a template or a callback: the families differ only in data): the
//   receiver reads 6 bytes, refuses a bad header, another family's magic or
//   a length over its limit before allocating, then reads the payload into a
//   buffer that grows as bytes arrive (at most 1 MiB ahead of them), so a
//   peer that announces a large message and sends nothing costs nothing;
// - plain POSIX sockets, IPv4 loopback only (the issue's "--serve PORT /
//   --connect 127.0.0.1:PORT"), TCP_NODELAY (a view request is 86 bytes and
//   waits for its answer), MSG_NOSIGNAL (a vanished peer is a kIo status,
//   not SIGPIPE), and poll() before every read and write so a dead or
//   silent peer ends in a timeout instead of a hang;
// - the in-memory pipe runs every message through the same header check,
//   so the one-process simulation refuses what a socket would.
#include "lib/replay/stream_transport.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>
#include <vector>

namespace lodbake {
namespace {

// ---- in-memory pipe ----

struct Pipe {
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<Bytes> queue[2];       // [0]: to end 0, [1]: to end 1
  bool closed[2] = {false, false};  // end k closed
};

class MemoryTransport final : public StreamTransport {
 public:
  MemoryTransport(std::shared_ptr<Pipe> pipe, int end, int timeout_ms,
                  const MessageFamily& receives)
      : StreamTransport(receives), pipe_(std::move(pipe)), end_(end), timeout_ms_(timeout_ms) {}
  ~MemoryTransport() override { close(); }

  Status send(const Bytes& message) override {
    std::lock_guard<std::mutex> lock(pipe_->mutex);
    if (pipe_->closed[end_]) return io_error("stream transport: this end is closed");
    if (pipe_->closed[1 - end_])
      return io_error("stream transport: the peer closed the connection");
    pipe_->queue[1 - end_].push_back(message);
    pipe_->ready.notify_all();
    count_sent(message.size());
    return Status::ok();
  }

  Result<Bytes> receive(bool* closed) override {
    *closed = false;
    std::unique_lock<std::mutex> lock(pipe_->mutex);
    std::deque<Bytes>& q = pipe_->queue[end_];
    const auto has_news = [&] {
      return !q.empty() || pipe_->closed[1 - end_] || pipe_->closed[end_];
    };
    if (!has_news() && timeout_ms_ > 0) {
      pipe_->ready.wait_for(lock, std::chrono::milliseconds(timeout_ms_), has_news);
    }
    if (pipe_->closed[end_]) return io_error("stream transport: this end is closed");
    if (q.empty()) {
      if (pipe_->closed[1 - end_]) {
        *closed = true;
        return Bytes();
      }
      return io_error("stream transport: no message within " + std::to_string(timeout_ms_) + " ms");
    }
    Bytes m = std::move(q.front());
    q.pop_front();
    lock.unlock();
    LODBAKE_ASSIGN_OR_RETURN(uint32_t length, checked_length(m.data(), m.size()));
    if (m.size() != kMessageHeaderBytes + length) {
      return invalid_input(std::string(receives().name) + " message: header says " +
                           std::to_string(length) + " payload bytes, " +
                           std::to_string(m.size() - kMessageHeaderBytes) + " follow");
    }
    count_received(m.size());
    return m;
  }

  void close() override {
    std::lock_guard<std::mutex> lock(pipe_->mutex);
    pipe_->closed[end_] = true;
    pipe_->queue[end_].clear();
    pipe_->ready.notify_all();
  }

 private:
  std::shared_ptr<Pipe> pipe_;
  int end_;
  int timeout_ms_;
};

// ---- TCP ----

std::string errno_text() {
  return std::strerror(errno);
}

// Waits for `events` on fd; false on timeout (errno ETIMEDOUT) or error.
bool wait_fd(int fd, short events, int timeout_ms) {
  pollfd p{fd, events, 0};
  for (;;) {
    const int r = ::poll(&p, 1, timeout_ms);
    if (r > 0) return true;
    if (r == 0) {
      errno = ETIMEDOUT;
      return false;
    }
    if (errno != EINTR) return false;
  }
}

class TcpTransport final : public StreamTransport {
 public:
  TcpTransport(int fd, const TcpOptions& options, const MessageFamily& receives)
      : StreamTransport(receives), fd_(fd), options_(options) {}
  ~TcpTransport() override { close(); }

  Status send(const Bytes& message) override {
    if (fd_ < 0) return io_error("stream transport: the connection is closed");
    size_t done = 0;
    while (done < message.size()) {
      if (!wait_fd(fd_, POLLOUT, options_.io_timeout_ms)) {
        return io_error("stream transport: send: " + errno_text());
      }
      const ssize_t n = ::send(fd_, message.data() + done, message.size() - done, MSG_NOSIGNAL);
      if (n < 0) {
        if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) continue;
        return io_error("stream transport: send: " + errno_text());
      }
      done += static_cast<size_t>(n);
    }
    count_sent(message.size());
    return Status::ok();
  }

  Result<Bytes> receive(bool* closed) override {
    *closed = false;
    if (fd_ < 0) return io_error("stream transport: the connection is closed");
    try {
      Bytes m(kMessageHeaderBytes);
      size_t got = 0;
      LODBAKE_RETURN_IF_ERROR(read_into(&m, 0, kMessageHeaderBytes, &got));
      if (got == 0) {
        *closed = true;
        return Bytes();
      }
      if (got < kMessageHeaderBytes) {
        return io_error("stream transport: the peer closed the connection inside a message header");
      }
      LODBAKE_ASSIGN_OR_RETURN(uint32_t length, checked_length(m.data(), m.size()));
      // Grow with what arrives, not with what the header announces.
      constexpr size_t kStep = size_t{1} << 20;
      size_t have = kMessageHeaderBytes;
      const size_t total = kMessageHeaderBytes + size_t{length};
      while (have < total) {
        const size_t chunk = std::min(kStep, total - have);
        m.resize(have + chunk);
        LODBAKE_RETURN_IF_ERROR(read_into(&m, have, chunk, &got));
        if (got < chunk) {
          return io_error("stream transport: the peer closed the connection inside a message (" +
                          std::to_string(have + got) + " of " + std::to_string(total) + " bytes)");
        }
        have += chunk;
      }
      count_received(m.size());
      return m;
    } catch (const std::bad_alloc&) {
      return runtime_error(std::string("out of memory receiving a ") + receives().name +
                           " message");
    }
  }

  void close() override {
    if (fd_ >= 0) {
      ::shutdown(fd_, SHUT_RDWR);
      ::close(fd_);
      fd_ = -1;
    }
  }

 private:
  // Reads up to `want` bytes at offset `at`; *got < want only at EOF.
  Status read_into(Bytes* m, size_t at, size_t want, size_t* got) {
    *got = 0;
    while (*got < want) {
      if (!wait_fd(fd_, POLLIN, options_.io_timeout_ms)) {
        return io_error("stream transport: receive: " +
                        (errno == ETIMEDOUT ? "nothing from the peer within " +
                                                  std::to_string(options_.io_timeout_ms) + " ms"
                                            : errno_text()));
      }
      const ssize_t n = ::recv(fd_, m->data() + at + *got, want - *got, 0);
      if (n == 0) return Status::ok();
      if (n < 0) {
        if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) continue;
        return io_error("stream transport: receive: " + errno_text());
      }
      *got += static_cast<size_t>(n);
    }
    return Status::ok();
  }

  int fd_;
  TcpOptions options_;
};

sockaddr_in socket_address(const LoopbackAddress& a) {
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(a.port);
  ::inet_pton(AF_INET, a.host.c_str(), &sa.sin_addr);
  return sa;
}

std::string text_of(const LoopbackAddress& a) {
  return a.host + ":" + std::to_string(a.port);
}

void set_nodelay(int fd) {
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

}  // namespace

std::pair<std::unique_ptr<StreamTransport>, std::unique_ptr<StreamTransport>>
make_memory_transport_pair(int timeout_ms, const MessageFamily& first_receives,
                           const MessageFamily& second_receives) {
  auto pipe = std::make_shared<Pipe>();
  return {std::make_unique<MemoryTransport>(pipe, 0, timeout_ms, first_receives),
          std::make_unique<MemoryTransport>(pipe, 1, timeout_ms, second_receives)};
}

Result<LoopbackAddress> parse_loopback_address(const std::string& text) {
  const size_t colon = text.rfind(':');
  auto usage = [&](const std::string& why) {
    return Status(ErrorKind::kUsage,
                  "'" + text + "' is not a loopback address HOST:PORT (" + why + ")");
  };
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) {
    return usage("HOST:PORT, such as 127.0.0.1:4000");
  }
  LoopbackAddress a;
  a.host = text.substr(0, colon);
  if (a.host == "localhost") a.host = "127.0.0.1";
  const std::string port = text.substr(colon + 1);
  unsigned value = 0;
  const auto parsed = std::from_chars(port.data(), port.data() + port.size(), value);
  if (parsed.ec != std::errc() || parsed.ptr != port.data() + port.size() || value > 65535) {
    return usage("the port is not 0 .. 65535");
  }
  a.port = static_cast<uint16_t>(value);
  in_addr ip{};
  if (::inet_pton(AF_INET, a.host.c_str(), &ip) != 1)
    return usage("the host is not an IPv4 address");
  if ((ntohl(ip.s_addr) >> 24) != 127) return usage("only loopback, 127.x.y.z, is served");
  return a;
}

Result<std::unique_ptr<StreamTransport>> tcp_connect(const LoopbackAddress& address,
                                                     const TcpOptions& options,
                                                     const MessageFamily& receives) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return io_error("socket: " + errno_text());
  const sockaddr_in sa = socket_address(address);
  int r = ::connect(fd, reinterpret_cast<const sockaddr*>(&sa), sizeof sa);
  if (r < 0 && errno == EINPROGRESS) {
    if (!wait_fd(fd, POLLOUT, options.connect_timeout_ms)) {
      const std::string why = errno_text();
      ::close(fd);
      return io_error("cannot connect to " + text_of(address) + ": " + why);
    }
    int err = 0;
    socklen_t len = sizeof err;
    ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len);
    errno = err;
    r = err == 0 ? 0 : -1;
  }
  if (r < 0) {
    const std::string why = errno_text();
    ::close(fd);
    return io_error("cannot connect to " + text_of(address) + ": " + why);
  }
  set_nodelay(fd);
  return std::unique_ptr<StreamTransport>(std::make_unique<TcpTransport>(fd, options, receives));
}

Result<TcpListener> TcpListener::listen(const LoopbackAddress& address, int backlog) {
  TcpListener l;
  l.fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (l.fd_ < 0) return io_error("socket: " + errno_text());
  const int one = 1;
  ::setsockopt(l.fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in sa = socket_address(address);
  if (::bind(l.fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) < 0 ||
      ::listen(l.fd_, backlog) < 0) {
    return io_error("cannot listen on " + text_of(address) + ": " + errno_text());
  }
  socklen_t len = sizeof sa;
  ::getsockname(l.fd_, reinterpret_cast<sockaddr*>(&sa), &len);
  l.port_ = ntohs(sa.sin_port);
  l.host_ = address.host;
  return l;
}

TcpListener::TcpListener(TcpListener&& o) noexcept : fd_(o.fd_), port_(o.port_), host_(o.host_) {
  o.fd_ = -1;
}

TcpListener& TcpListener::operator=(TcpListener&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = o.fd_;
    port_ = o.port_;
    host_ = o.host_;
    o.fd_ = -1;
  }
  return *this;
}

TcpListener::~TcpListener() {
  if (fd_ >= 0) ::close(fd_);
}

Result<std::unique_ptr<StreamTransport>> TcpListener::accept(const TcpOptions& options,
                                                             const MessageFamily& receives) {
  for (;;) {
    if (!wait_fd(fd_, POLLIN, options.connect_timeout_ms)) {
      return io_error("no client connected to " + host_ + ":" + std::to_string(port_) + " within " +
                      std::to_string(options.connect_timeout_ms) + " ms");
    }
    const int fd = ::accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0) {
      if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK || errno == ECONNABORTED) {
        continue;
      }
      return io_error("accept on " + host_ + ":" + std::to_string(port_) + ": " + errno_text());
    }
    set_nodelay(fd);
    return std::unique_ptr<StreamTransport>(std::make_unique<TcpTransport>(fd, options, receives));
  }
}

Status serve_connections(TcpListener* listener, size_t clients, const TcpOptions& tcp,
                         const MessageFamily& receives, const ConnectionServer& serve) {
  std::vector<std::thread> threads;
  Status accept_status;
  try {
    for (size_t k = 0; k < clients; ++k) {
      Result<std::unique_ptr<StreamTransport>> t = listener->accept(tcp, receives);
      if (!t.is_ok()) {
        accept_status = t.status();
        break;
      }
      threads.emplace_back([&serve, k, transport = std::move(t).value()]() mutable {
        serve(k, std::move(transport));
      });
    }
  } catch (const std::system_error& e) {
    accept_status = runtime_error(std::string("cannot start a server thread: ") + e.what());
  }
  for (std::thread& t : threads)
    t.join();
  return accept_status;
}

}  // namespace lodbake
