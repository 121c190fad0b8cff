// publish/subscribe: events reach exactly the clients that asked for them.
#include <thread>

#include "knoblab/control/client.hpp"
#include "test_support.hpp"

namespace knoblab::control::test {
namespace {

using EventsTest = ServerTest;

TEST_F(EventsTest, OnlySubscribersReceiveAnEvent) {
  Client state_only(config.socket_path), all(config.socket_path), none(config.socket_path);
  EXPECT_EQ(state_only.call("subscribe", {{"events", {"state"}}}).at("events"), json({"state"}));
  EXPECT_EQ(all.call("subscribe", {{"events", {"*"}}}).at("events").size(), kEventNames.size());

  server->publish({"fault_latched", {{"bits", 4}}});
  server->publish({"state", {{"mode", "render"}}});

  const auto s = state_only.wait_event(2s);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->name, "state");
  EXPECT_EQ(s->data, json({{"mode", "render"}}));

  const auto a1 = all.wait_event(2s);
  const auto a2 = all.wait_event(2s);
  ASSERT_TRUE(a1 && a2);
  EXPECT_EQ(a1->name, "fault_latched") << "events keep their publish order";
  EXPECT_EQ(a2->name, "state");

  EXPECT_FALSE(none.wait_event(100ms).has_value());
  EXPECT_FALSE(state_only.wait_event(50ms).has_value()) << "fault_latched was not subscribed";
}

TEST_F(EventsTest, EmptyListUnsubscribes) {
  Client c(config.socket_path);
  c.call("subscribe", {{"events", {"stats"}}});
  c.call("subscribe", {{"events", json::array()}});
  server->publish({"stats", {{"n", 1}}});
  EXPECT_FALSE(c.wait_event(100ms).has_value());
}

TEST_F(EventsTest, SubscribeReportsTheTelemetryShm) {
  Client c(config.socket_path);
  const json r = c.call("subscribe", {{"events", json::array()}, {"telemetry", true}});
  EXPECT_EQ(r.at("telemetry_shm"), config.telemetry_shm);
  EXPECT_FALSE(c.call("subscribe", {{"events", json::array()}}).contains("telemetry_shm"));
}

TEST_F(EventsTest, UnknownEventNamesAreRefused) {
  EXPECT_THROW(server->publish({"no_such_event", json::object()}), std::invalid_argument);
  EXPECT_THROW(server->publish({"stats", {{"blob", std::string(kMaxFramePayload, 'x')}}}), std::invalid_argument);
  Client c(config.socket_path);
  const Reply r = c.request("subscribe", {{"events", {"state", "bogus"}}});
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.code, ErrorCode::bad_args);
  EXPECT_EQ(r.error.key, "events");
}

TEST_F(EventsTest, EventsArrivingBeforeAReplyAreKeptForLater) {
  Client c(config.socket_path);
  c.call("subscribe", {{"events", {"capture_finished"}}});
  server->publish({"capture_finished", {{"samples", 60000}}});
  std::this_thread::sleep_for(50ms);  // the event now waits in c's socket, ahead of any reply
  ASSERT_TRUE(c.request("ping").ok);
  c.close();  // so the event can only come from the client's queue
  const auto e = c.wait_event(0ms);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->name, "capture_finished");
  EXPECT_EQ(e->data.at("samples"), 60000);
}

TEST_F(EventsTest, HandlerMayPublishWhileHandling) {
  Client c(config.socket_path);
  c.call("subscribe", {{"events", {"trial"}}});
  handler.respond = [this](const Request& r) {
    server->publish({"trial", {{"running", true}, {"participant", r.args.at("participant")}}});
    return Reply::success();
  };
  ASSERT_TRUE(c.request("start_trial", {{"study", "S1"}, {"participant", 7}, {"condition", "c"}}).ok);
  const auto e = c.wait_event(2s);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->data.at("participant"), 7);
}

TEST_F(EventsTest, PublishFromManyThreads) {
  Client c(config.socket_path);
  c.call("subscribe", {{"events", {"stats"}}});
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 100; ++i) server->publish({"stats", {{"t", t}, {"i", i}}});
    });
  for (auto& th : threads) th.join();
  std::vector<int> next(4, 0);
  for (int n = 0; n < 400; ++n) {
    const auto e = c.wait_event(2s);
    ASSERT_TRUE(e.has_value()) << n;
    const int t = e->data.at("t");
    EXPECT_EQ(e->data.at("i"), next[static_cast<std::size_t>(t)]++) << "per-thread order is kept";
  }
  EXPECT_EQ(server->stats().events_dropped, 0u);
}

}  // namespace
}  // namespace knoblab::control::test
