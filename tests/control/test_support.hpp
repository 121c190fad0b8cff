// Shared helpers for the control tests: a temp socket directory, a handler
// that records (and re-checks) what the server hands it, and a raw socket
// that can send arbitrary bytes.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/control/command_handler.hpp"
#include "knoblab/control/server.hpp"

namespace knoblab::control::test {

using namespace std::chrono_literals;
using nlohmann::json;

// A fresh directory under /tmp, removed with its contents.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

class RecordingHandler : public CommandHandler {
 public:
  Reply handle(const Request& request) override;
  void on_watchdog_expired(WatchdogReason reason) override;

  // Replaces the default answer (ok, {"echo": cmd}).
  std::function<Reply(const Request&)> respond;

  std::vector<Request> requests() const;
  std::size_t request_count() const;
  // Requests that would not pass decode_request again, or that the server
  // should have answered itself. Must stay 0.
  std::size_t invalid_requests() const { return invalid_.load(); }
  std::vector<WatchdogReason> expiries() const;
  bool wait_for_expiries(std::size_t n, std::chrono::milliseconds timeout) const;

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable cv_;
  std::vector<Request> requests_;
  std::vector<WatchdogReason> expiries_;
  std::atomic<std::size_t> invalid_{0};
};

// A socket for sending anything at all.
class RawConnection {
 public:
  explicit RawConnection(const std::string& path);
  ~RawConnection();
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  // False if the peer is gone (EPIPE/ECONNRESET); never raises SIGPIPE.
  bool send_bytes(std::string_view bytes);
  bool send_json(const json& message);
  void shutdown_write();
  void close();

  // The next frame as JSON (a frame that is not JSON fails the test), or
  // nullopt on timeout or when the connection closed (then closed() is true).
  std::optional<json> read_message(std::chrono::milliseconds timeout);
  // Every message until the server closes the connection (or timeout).
  std::vector<json> read_until_closed(std::chrono::milliseconds timeout);
  bool closed() const { return closed_; }

 private:
  int fd_ = -1;
  std::string buffer_;
  bool closed_ = false;
};

// A request frame as the protocol wants it.
std::string request_frame(std::int64_t id, std::string_view cmd, const json& args = json::object());
// A frame around arbitrary payload bytes (any length that fits 32 bits).
std::string raw_frame(std::string_view payload);
std::string header_only(std::uint32_t length);

// Error code of a reply message ("ok" for success replies).
std::string outcome(const json& reply);

bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout);

// A started server on a temp socket with a RecordingHandler.
class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  // Override to change the config before start.
  virtual void configure(ServerConfig&) {}
  // A raw connection, checked to be still answering: ping round trip.
  void expect_server_answers();

  TempDir dir;
  RecordingHandler handler;
  ServerConfig config;
  std::unique_ptr<Server> server;
};

}  // namespace knoblab::control::test
