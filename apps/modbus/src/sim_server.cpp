#include "knoblab/modbus/sim_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <modbus.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <optional>
#include <span>

#include "knoblab/modbus/mbap.hpp"
#include "sim_devices.hpp"

namespace knoblab::modbus {

using Clock = std::chrono::steady_clock;

namespace {

// The loop wakes at least this often: keeps 32 Hz ticks on time and stop() prompt.
constexpr long kSelectTimeoutUs = 2000;

modbus_t* as_ctx(void* p) { return static_cast<modbus_t*>(p); }

bool set_flags(int fd) {
  const int fl = fcntl(fd, F_GETFL);
  return fl != -1 && fcntl(fd, F_SETFL, fl | O_NONBLOCK) != -1 && fcntl(fd, F_SETFD, FD_CLOEXEC) != -1;
}

}  // namespace

struct SimServer::Client {
  int fd = -1;
  std::array<std::uint8_t, mbap::kMaxAduLength> buffer{};
  std::size_t length = 0;                // bytes of an unfinished frame
  Clock::time_point last_frame{};        // last complete request (or connect)
  Clock::time_point partial_since{};     // first byte of the unfinished frame
  bool closed = false;
  // A complete request to a slow unit waits here for its reply time; until
  // then nothing more is read from this client (answers stay in order).
  std::optional<Clock::time_point> answer_at;
};

SimServer::SimServer(SimConfig config) : config_(std::move(config)) {}

SimServer::~SimServer() { stop(); }

bool SimServer::start(std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = "modbus sim: " + why;
    if (listen_fd_ != -1) ::close(listen_fd_);
    listen_fd_ = -1;
    if (ctx_ != nullptr) modbus_free(as_ctx(ctx_));
    ctx_ = nullptr;
    return false;
  };
  if (thread_.joinable()) return fail("already started");
  in_addr probe{};
  if (inet_pton(AF_INET, config_.bind.c_str(), &probe) != 1)
    return fail("--bind needs an IPv4 address, got '" + config_.bind + "'");

  ctx_ = modbus_new_tcp(config_.bind.c_str(), config_.port);
  if (ctx_ == nullptr) return fail(std::string("modbus_new_tcp: ") + modbus_strerror(errno));
  // The context only builds replies; libmodbus sleeps one response timeout
  // on some malformed requests, so keep that at 1 ms (we pre-check anyway).
  modbus_set_response_timeout(as_ctx(ctx_), 0, 1000);
  listen_fd_ = modbus_tcp_listen(as_ctx(ctx_), 64);  // room for a burst of connects
  if (listen_fd_ == -1) {
    return fail("cannot listen on " + config_.bind + ":" + std::to_string(config_.port) + ": " +
                std::strerror(errno));
  }
  sockaddr_in bound{};
  socklen_t len = sizeof bound;
  if (!set_flags(listen_fd_) || getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&bound), &len) != 0)
    return fail(std::string("listening socket: ") + std::strerror(errno));
  port_ = ntohs(bound.sin_port);

  start_ = Clock::now();
  devices_ = std::make_unique<SimDevices>(config_, start_);
  schedule_done_.assign(config_.faults.size(), false);
  stop_ = false;
  running_ = true;
  thread_ = std::thread([this] { run(); });
  return true;
}

void SimServer::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (listen_fd_ != -1) ::close(listen_fd_);
  listen_fd_ = -1;
  if (ctx_ != nullptr) modbus_free(as_ctx(ctx_));
  ctx_ = nullptr;
}

