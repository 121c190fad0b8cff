// One client connection on the server side: its bounded read buffer, its
// bounded queue of outgoing frames, and what it subscribed to.
#pragma once

#include <bitset>
#include <chrono>
#include <cstddef>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include <sys/types.h>

#include "knoblab/control/framing.hpp"
#include "knoblab/control/messages.hpp"
#include "knoblab/control/protocol.hpp"
#include "unique_fd.hpp"

namespace knoblab::control::detail {

using Frame = std::shared_ptr<const std::string>;  // shared by every subscriber of an event

class Connection {
 public:
  using Clock = std::chrono::steady_clock;
  enum class ReadStatus { data, would_block, eof, error };

  Connection(UniqueFd fd, ClientId id, std::size_t max_queued_bytes, Clock::time_point accepted_at,
             std::optional<pid_t> peer_pid);

  int fd() const { return fd_.get(); }
  ClientId id() const { return id_; }
  FrameDecoder& decoder() { return decoder_; }

  // One read() into the decoder's free space.
  ReadStatus read_some();

  // False if the frame would push the queue past its bound: the caller
  // drops the client rather than let it hold memory.
  bool enqueue(Frame frame);
  // Writes what the socket accepts now, never blocking. False if the peer
  // is gone.
  bool flush();
  bool wants_write() const { return !queue_.empty(); }

  std::bitset<kEventNames.size()> subscriptions;
  // Stop reading, close once the queue is flushed or at close_deadline
  // (after oversized, an incomplete frame timing out, or the peer's EOF).
  bool closing = false;
  Clock::time_point close_deadline{};
  bool dead = false;
  // Since when a started frame has been waiting for its remaining bytes.
  std::optional<Clock::time_point> partial_since;
  // For the idle rules: when the connection was accepted, and when its last
  // valid request arrived (none yet: it has not said hello).
  Clock::time_point accepted_at;
  std::optional<Clock::time_point> last_request;
  // The process that connected (SO_PEERCRED), for max_clients_per_peer;
  // nullopt when the kernel cannot name it (e.g. another pid namespace).
  std::optional<pid_t> peer_pid;

 private:
  UniqueFd fd_;
  ClientId id_;
  FrameDecoder decoder_;
  std::size_t max_queued_bytes_;
  std::deque<Frame> queue_;
  std::size_t queued_bytes_ = 0;
  std::size_t front_offset_ = 0;  // bytes of queue_.front() already sent
};

// The process on the other end of a connected Unix socket, or nullopt.
std::optional<pid_t> peer_process(int fd);

}  // namespace knoblab::control::detail
