#include "knoblab/control/client.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace knoblab::control {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

std::string describe(const Error& e) {
  return std::string(to_string(e.code)) + ": " + e.message;
}

int remaining_ms(Clock::time_point deadline) {
  const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left <= 0 ? 0 : static_cast<int>(std::min<long long>(left, 60'000));
}

}  // namespace

RemoteError::RemoteError(Error error) : std::runtime_error(describe(error)), error_(std::move(error)) {}

Client::Client(const std::string& socket_path, Duration timeout) : timeout_(timeout) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (socket_path.empty() || socket_path.size() >= sizeof addr.sun_path)
    throw ClientError("control socket path '" + socket_path + "' is empty or too long");
  std::memcpy(addr.sun_path, socket_path.c_str(), socket_path.size() + 1);
  fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw ClientError(std::string("socket(): ") + std::strerror(errno));
  // A Unix-socket connect does not block for long; the server accepts from its loop.
  if (::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    close();
    throw ClientError("cannot connect to " + socket_path + ": " + std::strerror(err));
  }
}

Client::~Client() { close(); }

Client::Client(Client&& o) noexcept
    : fd_(std::exchange(o.fd_, -1)),
      timeout_(o.timeout_),
      next_id_(o.next_id_),
      decoder_(std::move(o.decoder_)),
      events_(std::move(o.events_)),
      events_dropped_(o.events_dropped_) {}

Client& Client::operator=(Client&& o) noexcept {
  if (this != &o) {
    close();
    fd_ = std::exchange(o.fd_, -1);
    timeout_ = o.timeout_;
    next_id_ = o.next_id_;
    decoder_ = std::move(o.decoder_);
    events_ = std::move(o.events_);
    events_dropped_ = o.events_dropped_;
  }
  return *this;
}

void Client::close() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

json Client::hello(const HelloOptions& options) {
  json args = {{"versions", options.versions}};
  if (!options.client_name.empty()) args["client"] = options.client_name;
  if (options.watchdog_ms) args["watchdog_ms"] = *options.watchdog_ms;
  return call("hello", std::move(args));
}

Reply Client::request(std::string_view cmd, json args) { return request(cmd, std::move(args), timeout_); }

Reply Client::request(std::string_view cmd, json args, Duration timeout) {
  if (fd_ < 0) throw ClientError("not connected");
  const auto deadline = Clock::now() + timeout;
  const std::int64_t id = next_id_++;
  std::string frame;
  try {
    frame = encode_json_frame(request_message(id, cmd, std::move(args)));
  } catch (const std::length_error& e) {
    throw ClientError(std::string("request does not fit one frame: ") + e.what());
  }
  if (const int err = send_all(frame, deadline); err != 0) {
    // The server may have closed after saying why (busy: too many clients,
    // a silent connection closed); that reply says more than the errno.
    auto reason = parting_reply();
    close();
    if (reason) return std::move(*reason);
    throw ClientError(std::string("connection lost while sending: ") + std::strerror(err));
  }
  for (;;) {
    auto message = receive(deadline);
    if (!message)
      throw ClientError("no reply to '" + std::string(cmd) + "' (id " + std::to_string(id) + ") within " +
                        std::to_string(timeout.count()) + " ms");
    if (auto* event = std::get_if<Event>(&*message)) {
      keep_event(std::move(*event));
      continue;
    }
    auto& reply = std::get<ReplyMessage>(*message);
    // A null id answers the frame the server could not read — ours, since
    // requests go one at a time. Other ids are late replies to timed-out requests.
    if (!reply.id || *reply.id == id) return std::move(reply.reply);
  }
}

json Client::call(std::string_view cmd, json args) {
  Reply reply = request(cmd, std::move(args));
  if (!reply.ok) throw RemoteError(std::move(reply.error));
  return std::move(reply.result);
}

std::optional<Event> Client::wait_event(Duration timeout) {
  if (!events_.empty()) {
    Event e = std::move(events_.front());
    events_.pop_front();
    return e;
  }
  if (fd_ < 0) throw ClientError("not connected");
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    auto message = receive(deadline);
    if (!message) return std::nullopt;
    if (auto* event = std::get_if<Event>(&*message)) return std::move(*event);
    // replies to timed-out requests: nothing waits for them any more
  }
}

void Client::keep_event(Event event) {
  if (events_.size() >= kMaxQueuedEvents) {
    events_.pop_front();
    ++events_dropped_;
  }
  events_.push_back(std::move(event));
}

int Client::send_all(const std::string& bytes, Deadline deadline) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      sent += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{fd_, POLLOUT, 0};
      if (::poll(&p, 1, remaining_ms(deadline)) == 0) throw ClientError("timed out sending a request");
      continue;
    }
    return n < 0 && errno != 0 ? errno : EPIPE;
  }
  return 0;
}

std::optional<Reply> Client::parting_reply() {
  try {
    for (;;) {
      auto message = receive(Clock::now());  // what has arrived already; no waiting
      if (!message) return std::nullopt;
      if (auto* event = std::get_if<Event>(&*message)) {
        keep_event(std::move(*event));
        continue;
      }
      auto& reply = std::get<ReplyMessage>(*message);
      if (!reply.id) return std::move(reply.reply);
    }
  } catch (const ClientError&) {
    return std::nullopt;  // the connection ended without a reason
  }
}

std::optional<ServerMessage> Client::receive(Deadline deadline) {
  for (;;) {
    std::string_view payload;
    switch (decoder_.next(payload)) {
      case FrameDecoder::Status::Frame: {
        json m = json::parse(payload, nullptr, false);
        if (m.is_discarded()) {
          close();
          throw ClientError("server sent a frame that is not JSON");
        }
        try {
          return parse_server_message(m);
        } catch (const std::runtime_error& e) {
          close();
          throw ClientError(e.what());
        }
      }
      case FrameDecoder::Status::Oversized:
        close();
        throw ClientError("server sent an oversized frame");
      case FrameDecoder::Status::NeedMore: break;
    }
    pollfd p{fd_, POLLIN, 0};
    const int rc = ::poll(&p, 1, remaining_ms(deadline));
    if (rc < 0 && errno == EINTR) continue;
    if (rc == 0) return std::nullopt;
    const auto area = decoder_.write_area();
    const ssize_t n = ::read(fd_, area.data(), area.size());
    if (n > 0) {
      decoder_.commit(static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    const std::string why = n == 0 ? "closed by the server" : std::strerror(errno);
    close();
    throw ClientError("connection lost: " + why);
  }
}

}  // namespace knoblab::control