void SimServer::run() {
  while (!stop_) {
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(listen_fd_, &readable);
    int max_fd = listen_fd_;
    for (const auto& c : clients_) {
      if (c->answer_at) continue;  // held for a slow reply
      FD_SET(c->fd, &readable);
      max_fd = std::max(max_fd, c->fd);
    }
    timeval tv{0, kSelectTimeoutUs};
    const int ready = select(max_fd + 1, &readable, nullptr, nullptr, &tv);
    if (ready < 0 && errno != EINTR) std::this_thread::sleep_for(std::chrono::milliseconds(1));  // never spin
    const auto now = Clock::now();

    std::lock_guard lock(mutex_);
    devices_->advance(now);
    apply_schedule(now);
    if (ready > 0) {
      for (auto& c : clients_) {
        if (!c->closed && !c->answer_at && FD_ISSET(c->fd, &readable)) serve_client(*c, now);
      }
    }
    for (auto& c : clients_) {
      if (!c->closed && c->answer_at && now >= *c->answer_at) answer_frames(*c, now);
    }
    if (auto refuse = devices_->take_drop_request()) {
      refuse_until_ = now + *refuse;
      drop_all();
    }
    for (auto& c : clients_) {
      const bool idle = now - c->last_frame > config_.idle_timeout;
      const bool stuck = c->length > 0 && now - c->partial_since > config_.partial_frame_timeout;
      if (!c->closed && !c->answer_at && (idle || stuck)) {  // a held request is the server's wait
        c->closed = true;
        ++counters_.dropped;
      }
    }
    std::erase_if(clients_, [](const std::unique_ptr<Client>& c) {
      if (c->closed) ::close(c->fd);
      return c->closed;
    });
    if (ready > 0 && FD_ISSET(listen_fd_, &readable)) accept_clients(now);
    counters_.clients = static_cast<int>(clients_.size());
    counters_.sample_counter = devices_->sample_counter();
    devices_->publish_counters(counters_);
    if (config_.duration.count() > 0 && now - start_ >= config_.duration) break;
  }
  std::lock_guard lock(mutex_);
  for (auto& c : clients_) ::close(c->fd);
  clients_.clear();
  counters_.clients = 0;
  running_ = false;
}

void SimServer::accept_clients(Clock::time_point now) {
  for (;;) {
    const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd == -1) return;  // EAGAIN: none left (or a transient error: next round)
    const bool refusing = now < refuse_until_;
    const bool full = static_cast<int>(clients_.size()) >= config_.max_clients;
    if (refusing || full || fd >= FD_SETSIZE) {  // select() cannot watch fds past FD_SETSIZE
      ::close(fd);
      ++counters_.dropped;
      continue;
    }
    const int one = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    auto c = std::make_unique<Client>();
    c->fd = fd;
    c->last_frame = now;
    clients_.push_back(std::move(c));
  }
}

void SimServer::serve_client(Client& c, Clock::time_point now) {
  const ssize_t got = recv(c.fd, c.buffer.data() + c.length, c.buffer.size() - c.length, 0);
  if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
  if (got <= 0) {  // orderly close or a socket error
    c.closed = true;
    return;
  }
  if (c.length == 0) c.partial_since = now;
  c.length += static_cast<std::size_t>(got);
  answer_frames(c, now);
}

void SimServer::answer_frames(Client& c, Clock::time_point now) {
  for (;;) {
    std::size_t frame_length = 0;
    const auto header = mbap::check_header({c.buffer.data(), c.length}, frame_length);
    if (header == mbap::Header::bad) {  // no way to find the next frame in a TCP stream
      ++counters_.bad_frames;
      ++counters_.dropped;
      c.closed = true;
      return;
    }
    if (header == mbap::Header::incomplete) return;
    if (!c.answer_at) {
      const auto delay = devices_->route(c.buffer[mbap::kHeaderLength - 1]).delay;
      if (delay.count() > 0) {
        c.answer_at = now + delay;
        return;
      }
    } else if (now < *c.answer_at) {
      return;
    }
    c.answer_at.reset();
    answer(c, c.buffer.data(), frame_length, now);
    if (c.closed) return;
    std::memmove(c.buffer.data(), c.buffer.data() + frame_length, c.length - frame_length);
    c.length -= frame_length;
    c.last_frame = now;
    c.partial_since = now;
  }
}

void SimServer::answer(Client& c, const std::uint8_t* frame, std::size_t length, Clock::time_point now) {
  ++counters_.requests;
  // modbus_reply() reads a few fixed offsets even of one-byte PDUs: give it
  // a full-size, zero-padded copy.
  std::array<std::uint8_t, mbap::kMaxAduLength> req{};
  std::memcpy(req.data(), frame, length);
  const int unit = req[mbap::kHeaderLength - 1];
  const std::span<const std::uint8_t> pdu(req.data() + mbap::kHeaderLength, length - mbap::kHeaderLength);

  modbus_t* ctx = as_ctx(ctx_);
  modbus_set_socket(ctx, c.fd);
  const SimDevices::Route route = devices_->route(unit);
  int exception = 0;
  if (route.mapping == nullptr) {
    exception = MODBUS_EXCEPTION_GATEWAY_TARGET;  // what a gateway says for an absent unit
  } else if (route.mute) {
    return;  // a hung device answers nothing
  } else if (route.exception != 0) {
    exception = route.exception;
  } else {
    switch (mbap::check_pdu(pdu)) {
      case mbap::Pdu::ok: break;
      case mbap::Pdu::unsupported_function: exception = MODBUS_EXCEPTION_ILLEGAL_FUNCTION; break;
      case mbap::Pdu::bad_length:
      case mbap::Pdu::bad_quantity: exception = MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE; break;
    }
  }
  int rc = 0;
  if (exception != 0) {
    ++counters_.exceptions;
    rc = modbus_reply_exception(ctx, req.data(), static_cast<unsigned>(exception));
  } else {
    rc = modbus_reply(ctx, req.data(), static_cast<int>(length), route.mapping);
    devices_->after_request(unit, now);
  }
  if (rc == -1) {  // peer gone or not reading (send buffer full): drop it
    c.closed = true;
    ++counters_.dropped;
  }
}

