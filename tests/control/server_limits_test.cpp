// Bounded resources: the client limit, clients that never read, frames that
// never finish. In each case the server drops the offender and keeps serving.
#include <thread>

#include "knoblab/control/client.hpp"
#include "test_support.hpp"

namespace knoblab::control::test {
namespace {

class ServerLimits : public ServerTest {
 protected:
  void configure(ServerConfig& c) override {
    c.max_clients = 4;
    c.max_queued_bytes = 64 * 1024;
    c.partial_frame_timeout = 200ms;
  }
};

TEST_F(ServerLimits, ClientOverTheLimitGetsBusyAndIsClosed) {
  std::vector<std::unique_ptr<Client>> clients;
  for (std::size_t i = 0; i < config.max_clients; ++i) {
    clients.push_back(std::make_unique<Client>(config.socket_path));
    ASSERT_TRUE(clients.back()->request("ping").ok);  // accepted, not just queued in the backlog
  }
  RawConnection extra(config.socket_path);
  const auto messages = extra.read_until_closed(2s);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(outcome(messages[0]), "busy");
  EXPECT_TRUE(messages[0]["id"].is_null());
  EXPECT_TRUE(extra.closed());
  EXPECT_EQ(server->stats().clients_refused, 1u);
  for (auto& c : clients) EXPECT_TRUE(c->request("ping").ok);

  clients.pop_back();  // a slot frees up
  ASSERT_TRUE(wait_until([&] {
    try {
      Client again(config.socket_path);
      return again.request("ping", json::object(), 200ms).ok;
    } catch (const ClientError&) {
      return false;
    }
  }, 2s));
}

TEST_F(ServerLimits, ClientThatNeverReadsIsDroppedWithoutStallingOthers) {
  RawConnection sleeper(config.socket_path);
  ASSERT_TRUE(sleeper.send_bytes(request_frame(1, "subscribe", {{"events", {"*"}}})));
  ASSERT_TRUE(wait_until([&] { return server->stats().requests >= 1; }, 2s));
  Client good(config.socket_path);
  ASSERT_TRUE(good.request("ping").ok);

  // ~8 MB of events: far more than the socket buffer plus the 64 KiB queue.
  const json blob = std::string(8000, 'x');
  for (int i = 0; i < 1000; ++i) {
    server->publish({"stats", {{"i", i}, {"blob", blob}}});
    if (i % 100 == 0) {
      const auto t0 = std::chrono::steady_clock::now();
      ASSERT_TRUE(good.request("ping").ok);
      EXPECT_LT(std::chrono::steady_clock::now() - t0, 500ms) << "a slow client must not stall the server";
    }
  }
  ASSERT_TRUE(wait_until([&] { return server->stats().clients_dropped == 1; }, 2s));
  EXPECT_TRUE(good.request("ping").ok);
}

TEST_F(ServerLimits, ClientThatFloodsRequestsWithoutReadingIsDropped) {
  RawConnection flooder(config.socket_path);
  std::string batch;
  for (int i = 0; i < 500; ++i) batch += request_frame(i, "get_state");
  bool sending = true;
  for (int round = 0; round < 200 && sending; ++round) sending = flooder.send_bytes(batch);
  ASSERT_TRUE(wait_until([&] { return server->stats().clients_dropped == 1; }, 3s));
  expect_server_answers();
}

TEST_F(ServerLimits, IncompleteFrameTimesOutWithBadFrame) {
  RawConnection slow(config.socket_path);
  const std::string frame = request_frame(5, "ping");
  ASSERT_TRUE(slow.send_bytes(frame.substr(0, 6)));
  const auto t0 = std::chrono::steady_clock::now();
  const auto messages = slow.read_until_closed(2s);
  const auto waited = std::chrono::steady_clock::now() - t0;
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(outcome(messages[0]), "bad_frame");
  EXPECT_TRUE(slow.closed());
  EXPECT_GE(waited, 150ms);
  EXPECT_LT(waited, 1500ms);
  expect_server_answers();
}

TEST_F(ServerLimits, SlowButSteadyFramesDoNotTimeOut) {
  RawConnection slow(config.socket_path);
  const std::string frame = request_frame(5, "ping");
  for (int i = 0; i < 3; ++i) {  // each frame completes within the timeout
    ASSERT_TRUE(slow.send_bytes(frame.substr(0, 6)));
    std::this_thread::sleep_for(120ms);
    ASSERT_TRUE(slow.send_bytes(frame.substr(6)));
    const auto m = slow.read_message(1s);
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(outcome(*m), "ok");
  }
}

TEST_F(ServerLimits, PeerThatHalfClosesStillGetsItsReplies) {
  RawConnection raw(config.socket_path);
  std::string batch;
  for (int i = 0; i < 50; ++i) batch += request_frame(i, "ping");
  ASSERT_TRUE(raw.send_bytes(batch));
  raw.shutdown_write();
  const auto messages = raw.read_until_closed(2s);
  EXPECT_EQ(messages.size(), 50u);
  EXPECT_TRUE(raw.closed());
}

}  // namespace
}  // namespace knoblab::control::test
