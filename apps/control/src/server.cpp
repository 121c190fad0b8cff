// The server thread: accept, read frames, answer, broadcast events, and keep
// the watchdog — all on one poll() loop. Per-client memory is bounded by the
// frame limit (read side) and max_queued_bytes (write side).
#include "knoblab/control/server.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <vector>

#include "connection.hpp"
#include "knoblab/control/decode.hpp"
#include "knoblab/control/framing.hpp"
#include "listen_socket.hpp"
#include "watchdog.hpp"

namespace knoblab::control {

using detail::Connection;
using detail::Frame;
using nlohmann::json;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

namespace {

constexpr milliseconds kCloseGrace{1000};     // to flush a final error frame
constexpr milliseconds kAcceptBackoff{100};   // after EMFILE/ENFILE
constexpr int kReadsPerRound = 8;             // fairness between clients

Frame make_frame(const json& message) { return std::make_shared<const std::string>(encode_json_frame(message)); }

}  // namespace

struct Server::Impl {
  Impl(const ServerConfig& c, CommandHandler& h)
      : config(c), handler(h), wake(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
    if (!wake) throw std::system_error(errno, std::generic_category(), "control server: eventfd");
  }

  const ServerConfig& config;
  CommandHandler& handler;

  detail::ListeningSocket listener;
  detail::UniqueFd wake;  // eventfd: publish() and stop() wake the loop; lives as long as Impl
  std::thread thread;
  std::atomic<bool> stopping{false};
  bool running = false;

  std::vector<std::unique_ptr<Connection>> clients;
  ClientId next_id = 1;
  detail::Watchdog watchdog;
  Clock::time_point accept_paused_until{};

  std::mutex pending_mutex;
  std::deque<std::pair<std::size_t, Frame>> pending;  // (event index, frame)

  struct Counters {
    std::atomic<std::uint64_t> accepted{0}, refused{0}, dropped{0}, requests{0}, rejections{0},
        events_dropped{0}, watchdog_expiries{0};
  } counters;

  void log(const std::string& line) const {
    if (config.log) config.log(line);
  }

  // ---- the loop -------------------------------------------------------------

  void run() {
    std::vector<pollfd> fds;
    while (!stopping.load()) {
      const auto now = Clock::now();
      fds.clear();
      const bool accepting = now >= accept_paused_until;
      fds.push_back({accepting ? listener.fd.get() : -1, POLLIN, 0});
      fds.push_back({wake.get(), POLLIN, 0});
      for (const auto& c : clients) {
        short events = 0;
        if (!c->closing) events |= POLLIN;
        if (c->wants_write()) events |= POLLOUT;
        fds.push_back({c->fd(), events, 0});
      }
      const int rc = ::poll(fds.data(), fds.size(), poll_timeout_ms(now));
      if (rc < 0 && errno != EINTR) {
        log(std::string("poll failed: ") + std::strerror(errno));
        std::this_thread::sleep_for(milliseconds(10));
        continue;
      }
      if (rc > 0) {
        if (fds[1].revents & POLLIN) take_pending_events();
        // clients accepted below are not in fds yet; serve the ones polled
        const std::size_t polled = clients.size();
        for (std::size_t i = 0; i < polled; ++i) serve(*clients[i], fds[i + 2].revents);
        remove_dead();  // before accepting, so freed slots count
        if (fds[0].revents & POLLIN) accept_clients();
      }
      housekeeping(Clock::now());
    }
  }

  int poll_timeout_ms(Clock::time_point now) const {
    auto next = now + milliseconds(1000);
    if (now < accept_paused_until) next = std::min(next, accept_paused_until);
    if (const auto d = watchdog.deadline()) next = std::min(next, *d);
    for (const auto& c : clients) {
      if (c->closing) next = std::min(next, c->close_deadline);
      else if (c->partial_since) next = std::min(next, *c->partial_since + config.partial_frame_timeout);
    }
    if (next <= now) return 0;
    // round up so we never wake just before a deadline and spin
    const auto ms = std::chrono::ceil<milliseconds>(next - now).count();
    return static_cast<int>(ms);
  }