void SimServer::drop_all() {
  for (auto& c : clients_) {
    if (!c->closed) ++counters_.dropped;
    c->closed = true;
  }
}

void SimServer::apply_schedule(Clock::time_point now) {
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  for (std::size_t i = 0; i < config_.faults.size(); ++i) {
    const FaultAction& f = config_.faults[i];
    if (schedule_done_[i] || elapsed < f.at_seconds) continue;
    schedule_done_[i] = true;
    switch (f.kind) {
      case FaultAction::Kind::disconnect:
        refuse_until_ = now + f.refuse_for;
        drop_all();
        break;
      case FaultAction::Kind::exception:
        if (f.to_amplifier) devices_->control(simctl::kAmpException) = static_cast<std::uint16_t>(f.exception_code);
        if (f.to_biometrics) devices_->control(simctl::kBioException) = static_cast<std::uint16_t>(f.exception_code);
        break;
      case FaultAction::Kind::stale:
        devices_->control(simctl::kFreeze) |= static_cast<std::uint16_t>(
            (f.to_amplifier ? simctl::kFreezeAmplifier : 0) | (f.to_biometrics ? simctl::kFreezeBiometrics : 0));
        break;
      case FaultAction::Kind::amp_fault:
        devices_->control(simctl::kAmpFaultInject) |= f.fault_bits;
        break;
      case FaultAction::Kind::slow: {
        const auto ms = static_cast<std::uint16_t>(f.reply_delay.count());
        if (f.to_amplifier) devices_->control(simctl::kAmpReplyDelay) = ms;
        if (f.to_biometrics) devices_->control(simctl::kBioReplyDelay) = ms;
        break;
      }
      case FaultAction::Kind::hang:
        devices_->control(simctl::kMute) |= static_cast<std::uint16_t>(
            (f.to_amplifier ? simctl::kMuteAmplifier : 0) | (f.to_biometrics ? simctl::kMuteBiometrics : 0));
        break;
    }
    devices_->after_request(config_.control_unit, now);
  }
}

void SimServer::write_control(std::uint16_t reg, std::uint16_t value) {
  std::lock_guard lock(mutex_);
  if (!devices_) return;
  devices_->control(reg) = value;
  devices_->after_request(config_.control_unit, Clock::now());
}

void SimServer::set_exception(int unit, int code) {
  const auto v = static_cast<std::uint16_t>(code);
  if (unit == config_.amplifier_unit) write_control(simctl::kAmpException, v);
  if (unit == config_.biometrics_unit) write_control(simctl::kBioException, v);
}

void SimServer::set_freeze(std::uint16_t bits) { write_control(simctl::kFreeze, bits); }
void SimServer::set_amp_fault(std::uint16_t bits) { write_control(simctl::kAmpFaultInject, bits); }
void SimServer::set_mute(std::uint16_t bits) { write_control(simctl::kMute, bits); }
void SimServer::stimulus() { write_control(simctl::kStimulus, 1); }

void SimServer::set_reply_delay(int unit, std::chrono::milliseconds delay) {
  const auto ms = static_cast<std::uint16_t>(std::clamp<std::chrono::milliseconds::rep>(delay.count(), 0, 0xFFFF));
  if (unit == config_.amplifier_unit) write_control(simctl::kAmpReplyDelay, ms);
  if (unit == config_.biometrics_unit) write_control(simctl::kBioReplyDelay, ms);
}

void SimServer::set_map_version(int unit, std::uint16_t version) {
  if (unit == config_.amplifier_unit) write_control(simctl::kAmpMapVersion, version);
  if (unit == config_.biometrics_unit) write_control(simctl::kBioMapVersion, version);
}

void SimServer::drop_connections(std::chrono::milliseconds refuse_for) {
  const auto ms = std::clamp<std::chrono::milliseconds::rep>(refuse_for.count(), 1, 0xFFFF);
  write_control(simctl::kDropConnections, static_cast<std::uint16_t>(ms));
}

SimCounters SimServer::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

}  // namespace knoblab::modbus
