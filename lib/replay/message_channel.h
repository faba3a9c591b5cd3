// Two in-memory message queues between a client and a server in one
// process, counting every byte and message both ways: what a one-thread
// simulation of a client-server system needs when its messages are not mode
// stream's (whose StreamTransport checks its own header on every message).
#pragma once

#include <cstdint>
#include <deque>
#include <utility>

#include "formats/support/file_io.h"

namespace lodbake {

class MessageChannel {
 public:
  void send_up(Bytes message) { push(&up_, &up_bytes_, &up_messages_, std::move(message)); }
  void send_down(Bytes message) { push(&down_, &down_bytes_, &down_messages_, std::move(message)); }
  /// False when the queue is empty.
  bool receive_up(Bytes* message) { return pop(&up_, message); }
  bool receive_down(Bytes* message) { return pop(&down_, message); }
  uint64_t uplink_bytes() const { return up_bytes_; }
  uint64_t downlink_bytes() const { return down_bytes_; }
  uint64_t uplink_messages() const { return up_messages_; }
  uint64_t downlink_messages() const { return down_messages_; }

 private:
  static void push(std::deque<Bytes>* queue, uint64_t* bytes, uint64_t* messages, Bytes m) {
    *bytes += m.size();
    ++*messages;
    queue->push_back(std::move(m));
  }
  static bool pop(std::deque<Bytes>* queue, Bytes* message) {
    if (queue->empty()) return false;
    *message = std::move(queue->front());
    queue->pop_front();
    return true;
  }

  std::deque<Bytes> up_;
  std::deque<Bytes> down_;
  uint64_t up_bytes_ = 0, down_bytes_ = 0, up_messages_ = 0, down_messages_ = 0;
};

}  // namespace lodbake
