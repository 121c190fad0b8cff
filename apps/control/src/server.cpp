// Server's public face: lifecycle, publish() from any thread, statistics.
#include "knoblab/control/server.hpp"

#include <sys/eventfd.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>

#include "server_impl.hpp"

namespace knoblab::control {

Server::Impl::Impl(const ServerConfig& c, CommandHandler& h)
    : config(c), handler(h), wake(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  if (!wake) throw std::system_error(errno, std::generic_category(), "control server: eventfd");
}

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
    frame = make_frame(event_message(event));  // serialised here, off the server thread
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
  ServerStats s;
  s.clients_accepted = c.accepted.load();
  s.clients_refused = c.refused.load();
  s.clients_refused_per_peer = c.refused_per_peer.load();
  s.clients_hello_timed_out = c.hello_timeouts.load();
  s.clients_idle_timed_out = c.idle_timeouts.load();
  s.clients_dropped = c.dropped.load();
  s.requests = c.requests.load();
  s.rejections = c.rejections.load();
  s.events_dropped = c.events_dropped.load();
  s.watchdog_expiries = c.watchdog_expiries.load();
  return s;
}

}  // namespace knoblab::control
