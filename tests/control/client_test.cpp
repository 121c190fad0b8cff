// The blocking client: timeouts, late replies, errors, lost connections.
#include <poll.h>

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

class ClientRefused : public ServerTest {
 protected:
  void configure(ServerConfig& c) override { c.max_clients = 1; }
};

// The server refuses (busy) and closes before the client has sent anything;
// the client's send then fails, but the reason is already in its socket.
TEST_F(ClientRefused, RequestOnAConnectionTheServerRefusedReturnsItsReason) {
  Client first(config.socket_path);
  ASSERT_TRUE(first.request("ping").ok);
  Client second(config.socket_path);
  ASSERT_TRUE(wait_until([&] {
    pollfd p{second.native_handle(), POLLIN, 0};
    return ::poll(&p, 1, 0) == 1 && (p.revents & POLLHUP);  // the server has closed its end
  }, 5s));
  Reply r;
  ASSERT_NO_THROW(r = second.request("ping")) << "the server's reason was lost";
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.code, ErrorCode::busy);
  EXPECT_NE(r.error.message.find("too many clients"), std::string::npos) << r.error.message;
}

}  // namespace
}  // namespace knoblab::control::test
