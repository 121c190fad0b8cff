// The blocking client: timeouts, late replies, errors, lost connections.
#include <thread>

#include "knoblab/control/client.hpp"
#include "test_support.hpp"

namespace knoblab::control::test {
namespace {

using ClientTest = ServerTest;

TEST_F(ClientTest, TimesOutAndThenSkipsTheLateReply) {
  handler.respond = [](const Request& r) {
    if (r.command == Command::calibrate) std::this_thread::sleep_for(300ms);
    return Reply::success({{"cmd", to_string(r.command)}});
  };
  Client c(config.socket_path);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_THROW(c.request("calibrate", {{"kind", "gravity"}}, 100ms), ClientError);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 250ms);
  // The calibrate reply arrives later; the next request must get its own.
  const json r = c.call("get_state");
  EXPECT_EQ(r.at("cmd"), "get_state");
}

TEST_F(ClientTest, CallThrowsRemoteErrorWithTheCode) {
  Client c(config.socket_path);
  try {
    c.call("set_mode", {{"mode", "warp"}});
    FAIL();
  } catch (const RemoteError& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_args);
    EXPECT_EQ(e.error().key, "mode");
  }
  try {
    c.call("frobnicate");
    FAIL();
  } catch (const RemoteError& e) {
    EXPECT_EQ(e.code(), ErrorCode::unknown_command);
  }
}

TEST_F(ClientTest, HelloWithNoCommonVersionIsUnsupported) {
  Client c(config.socket_path);
  try {
    c.hello({.versions = {2, 3}, .client_name = "", .watchdog_ms = std::nullopt});
    FAIL();
  } catch (const RemoteError& e) {
    EXPECT_EQ(e.code(), ErrorCode::unsupported_version);
  }
}

TEST_F(ClientTest, RequestTooLargeForAFrameIsRefusedLocally) {
  Client c(config.socket_path);
  EXPECT_THROW(c.request("start_capture", {{"knob", std::string(kMaxFramePayload, 'k')}}), ClientError);
  EXPECT_TRUE(c.request("ping").ok) << "nothing was sent";
}

TEST(ClientAlone, ConnectFailureIsAClientError) {
  TempDir dir;
  EXPECT_THROW(Client(dir.path() + "/nobody.sock"), ClientError);
}

TEST_F(ClientTest, ServerGoingAwayIsAClientError) {
  Client c(config.socket_path);
  ASSERT_TRUE(c.request("ping").ok);
  server->stop();
  EXPECT_THROW(c.request("ping"), ClientError);
  EXPECT_FALSE(c.connected());
}

}  // namespace
}  // namespace knoblab::control::test
