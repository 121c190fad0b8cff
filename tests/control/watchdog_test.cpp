// The supervising client's watchdog: silence or disconnect → the handler's
// safe state, exactly once; regular pings keep it quiet.
#include <thread>

#include "knoblab/control/client.hpp"
#include "test_support.hpp"

namespace knoblab::control::test {
namespace {

using Watchdog = ServerTest;
using Clock = std::chrono::steady_clock;

HelloOptions supervising(int ms) { return {.versions = {1}, .client_name = "ui", .watchdog_ms = ms}; }

TEST_F(Watchdog, FiresOnSilence) {
  Client ui(config.socket_path);
  const auto t0 = Clock::now();
  const json hello = ui.hello(supervising(100));
  EXPECT_EQ(hello.at("supervising"), true);
  EXPECT_EQ(hello.at("watchdog_ms"), 100);
  ASSERT_TRUE(handler.wait_for_expiries(1, 2s));
  const auto after = Clock::now() - t0;
  EXPECT_GE(after, 95ms) << "fired early";
  EXPECT_LT(after, 600ms) << "fired late";
  EXPECT_EQ(handler.expiries(), std::vector{WatchdogReason::silence});
  // Once: supervision ended with the expiry.
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(handler.expiries().size(), 1u);
  EXPECT_EQ(server->stats().watchdog_expiries, 1u);
}

TEST_F(Watchdog, FiresOnDisconnectLongBeforeTheTimeout) {
  auto ui = std::make_unique<Client>(config.socket_path);
  ui->hello(supervising(10000));
  const auto t0 = Clock::now();
  ui.reset();
  ASSERT_TRUE(handler.wait_for_expiries(1, 2s));
  EXPECT_LT(Clock::now() - t0, 500ms);
  EXPECT_EQ(handler.expiries(), std::vector{WatchdogReason::disconnect});
}

TEST_F(Watchdog, DoesNotFireWhilePingsArrive) {
  Client ui(config.socket_path);
  ui.hello(supervising(100));
  const auto until = Clock::now() + 600ms;
  while (Clock::now() < until) {
    ASSERT_TRUE(ui.request("ping").ok);
    std::this_thread::sleep_for(25ms);
  }
  EXPECT_TRUE(handler.expiries().empty()) << "fired although pings arrived every 25 ms";
  // Stop pinging: now it fires.
  ASSERT_TRUE(handler.wait_for_expiries(1, 2s));
  EXPECT_EQ(handler.expiries(), std::vector{WatchdogReason::silence});
}

TEST_F(Watchdog, InvalidMessagesDoNotCountAsLifeSigns) {
  RawConnection ui(config.socket_path);
  ASSERT_TRUE(ui.send_bytes(request_frame(1, "hello", {{"versions", {1}}, {"watchdog_ms", 100}})));
  ASSERT_TRUE(ui.read_message(1s).has_value());
  const auto until = Clock::now() + 400ms;
  while (Clock::now() < until && handler.expiries().empty()) {
    ASSERT_TRUE(ui.send_bytes(raw_frame("{garbage")));
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_EQ(handler.expiries(), std::vector{WatchdogReason::silence});
}

TEST_F(Watchdog, AnySecondSupervisorIsBusyUntilTheFirstLeaves) {
  auto first = std::make_unique<Client>(config.socket_path);
  first->hello(supervising(5000));
  Client second(config.socket_path);
  try {
    second.hello(supervising(5000));
    FAIL() << "two supervisors";
  } catch (const RemoteError& e) {
    EXPECT_EQ(e.code(), ErrorCode::busy);
  }
  EXPECT_EQ(second.hello().at("supervising"), false) << "a plain hello is fine";
  first.reset();
  ASSERT_TRUE(handler.wait_for_expiries(1, 2s));
  EXPECT_EQ(second.hello(supervising(5000)).at("supervising"), true);
}

TEST_F(Watchdog, HelloWithoutWatchdogEndsSupervisionQuietly) {
  Client ui(config.socket_path);
  ui.hello(supervising(100));
  EXPECT_EQ(ui.hello().at("supervising"), false);
  std::this_thread::sleep_for(300ms);
  ui.close();
  std::this_thread::sleep_for(100ms);
  EXPECT_TRUE(handler.expiries().empty());
}

TEST_F(Watchdog, SubscribersHearAboutTheExpiry) {
  Client observer(config.socket_path);
  observer.call("subscribe", {{"events", {"watchdog_expired"}}});
  Client ui(config.socket_path);
  ui.hello(supervising(50));
  const auto e = observer.wait_event(2s);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->name, "watchdog_expired");
  EXPECT_EQ(e->data.at("reason"), "silence");
}

TEST_F(Watchdog, StopDoesNotFireIt) {
  Client ui(config.socket_path);
  ui.hello(supervising(10000));
  server->stop();
  EXPECT_TRUE(handler.expiries().empty());
}

}  // namespace
}  // namespace knoblab::control::test
