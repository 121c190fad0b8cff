// A small blocking client of protocol v1 for the CLI, the UI and tests:
// one request at a time; events that arrive meanwhile are kept (bounded)
// for wait_event().
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/control/framing.hpp"
#include "knoblab/control/messages.hpp"

namespace knoblab::control {

// Transport trouble: cannot connect, timed out, connection lost, or the
// server broke the protocol. The connection is unusable afterwards except
// after a timeout (a late reply is recognised by its id and skipped).
class ClientError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The server answered with an error (thrown by call()/hello()).
class RemoteError : public std::runtime_error {
 public:
  RemoteError(Error error);
  const Error& error() const noexcept { return error_; }
  ErrorCode code() const noexcept { return error_.code; }

 private:
  Error error_;
};

struct HelloOptions {
  std::vector<int> versions{kProtocolVersion};
  std::string client_name;
  // Become the supervising client: from then on send a request (ping) well
  // within every watchdog_ms, e.g. from a timer, or the motor goes safe.
  std::optional<int> watchdog_ms;
};

class Client {
 public:
  using Duration = std::chrono::milliseconds;

  // Connects; throws ClientError.
  explicit Client(const std::string& socket_path, Duration timeout = std::chrono::seconds(2));
  ~Client();
  Client(Client&& other) noexcept;
  Client& operator=(Client&& other) noexcept;
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // hello; returns its result. Throws RemoteError (e.g. busy, unsupported_version).
  nlohmann::json hello(const HelloOptions& options = {});

  // Sends one request and waits for its reply (ok or error). If the server
  // had already closed the connection, the reply is the error it gave as its
  // reason (e.g. busy), when it gave one; else ClientError.
  Reply request(std::string_view cmd, nlohmann::json args = nlohmann::json::object());
  Reply request(std::string_view cmd, nlohmann::json args, Duration timeout);
  // request(), returning the result or throwing RemoteError.
  nlohmann::json call(std::string_view cmd, nlohmann::json args = nlohmann::json::object());

  // The next pushed event (queued earlier or arriving within timeout).
  std::optional<Event> wait_event(Duration timeout);
  // Events discarded because nobody called wait_event (queue bound).
  std::uint64_t events_dropped() const noexcept { return events_dropped_; }

  void set_timeout(Duration timeout) noexcept { timeout_ = timeout; }
  int native_handle() const noexcept { return fd_; }
  bool connected() const noexcept { return fd_ >= 0; }
  void close() noexcept;

  static constexpr std::size_t kMaxQueuedEvents = 4096;

 private:
  using Deadline = std::chrono::steady_clock::time_point;
  // 0 once every byte is sent, else the errno of a lost connection. Throws
  // ClientError at the deadline.
  int send_all(const std::string& bytes, Deadline deadline);
  // A reply without an id the server sent before closing (why it closed),
  // if one has arrived.
  std::optional<Reply> parting_reply();
  // The next message from the server, or nullopt at the deadline.
  std::optional<ServerMessage> receive(Deadline deadline);
  void keep_event(Event event);

  int fd_ = -1;
  Duration timeout_;
  std::int64_t next_id_ = 1;
  FrameDecoder decoder_;
  std::deque<Event> events_;
  std::uint64_t events_dropped_ = 0;
};

}  // namespace knoblab::control
