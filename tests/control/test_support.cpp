#include "test_support.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>

#include "knoblab/control/client.hpp"
#include "knoblab/control/decode.hpp"
#include "knoblab/control/framing.hpp"

namespace knoblab::control::test {

TempDir::TempDir() {
  char tmpl[] = "/tmp/knoblab-control-XXXXXX";
  if (!::mkdtemp(tmpl)) throw std::runtime_error("mkdtemp failed");
  path_ = tmpl;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

// ---- RecordingHandler ---------------------------------------------------------

Reply RecordingHandler::handle(const Request& request) {
  // Independent re-check: the request must survive the wire format again,
  // and must not be one the server answers itself.
  const auto again = decode_request(request_message(request.id, to_string(request.command), request.args).dump());
  const auto* r = std::get_if<Request>(&again);
  if (!r || r->command != request.command || r->args != request.args || handled_by_server(request.command) ||
      !request.args.is_object())
    ++invalid_;
  {
    std::lock_guard lock(mutex_);
    requests_.push_back(request);
  }
  if (respond) return respond(request);
  return Reply::success({{"echo", to_string(request.command)}});
}

void RecordingHandler::on_watchdog_expired(WatchdogReason reason) {
  std::lock_guard lock(mutex_);
  expiries_.push_back(reason);
  cv_.notify_all();
}

std::vector<Request> RecordingHandler::requests() const {
  std::lock_guard lock(mutex_);
  return requests_;
}

std::size_t RecordingHandler::request_count() const {
  std::lock_guard lock(mutex_);
  return requests_.size();
}

std::vector<WatchdogReason> RecordingHandler::expiries() const {
  std::lock_guard lock(mutex_);
  return expiries_;
}

bool RecordingHandler::wait_for_expiries(std::size_t n, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  return cv_.wait_for(lock, timeout, [&] { return expiries_.size() >= n; });
}

// ---- RawConnection ------------------------------------------------------------

RawConnection::RawConnection(const std::string& path) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
  fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0 || ::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
    throw std::runtime_error("RawConnection: cannot connect to " + path + ": " + std::strerror(errno));
}

RawConnection::~RawConnection() { close(); }

void RawConnection::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool RawConnection::send_bytes(std::string_view bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

bool RawConnection::send_json(const json& message) { return send_bytes(encode_json_frame(message)); }

void RawConnection::shutdown_write() { ::shutdown(fd_, SHUT_WR); }

std::optional<json> RawConnection::read_message(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    if (buffer_.size() >= 4) {
      const auto* h = reinterpret_cast<const unsigned char*>(buffer_.data());
      const std::size_t n = (std::size_t{h[0]} << 24) | (std::size_t{h[1]} << 16) | (std::size_t{h[2]} << 8) | h[3];
      if (n > kMaxFramePayload) {
        ADD_FAILURE() << "server sent a frame header of " << n << " bytes";
        closed_ = true;
        return std::nullopt;
      }
      if (buffer_.size() >= 4 + n) {
        json m = json::parse(buffer_.substr(4, n), nullptr, false);
        buffer_.erase(0, 4 + n);
        if (m.is_discarded()) ADD_FAILURE() << "server sent a frame that is not JSON";
        return m;
      }
    }
    if (closed_) return std::nullopt;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return std::nullopt;
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    char chunk[65536];
    const ssize_t n = ::read(fd_, chunk, sizeof chunk);
    if (n > 0) buffer_.append(chunk, static_cast<std::size_t>(n));
    else if (n == 0 || (errno != EINTR && errno != EAGAIN)) closed_ = true;  // EOF or ECONNRESET
  }
}

std::vector<json> RawConnection::read_until_closed(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::vector<json> out;
  while (!closed_) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    if (auto m = read_message(left)) out.push_back(std::move(*m));
  }
  while (auto m = read_message(0ms)) out.push_back(std::move(*m));  // frames buffered before EOF
  return out;
}

// ---- frames -------------------------------------------------------------------

std::string request_frame(std::int64_t id, std::string_view cmd, const json& args) {
  return encode_json_frame(request_message(id, cmd, args));
}

std::string header_only(std::uint32_t n) {
  return {static_cast<char>(n >> 24), static_cast<char>((n >> 16) & 0xFF), static_cast<char>((n >> 8) & 0xFF),
          static_cast<char>(n & 0xFF)};
}

std::string raw_frame(std::string_view payload) {
  return header_only(static_cast<std::uint32_t>(payload.size())) + std::string(payload);
}

std::string outcome(const json& reply) {
  if (reply.value("ok", false)) return "ok";
  if (reply.contains("error") && reply["error"].contains("code")) return reply["error"]["code"].get<std::string>();
  return "?";
}

bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

// ---- ServerTest ---------------------------------------------------------------

void ServerTest::SetUp() {
  config.socket_path = dir.path() + "/run/hapticd.sock";
  config.telemetry_shm = "/knoblab-telemetry-test";
  configure(config);
  server = std::make_unique<Server>(config, handler);
  server->start();
}

void ServerTest::TearDown() {
  if (server) server->stop();
  EXPECT_EQ(handler.invalid_requests(), 0u) << "the handler was called with an invalid request";
}

void ServerTest::expect_server_answers() {
  Client c(config.socket_path, 2s);
  const Reply r = c.request("ping");
  EXPECT_TRUE(r.ok) << "server stopped answering a well-behaved client";
}

}  // namespace knoblab::control::test
