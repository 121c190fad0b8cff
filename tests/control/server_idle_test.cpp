// Connection life: connections that say nothing are closed, so they cannot
// hold the client slots; subscribers and the supervisor stay while silent;
// one process cannot take every slot. Timeouts are short here, and the tests
// assert outcomes (closed or not, with which error), never how long it took.
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <thread>

#include "knoblab/control/client.hpp"
#include "test_support.hpp"

namespace knoblab::control::test {
namespace {

// Generous: only an outcome that never comes should take this long.
constexpr auto kPatience = 5s;

bool can_ping(const std::string& socket_path) {
  try {
    Client c(socket_path);
    return c.request("ping", json::object(), 500ms).ok;
  } catch (const ClientError&) {
    return false;
  }
}

// A closed connection's last words: one busy error without an id.
void expect_closed_with_busy(RawConnection& raw, std::string_view why) {
  const auto messages = raw.read_until_closed(kPatience);
  ASSERT_EQ(messages.size(), 1u) << why;
  EXPECT_EQ(outcome(messages[0]), "busy") << why;
  EXPECT_TRUE(messages[0]["id"].is_null());
  EXPECT_NE(messages[0]["error"]["message"].get<std::string>().find(why), std::string::npos)
      << messages[0].dump();
  EXPECT_TRUE(raw.closed()) << why;
}

class SilentClients : public ServerTest {
 protected:
  void configure(ServerConfig& c) override {
    c.max_clients = 16;
    c.max_clients_per_peer = 16;  // all the connections below come from this process
    c.hello_timeout = 300ms;
    c.idle_timeout = 60s;
  }
};

TEST_F(SilentClients, SixteenSilentConnectionsAreClosedAfterTheHelloTimeoutAndANewClientGetsIn) {
  std::vector<std::unique_ptr<RawConnection>> silent;
  for (std::size_t i = 0; i < config.max_clients; ++i)
    silent.push_back(std::make_unique<RawConnection>(config.socket_path));
  for (auto& s : silent) expect_closed_with_busy(*s, "no request");
  EXPECT_EQ(server->stats().clients_hello_timed_out, config.max_clients);
  EXPECT_TRUE(wait_until([&] { return can_ping(config.socket_path); }, kPatience))
      << "the slots of the silent connections were not freed";
  EXPECT_EQ(handler.request_count(), 0u);
}

TEST_F(SilentClients, ConnectionThatSentARequestOutlivesTheHelloTimeout) {
  Client c(config.socket_path);
  ASSERT_TRUE(c.request("ping").ok);
  std::this_thread::sleep_for(config.hello_timeout * 4);
  EXPECT_TRUE(c.request("ping").ok) << "a connection that spoke is past the hello rule";
  EXPECT_EQ(server->stats().clients_hello_timed_out, 0u);
}

TEST_F(SilentClients, InvalidFramesDoNotCountAsSayingHello) {
  RawConnection raw(config.socket_path);
  ASSERT_TRUE(raw.send_bytes(raw_frame("not json")));
  const auto first = raw.read_message(kPatience);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(outcome(*first), "bad_json");
  expect_closed_with_busy(raw, "no request");
}

TEST_F(SilentClients, HalfSentFrameIsStillClosedWhenTheHelloTimeoutIsShorter) {
  RawConnection raw(config.socket_path);
  ASSERT_TRUE(raw.send_bytes(request_frame(1, "ping").substr(0, 6)));
  expect_closed_with_busy(raw, "no request");
}

class IdleClients : public ServerTest {
 protected:
  void configure(ServerConfig& c) override {
    c.hello_timeout = 5s;
    c.idle_timeout = 300ms;
  }
};

TEST_F(IdleClients, ClientThatStopsSendingIsClosedAfterTheIdleTimeout) {
  RawConnection raw(config.socket_path);
  ASSERT_TRUE(raw.send_bytes(request_frame(1, "hello", {{"versions", {1}}})));
  const auto hello = raw.read_message(kPatience);
  ASSERT_TRUE(hello.has_value());
  EXPECT_EQ(outcome(*hello), "ok");
  expect_closed_with_busy(raw, "idle");
  EXPECT_EQ(server->stats().clients_idle_timed_out, 1u);
  EXPECT_EQ(server->stats().clients_hello_timed_out, 0u);
  expect_server_answers();
}

TEST_F(IdleClients, ClientThatKeepsSendingStaysConnected) {
  Client c(config.socket_path);
  for (int i = 0; i < 8; ++i) {
    ASSERT_TRUE(c.request("ping").ok) << "round " << i;
    std::this_thread::sleep_for(config.idle_timeout / 4);
  }
  EXPECT_EQ(server->stats().clients_idle_timed_out, 0u);
}

TEST_F(IdleClients, SubscribedSilentClientIsNotClosed) {
  Client watcher(config.socket_path);
  watcher.call("subscribe", {{"events", {"state"}}});
  std::this_thread::sleep_for(config.idle_timeout * 5);
  server->publish({"state", {{"mode", "render"}}});
  const auto event = watcher.wait_event(kPatience);
  ASSERT_TRUE(event.has_value()) << "a subscriber was closed for being silent";
  EXPECT_EQ(event->name, "state");
  EXPECT_TRUE(watcher.request("ping").ok);
  EXPECT_EQ(server->stats().clients_idle_timed_out, 0u);
}

TEST_F(IdleClients, ClientThatUnsubscribesBecomesIdleAgain) {
  RawConnection raw(config.socket_path);
  ASSERT_TRUE(raw.send_bytes(request_frame(1, "subscribe", {{"events", {"state"}}})));
  ASSERT_TRUE(raw.read_message(kPatience).has_value());
  ASSERT_TRUE(raw.send_bytes(request_frame(2, "subscribe", {{"events", json::array()}})));
  ASSERT_TRUE(raw.read_message(kPatience).has_value());
  expect_closed_with_busy(raw, "idle");
}

TEST_F(IdleClients, SupervisingClientIsNotClosedForBeingSilent) {
  Client ui(config.socket_path);
  ui.hello({.versions = {1}, .client_name = "ui", .watchdog_ms = 60000});
  std::this_thread::sleep_for(config.idle_timeout * 5);
  EXPECT_TRUE(ui.request("ping").ok) << "the supervisor was closed for being silent";
  EXPECT_TRUE(handler.expiries().empty()) << "closing the supervisor would have made the motor safe";
  EXPECT_EQ(server->stats().clients_idle_timed_out, 0u);
}

class PerPeerLimit : public ServerTest {
 protected:
  void configure(ServerConfig& c) override {
    c.max_clients = 16;
    c.max_clients_per_peer = 2;
  }
};

// In a forked child (a different peer): connect, ping, and exit 0 if the
// reply is ok. Only system calls after fork(): the parent has threads.
int ping_from_child(const std::string& socket_path) {
  const std::string frame = request_frame(7, "ping");
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, socket_path.c_str(), sizeof addr.sun_path - 1);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0 || ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) ::_exit(10);
    if (::send(fd, frame.data(), frame.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(frame.size())) ::_exit(11);
    timeval tv{5, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    char reply[512];
    std::size_t got = 0;
    for (;;) {
      const ssize_t n = ::recv(fd, reply + got, sizeof reply - 1 - got, 0);
      if (n <= 0) ::_exit(12);
      got += static_cast<std::size_t>(n);
      reply[got] = '\0';
      if (got > 4 && std::strstr(reply + 4, "}")) break;  // a whole (small) reply
    }
    ::_exit(std::strstr(reply + 4, "\"ok\":true") ? 0 : 13);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(PerPeerLimit, OneProcessCannotOpenMoreThanItsShareWhileAnotherProcessStillCan) {
  std::vector<std::unique_ptr<Client>> mine;
  for (std::size_t i = 0; i < config.max_clients_per_peer; ++i) {
    mine.push_back(std::make_unique<Client>(config.socket_path));
    ASSERT_TRUE(mine.back()->request("ping").ok);
  }
  RawConnection extra(config.socket_path);
  expect_closed_with_busy(extra, "limit 2 per process");
  EXPECT_EQ(server->stats().clients_refused_per_peer, 1u);
  EXPECT_EQ(server->stats().clients_refused, 0u) << "the server as a whole still has room";

  EXPECT_EQ(ping_from_child(config.socket_path), 0) << "another process must still get in";
  for (auto& c : mine) EXPECT_TRUE(c->request("ping").ok);

  mine.pop_back();  // this process's share frees up
  EXPECT_TRUE(wait_until([&] { return can_ping(config.socket_path); }, kPatience));
}

TEST_F(PerPeerLimit, ConnectionsClosedInABurstDoNotCountAgainstTheProcess) {
  for (int i = 0; i < 20; ++i) {
    RawConnection raw(config.socket_path);
    ASSERT_TRUE(raw.send_bytes(request_frame(i, "ping")));
  }  // each closed before the next opens, none read its reply
  // Two round trips: by the second, the server has reaped the burst.
  expect_server_answers();
  expect_server_answers();
  EXPECT_EQ(server->stats().clients_refused_per_peer, 0u);
}

}  // namespace
}  // namespace knoblab::control::test
