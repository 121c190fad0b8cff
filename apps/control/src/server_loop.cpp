// The server thread: accept, read frames, queue replies, broadcast events,
// time out what must not linger — all on one poll() loop. Per-client memory
// is bounded by the frame limit (read side) and max_queued_bytes (write side).
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "server_impl.hpp"

namespace knoblab::control {

using std::chrono::milliseconds;

namespace {

constexpr milliseconds kCloseGrace{1000};    // to flush a final error frame
constexpr milliseconds kAcceptBackoff{100};  // after EMFILE/ENFILE
constexpr int kReadsPerRound = 8;            // fairness between clients

}  // namespace

void Server::Impl::run() {
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

int Server::Impl::poll_timeout_ms(Clock::time_point now) const {
  auto next = now + milliseconds(1000);
  if (now < accept_paused_until) next = std::min(next, accept_paused_until);
  if (const auto d = watchdog.deadline()) next = std::min(next, *d);
  for (const auto& c : clients) {
    if (c->closing) {
      next = std::min(next, c->close_deadline);
      continue;
    }
    if (c->partial_since) next = std::min(next, *c->partial_since + config.partial_frame_timeout);
    if (const auto d = silence_deadline(*c)) next = std::min(next, *d);
  }
  if (next <= now) return 0;
  // round up so we never wake just before a deadline and spin
  const auto ms = std::chrono::ceil<milliseconds>(next - now).count();
  return static_cast<int>(ms);
}

void Server::Impl::housekeeping(Clock::time_point now) {
  for (auto& c : clients) {
    if (c->dead) continue;
    if (c->closing) {
      if (!c->wants_write() || now >= c->close_deadline) c->dead = true;
    } else if (c->partial_since && now - *c->partial_since >= config.partial_frame_timeout) {
      const auto waited = std::chrono::duration_cast<milliseconds>(config.partial_frame_timeout).count();
      send_final(*c, Rejection{std::nullopt, {ErrorCode::bad_frame,
                                              "frame incomplete after " + std::to_string(waited) + " ms", {}}});
    } else {
      close_if_silent(*c, now);
    }
  }
  remove_dead();
  if (watchdog.expired(now)) watchdog_fired(WatchdogReason::silence);
}

// One connection per round: a peer's connections that already hung up are
// served and reaped (next round's poll reports them) before its next one is
// counted against the limits, so a process that closes and reconnects
// quickly is not refused for connections it no longer has.
void Server::Impl::accept_clients() {
  detail::UniqueFd fd(::accept4(listener.fd.get(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
  if (!fd) {
    if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
      log(std::string("accept: ") + std::strerror(errno) + "; pausing");
      accept_paused_until = Clock::now() + kAcceptBackoff;
    }
    return;  // EAGAIN, EINTR, ECONNABORTED: the next round tries again if one is waiting
  }
  const auto peer = detail::peer_process(fd.get());
  if (const auto why = refusal(peer)) {
    // Tell the client why, best effort, without waiting for it.
    const auto frame = encode_json_frame(reply_message(std::nullopt, Reply::failure(ErrorCode::busy, *why)));
    [[maybe_unused]] const auto n = ::send(fd.get(), frame.data(), frame.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    return;
  }
  clients.push_back(std::make_unique<Connection>(std::move(fd), next_id++, config.max_queued_bytes, Clock::now(), peer));
  ++counters.accepted;
}

void Server::Impl::serve(Connection& c, short revents) {
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
bool Server::Impl::take_frames(Connection& c) {
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

void Server::Impl::send(Connection& c, std::optional<std::int64_t> id, const Reply& reply) {
  Frame frame;
  try {
    frame = make_frame(reply_message(id, reply));
  } catch (const std::length_error&) {
    frame = make_frame(reply_message(id, Reply::failure(ErrorCode::internal, "reply does not fit one frame")));
  }
  enqueue(c, std::move(frame));
}

void Server::Impl::enqueue(Connection& c, Frame frame) {
  if (c.dead) return;
  if (!c.enqueue(std::move(frame))) {
    log("client " + std::to_string(c.id()) + " does not read its replies/events; dropping it");
    ++counters.dropped;
    c.dead = true;
  }
}

void Server::Impl::send_final(Connection& c, const Rejection& r) {
  ++counters.rejections;
  send(c, r.id, Reply::failure(r.error.code, r.error.message));
  begin_close(c);
}

void Server::Impl::begin_close(Connection& c) {
  if (c.closing) return;
  c.closing = true;
  c.close_deadline = Clock::now() + kCloseGrace;
  c.partial_since.reset();
  ::shutdown(c.fd(), SHUT_RD);
  if (!c.flush() || !c.wants_write()) c.dead = true;  // else close once POLLOUT drains it
}

void Server::Impl::remove_dead() {
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

void Server::Impl::take_pending_events() {
  std::uint64_t n;
  [[maybe_unused]] const auto r = ::read(wake.get(), &n, sizeof n);
  std::deque<std::pair<std::size_t, Frame>> batch;
  {
    std::lock_guard lock(pending_mutex);
    batch.swap(pending);
  }
  for (auto& [index, frame] : batch) broadcast(index, frame);
}

void Server::Impl::broadcast(std::size_t index, const Frame& frame) {
  for (auto& c : clients)
    if (!c->dead && !c->closing && c->subscriptions.test(index)) {
      enqueue(*c, frame);
      if (!c->dead && !c->flush()) c->dead = true;
    }
}

void Server::Impl::wake_loop() {
  const std::uint64_t one = 1;
  [[maybe_unused]] const auto r = ::write(wake.get(), &one, sizeof one);
}

}  // namespace knoblab::control