  void housekeeping(Clock::time_point now) {
    for (auto& c : clients) {
      if (c->dead) continue;
      if (c->closing) {
        if (!c->wants_write() || now >= c->close_deadline) c->dead = true;
      } else if (c->partial_since && now - *c->partial_since >= config.partial_frame_timeout) {
        const auto waited = std::chrono::duration_cast<milliseconds>(config.partial_frame_timeout).count();
        send_final(*c, Rejection{std::nullopt, {ErrorCode::bad_frame,
                                                "frame incomplete after " + std::to_string(waited) + " ms", {}}});
      }
    }
    remove_dead();
    if (watchdog.expired(now)) watchdog_fired(WatchdogReason::silence);
  }

  // ---- connections ------------------------------------------------------------

  void accept_clients() {
    for (;;) {
      detail::UniqueFd fd(::accept4(listener.fd.get(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
      if (!fd) {
        if (errno == EINTR || errno == ECONNABORTED) continue;
        if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
          log(std::string("accept: ") + std::strerror(errno) + "; pausing");
          accept_paused_until = Clock::now() + kAcceptBackoff;
        }
        return;
      }
      if (clients.size() >= config.max_clients) {
        // Tell the client why, best effort, without waiting for it.
        const auto frame = encode_json_frame(reply_message(
            std::nullopt, Reply::failure(ErrorCode::busy, "too many clients (limit " +
                                                              std::to_string(config.max_clients) + ")")));
        [[maybe_unused]] const auto n = ::send(fd.get(), frame.data(), frame.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
        ++counters.refused;
        log("refused a client: " + std::to_string(clients.size()) + " connected (limit " +
            std::to_string(config.max_clients) + ")");
        continue;
      }
      clients.push_back(std::make_unique<Connection>(std::move(fd), next_id++, config.max_queued_bytes));
      ++counters.accepted;
    }
  }

  void serve(Connection& c, short revents) {
    if (c.dead) return;
    if (revents & POLLOUT) {
      if (!c.flush()) c.dead = true;
      if (c.closing && !c.wants_write()) c.dead = true;  // final words delivered
      if (c.dead) return;
    }
    if (c.closing && (revents & (POLLHUP | POLLERR))) {  // nobody left to read the final words
      c.dead = true;
      return;
    }
    if (!(revents & (POLLIN | POLLHUP | POLLERR)) || c.closing) return;
    for (int round = 0; round < kReadsPerRound && !c.closing && !c.dead; ++round) {
      const auto status = c.read_some();
      if (status == Connection::ReadStatus::error) {
        c.dead = true;
        return;
      }
      const bool completed = take_frames(c);
      const auto now = Clock::now();
      if (c.decoder().buffered() == 0) c.partial_since.reset();
      else if (completed || !c.partial_since) c.partial_since = now;
      if (status == Connection::ReadStatus::eof) {
        // The peer stopped sending; answer what it sent, then close.
        begin_close(c);
        return;
      }
      if (status == Connection::ReadStatus::would_block) break;
    }
    if (!c.dead && c.wants_write() && !c.flush()) c.dead = true;
  }

  // Answers every complete frame in c's buffer. True if any was complete.
  bool take_frames(Connection& c) {
    bool any = false;
    std::string_view payload;
    for (;;) {
      if (c.closing || c.dead) return any;
      switch (c.decoder().next(payload)) {
        case FrameDecoder::Status::NeedMore: return any;
        case FrameDecoder::Status::Oversized:
          send_final(c, Rejection{std::nullopt,
                                  {ErrorCode::oversized,
                                   "frame of " + std::to_string(c.decoder().announced_length()) +
                                       " bytes exceeds the " + std::to_string(kMaxFramePayload) +
                                       " byte limit; closing (the stream cannot be resynchronised)",
                                   {}}});
          return any;
        case FrameDecoder::Status::Frame:
          any = true;
          answer(c, payload);
          break;
      }
    }
  }

  void answer(Connection& c, std::string_view payload) {
    auto decoded = decode_request(payload);
    if (auto* rejection = std::get_if<Rejection>(&decoded)) {
      ++counters.rejections;
      send(c, rejection->id,
           Reply::failure(rejection->error.code, std::move(rejection->error.message), std::move(rejection->error.key)));
      return;
    }
    auto& request = std::get<Request>(decoded);
    request.client = c.id();
    ++counters.requests;
    watchdog.feed(c.id(), Clock::now());
    send(c, request.id, dispatch(c, request));
  }

  Reply dispatch(Connection& c, const Request& r) {
    switch (r.command) {
      case Command::hello: return hello(c, r);
      case Command::ping: return Reply::success();
      case Command::subscribe: return subscribe(c, r);
      default: break;
    }
    try {
      Reply reply = handler.handle(r);
      if (reply.ok && !reply.result.is_object())
        return Reply::failure(ErrorCode::internal, "handler returned a non-object result");
      return reply;
    } catch (const std::exception& e) {
      log(std::string("handler failed on ") + std::string(to_string(r.command)) + ": " + e.what());
      return Reply::failure(ErrorCode::internal, std::string("handler failed: ") + e.what());
    } catch (...) {
      return Reply::failure(ErrorCode::internal, "handler failed");
    }
  }

  Reply hello(Connection& c, const Request& r) {
    const auto& versions = r.args.at("versions");
    if (std::find(versions.begin(), versions.end(), json(kProtocolVersion)) == versions.end())
      return Reply::failure(ErrorCode::unsupported_version,
                            "no common version: client speaks " + versions.dump() + ", server speaks [1]");
    json result = {{"version", kProtocolVersion},
                   {"server", config.server_name},
                   {"max_frame_bytes", kMaxFramePayload},
                   {"client_id", c.id()}};
    if (const auto wd = r.args.find("watchdog_ms"); wd != r.args.end()) {
      const milliseconds period(wd->get<std::int64_t>());
      if (!watchdog.arm(c.id(), period, Clock::now()))
        return Reply::failure(ErrorCode::busy, "another client (id " + std::to_string(*watchdog.supervisor()) +
                                                   ") already supervises the device");
      result["watchdog_ms"] = period.count();
    } else {
      watchdog.release(c.id());
    }
    result["supervising"] = watchdog.supervised_by(c.id());
    return Reply::success(std::move(result));
  }

  Reply subscribe(Connection& c, const Request& r) {
    c.subscriptions.reset();
    for (const auto& e : r.args.at("events")) {
      const auto& name = e.get_ref<const std::string&>();
      if (name == "*") c.subscriptions.set();
      else c.subscriptions.set(*event_index(name));
    }
    json names = json::array();
    for (std::size_t i = 0; i < kEventNames.size(); ++i)
      if (c.subscriptions.test(i)) names.push_back(kEventNames[i]);
    json result = {{"events", std::move(names)}};
    if (r.args.value("telemetry", false)) result["telemetry_shm"] = config.telemetry_shm;
    return Reply::success(std::move(result));
  }

  void send(Connection& c, std::optional<std::int64_t> id, const Reply& reply) {
    Frame frame;
    try {
      frame = make_frame(reply_message(id, reply));
    } catch (const std::length_error&) {
      frame = make_frame(reply_message(id, Reply::failure(ErrorCode::internal, "reply does not fit one frame")));
    }
    enqueue(c, std::move(frame));
  }

  void enqueue(Connection& c, Frame frame) {
    if (c.dead) return;
    if (!c.enqueue(std::move(frame))) {
      log("client " + std::to_string(c.id()) + " does not read its replies/events; dropping it");
      ++counters.dropped;
      c.dead = true;
    }
  }

  void send_final(Connection& c, const Rejection& r) {
    ++counters.rejections;
    send(c, r.id, Reply::failure(r.error.code, r.error.message));
    begin_close(c);
  }

  void begin_close(Connection& c) {
    if (c.closing) return;
    c.closing = true;
    c.close_deadline = Clock::now() + kCloseGrace;
    c.partial_since.reset();
    ::shutdown(c.fd(), SHUT_RD);
    if (!c.flush() || !c.wants_write()) c.dead = true;  // else close once POLLOUT drains it
  }

  void remove_dead() {
    for (auto it = clients.begin(); it != clients.end();) {
      if (!(*it)->dead) {
        ++it;
        continue;
      }
      const ClientId id = (*it)->id();
      it = clients.erase(it);  // closes the socket
      if (watchdog.disconnected(id)) watchdog_fired(WatchdogReason::disconnect);
    }
  }

  void watchdog_fired(WatchdogReason reason) {
    ++counters.watchdog_expiries;
    const char* why = reason == WatchdogReason::silence ? "silence" : "disconnect";
    log(std::string("watchdog expired (") + why + ")");
    try {
      handler.on_watchdog_expired(reason);
    } catch (const std::exception& e) {
      log(std::string("on_watchdog_expired failed: ") + e.what());
    } catch (...) {
      log("on_watchdog_expired failed");
    }
    const auto index = *event_index("watchdog_expired");
    broadcast(index, make_frame(event_message(
                         {"watchdog_expired", {{"reason", why}, {"watchdog_ms", watchdog.period().count()}}})));
  }

  // ---- events -----------------------------------------------------------------

  void take_pending_events() {
    std::uint64_t n;
    [[maybe_unused]] const auto r = ::read(wake.get(), &n, sizeof n);
    std::deque<std::pair<std::size_t, Frame>> batch;
    {
      std::lock_guard lock(pending_mutex);
      batch.swap(pending);
    }
    for (auto& [index, frame] : batch) broadcast(index, frame);
  }

  void broadcast(std::size_t index, const Frame& frame) {
    for (auto& c : clients)
      if (!c->dead && !c->closing && c->subscriptions.test(index)) {
        enqueue(*c, frame);
        if (!c->dead && !c->flush()) c->dead = true;
      }
  }

  void wake_loop() {
    const std::uint64_t one = 1;
    [[maybe_unused]] const auto r = ::write(wake.get(), &one, sizeof one);
  }
};

Server::Server(ServerConfig config, CommandHandler& handler)
    : config_(std::move(config)), handler_(handler), impl_(std::make_unique<Impl>(config_, handler_)) {}

Server::~Server() { stop(); }

void Server::start() {
  if (impl_->running) throw std::logic_error("control server already running");
  impl_->listener = detail::open_listening_socket(config_.socket_path, config_.socket_group);
  impl_->stopping = false;
  impl_->thread = std::thread([this] { impl_->run(); });
  impl_->running = true;
  impl_->log("listening on " + config_.socket_path);
}

void Server::stop() {
  if (!impl_->running) return;
  impl_->stopping = true;
  impl_->wake_loop();
  impl_->thread.join();
  impl_->clients.clear();
  impl_->watchdog = {};  // a restart starts unsupervised
  detail::remove_socket_file(config_.socket_path, impl_->listener.dev, impl_->listener.ino);
  impl_->listener = {};
  impl_->running = false;
}

void Server::publish(const Event& event) {
  const auto index = event_index(event.name);
  if (!index) throw std::invalid_argument("publish: '" + event.name + "' is not a protocol v1 event");
  Frame frame;
  try {
    frame = make_frame(event_message(event));
  } catch (const std::length_error&) {
    throw std::invalid_argument("publish: event '" + event.name + "' does not fit one frame");
  }
  {
    std::lock_guard lock(impl_->pending_mutex);
    if (impl_->pending.size() >= config_.max_pending_events) {
      impl_->pending.pop_front();
      ++impl_->counters.events_dropped;
    }
    impl_->pending.emplace_back(*index, std::move(frame));
  }
  impl_->wake_loop();
}

ServerStats Server::stats() const {
  const auto& c = impl_->counters;
  return {c.accepted.load(), c.refused.load(), c.dropped.load(), c.requests.load(),
          c.rejections.load(), c.events_dropped.load(), c.watchdog_expiries.load()};
}

}  // namespace knoblab::control
