// The control socket of hapticd: a Unix stream socket serving protocol v1 to
// many clients from one non-realtime thread (poll). Slow or hostile clients
// cost bounded memory and never block the others; silent ones, and one
// process's connections beyond its share, do not keep the others out.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "knoblab/control/command_handler.hpp"
#include "knoblab/control/messages.hpp"

namespace knoblab::control {

struct ServerConfig {
  std::string socket_path = "/run/knoblab/hapticd.sock";
  // Group that owns the socket (mode 0660): its members may control the
  // device. Empty keeps the process's group. A name that does not exist is
  // a startup error.
  std::string socket_group;
  std::size_t max_clients = 16;
  // Connections one process (SO_PEERCRED pid) may hold at once; one more is
  // refused with busy. Without it a single client (a runaway script, a tool
  // that leaks connections) could take every slot and lock the UI out.
  // Zero: no limit.
  std::size_t max_clients_per_peer = 4;
  // A new connection must send a valid request (hello, or any other) within
  // this long, or it gets busy and is closed: a peer that connects and says
  // nothing would otherwise hold a slot forever (the partial-frame timeout
  // starts only at a frame's first byte). Zero: no limit.
  std::chrono::milliseconds hello_timeout{5000};
  // A connection that sends no valid request for this long is closed with
  // busy, unless it is subscribed to at least one event or supervises: those
  // are silent by design, and bounded by max_queued_bytes and the watchdog.
  // A forgotten terminal session frees its slot. Zero: no limit.
  std::chrono::milliseconds idle_timeout{60000};
  // Replies and events waiting for a client that does not read; beyond this
  // the client is dropped.
  std::size_t max_queued_bytes = 1024 * 1024;
  // A frame started but not finished within this long gets bad_frame and
  // the connection is closed (holds no slot forever).
  std::chrono::milliseconds partial_frame_timeout{5000};
  // Events published but not yet sent out by the server thread.
  std::size_t max_pending_events = 1024;
  std::string server_name = "hapticd";
  std::string telemetry_shm;  // reported by subscribe {"telemetry": true}
  std::function<void(std::string_view)> log;  // one line per notable event; may be empty
};

struct ServerStats {
  std::uint64_t clients_accepted = 0;
  std::uint64_t clients_refused = 0;   // over max_clients
  std::uint64_t clients_refused_per_peer = 0;  // over max_clients_per_peer
  std::uint64_t clients_hello_timed_out = 0;   // no valid request within hello_timeout
  std::uint64_t clients_idle_timed_out = 0;    // silent for idle_timeout, neither subscribed nor supervising
  std::uint64_t clients_dropped = 0;   // outgoing queue overflow
  std::uint64_t requests = 0;          // valid requests answered
  std::uint64_t rejections = 0;        // error replies for invalid input
  std::uint64_t events_dropped = 0;    // publish() while the pending queue was full
  std::uint64_t watchdog_expiries = 0;
};

class Server {
 public:
  Server(ServerConfig config, CommandHandler& handler);
  ~Server();  // stop()
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Creates the socket (parent directory, stale-file removal, mode, group)
  // and starts the thread. Throws std::runtime_error with a clear message
  // (path in use by a live server, not a socket, unknown group, …).
  void start();
  // Stops the thread, closes every connection, removes the socket file.
  // Does not call on_watchdog_expired. Idempotent.
  void stop();

  // Queues an event for every client subscribed to its name. Thread-safe,
  // from any non-realtime thread (also from inside CommandHandler::handle).
  // Throws std::invalid_argument for a name not in kEventNames or data that
  // does not fit one frame.
  void publish(const Event& event);

  ServerStats stats() const;
  const ServerConfig& config() const { return config_; }

 private:
  struct Impl;
  ServerConfig config_;
  CommandHandler& handler_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace knoblab::control
