// The server's state and its thread's steps, shared by server.cpp (public
// API), server_loop.cpp (sockets, frames, queues) and server_requests.cpp
// (what each valid request gets).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <sys/types.h>
#include <utility>
#include <vector>

#include "connection.hpp"
#include "knoblab/control/framing.hpp"
#include "knoblab/control/server.hpp"
#include "listen_socket.hpp"
#include "watchdog.hpp"

namespace knoblab::control {

using detail::Connection;
using detail::Frame;

inline Frame make_frame(const nlohmann::json& message) {
  return std::make_shared<const std::string>(encode_json_frame(message));
}

struct Server::Impl {
  using Clock = std::chrono::steady_clock;

  Impl(const ServerConfig& c, CommandHandler& h);

  const ServerConfig& config;
  CommandHandler& handler;

  detail::ListeningSocket listener;
  detail::UniqueFd wake;  // eventfd: publish() and stop() wake the loop; lives as long as Impl
  std::thread thread;
  std::atomic<bool> stopping{false};
  bool running = false;

  // Touched only by the server thread (or by stop() after joining it).
  std::vector<std::unique_ptr<Connection>> clients;
  ClientId next_id = 1;
  detail::Watchdog watchdog;
  Clock::time_point accept_paused_until{};

  std::mutex pending_mutex;
  std::deque<std::pair<std::size_t, Frame>> pending;  // published events: (event index, frame)

  struct Counters {
    std::atomic<std::uint64_t> accepted{0}, refused{0}, refused_per_peer{0}, hello_timeouts{0}, idle_timeouts{0},
        dropped{0}, requests{0}, rejections{0}, events_dropped{0}, watchdog_expiries{0};
  } counters;

  void log(const std::string& line) const {
    if (config.log) config.log(line);
  }

  // server_loop.cpp
  void run();
  int poll_timeout_ms(Clock::time_point now) const;
  void housekeeping(Clock::time_point now);
  void accept_clients();
  void serve(Connection& c, short revents);
  bool take_frames(Connection& c);
  void send(Connection& c, std::optional<std::int64_t> id, const Reply& reply);
  void enqueue(Connection& c, Frame frame);
  void send_final(Connection& c, const Rejection& r);
  void begin_close(Connection& c);
  void remove_dead();
  void take_pending_events();
  void broadcast(std::size_t index, const Frame& frame);
  void wake_loop();

  // server_life.cpp
  // Why a new connection from `peer` may not stay (a busy message), or nullopt.
  std::optional<std::string> refusal(std::optional<pid_t> peer);
  // When c must have sent its next valid request, or nullopt if it may stay silent.
  std::optional<Clock::time_point> silence_deadline(const Connection& c) const;
  void close_if_silent(Connection& c, Clock::time_point now);

  // server_requests.cpp
  void answer(Connection& c, std::string_view payload);
  Reply dispatch(Connection& c, const Request& r);
  Reply hello(Connection& c, const Request& r);
  Reply subscribe(Connection& c, const Request& r);
  void watchdog_fired(WatchdogReason reason);
};

}  // namespace knoblab::control
