// Who may hold a client slot, and for how long: the client limits checked
// when a connection arrives, and the silence rules after. Slots are few
// (max_clients), so a connection that says nothing, or one process that
// opens many, must not keep the UI or a lab user's CLI out.
#include <algorithm>
#include <string>

#include "server_impl.hpp"

namespace knoblab::control {

using std::chrono::milliseconds;

namespace {

std::string ms_text(milliseconds ms) { return std::to_string(ms.count()) + " ms"; }

}  // namespace

std::optional<std::string> Server::Impl::refusal(std::optional<pid_t> peer) {
  if (clients.size() >= config.max_clients) {
    ++counters.refused;
    log("refused a client: " + std::to_string(clients.size()) + " connected (limit " +
        std::to_string(config.max_clients) + ")");
    return "too many clients (limit " + std::to_string(config.max_clients) + ")";
  }
  if (!peer || config.max_clients_per_peer == 0) return std::nullopt;
  const auto held = static_cast<std::size_t>(
      std::count_if(clients.begin(), clients.end(), [&](const auto& c) { return c->peer_pid == peer; }));
  if (held < config.max_clients_per_peer) return std::nullopt;
  ++counters.refused_per_peer;
  const std::string limit = std::to_string(config.max_clients_per_peer);
  log("refused a client: pid " + std::to_string(*peer) + " already holds " + std::to_string(held) +
      " connections (limit " + limit + " per process)");
  return "too many connections from this process (pid " + std::to_string(*peer) + " holds " + std::to_string(held) +
         "; limit " + limit + " per process)";
}

std::optional<Server::Impl::Clock::time_point> Server::Impl::silence_deadline(const Connection& c) const {
  if (!c.last_request) {
    if (config.hello_timeout <= milliseconds::zero()) return std::nullopt;
    return c.accepted_at + config.hello_timeout;
  }
  // Subscribers wait for events and the supervisor's silence is the
  // watchdog's business: both are silent by design.
  if (config.idle_timeout <= milliseconds::zero() || c.subscriptions.any() || watchdog.supervised_by(c.id()))
    return std::nullopt;
  return *c.last_request + config.idle_timeout;
}

void Server::Impl::close_if_silent(Connection& c, Clock::time_point now) {
  const auto deadline = silence_deadline(c);
  if (!deadline || now < *deadline) return;
  std::string why;
  if (!c.last_request) {
    ++counters.hello_timeouts;
    why = "no request within " + ms_text(config.hello_timeout) + " of connecting (send hello first); closing";
  } else {
    ++counters.idle_timeouts;
    why = "idle for " + ms_text(config.idle_timeout) +
          " (no request; neither subscribed to events nor supervising); closing";
  }
  log("client " + std::to_string(c.id()) + ": " + why);
  send(c, std::nullopt, Reply::failure(ErrorCode::busy, why));
  begin_close(c);
}

}  // namespace knoblab::control
