// The server over a real socket in /tmp: round trips, the socket file, and
// each error code for the input that should produce it.
#include <grp.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <set>

#include "knoblab/control/client.hpp"
#include "knoblab/control/schema.hpp"
#include "test_support.hpp"

namespace knoblab::control::test {
namespace {

TEST_F(ServerTest, RequestReplyRoundTripThroughTheHandler) {
  handler.respond = [](const Request& r) {
    return Reply::success({{"mode", r.args.at("mode")}, {"id_seen", r.id}});
  };
  Client c(config.socket_path);
  const json hello = c.hello({.versions = {1}, .client_name = "test", .watchdog_ms = std::nullopt});
  EXPECT_EQ(hello.at("version"), 1);
  EXPECT_EQ(hello.at("server"), "hapticd");
  EXPECT_EQ(hello.at("max_frame_bytes"), kMaxFramePayload);
  const json result = c.call("set_mode", {{"mode", "render"}});
  EXPECT_EQ(result.at("mode"), "render");
  const auto seen = handler.requests();
  ASSERT_EQ(seen.size(), 1u) << "hello is answered by the server, set_mode by the handler";
  EXPECT_EQ(seen[0].command, Command::set_mode);
  EXPECT_EQ(result.at("id_seen"), seen[0].id);
}

TEST_F(ServerTest, RawRepliesEchoTheIdAndVersion) {
  RawConnection raw(config.socket_path);
  ASSERT_TRUE(raw.send_bytes(request_frame(41, "ping") + request_frame(42, "get_state")));
  const auto a = raw.read_message(2s);
  const auto b = raw.read_message(2s);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(*a, json({{"v", 1}, {"id", 41}, {"ok", true}, {"result", json::object()}}));
  EXPECT_EQ((*b)["id"], 42);
  EXPECT_EQ((*b)["result"], json({{"echo", "get_state"}}));
}

TEST_F(ServerTest, SocketFileIsASocketWithMode0660) {
  struct stat st{};
  ASSERT_EQ(::stat(config.socket_path.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 07777, 0660u);
}

TEST_F(ServerTest, SocketFileIsRemovedOnStop) {
  server->stop();
  EXPECT_NE(::access(config.socket_path.c_str(), F_OK), 0);
}

TEST(ServerSocket, ChownsToTheConfiguredGroup) {
  TempDir dir;
  RecordingHandler h;
  // A group other than ours where possible, so the chown is visible.
  const gid_t mine = ::getegid();
  gid_t target = mine;
  std::string name;
  for (const char* candidate : {"daemon", "adm", "users", "nogroup"}) {
    if (::geteuid() != 0) break;  // only root may give a file to any group
    if (const group* g = ::getgrnam(candidate)) {
      name = candidate;
      target = g->gr_gid;
      if (target != mine) break;
    }
  }
  if (name.empty()) {
    const group* g = ::getgrgid(mine);
    ASSERT_NE(g, nullptr);
    name = g->gr_name;
  }
  ServerConfig cfg;
  cfg.socket_path = dir.path() + "/hapticd.sock";
  cfg.socket_group = name;
  Server s(cfg, h);
  s.start();
  struct stat st{};
  ASSERT_EQ(::stat(cfg.socket_path.c_str(), &st), 0);
  EXPECT_EQ(st.st_gid, target) << "group " << name;
  EXPECT_EQ(st.st_mode & 07777, 0660u);
}

TEST(ServerSocket, UnknownGroupIsAClearStartupError) {
  TempDir dir;
  RecordingHandler h;
  ServerConfig cfg;
  cfg.socket_path = dir.path() + "/hapticd.sock";
  cfg.socket_group = "no-such-group-knoblab";
  Server s(cfg, h);
  try {
    s.start();
    FAIL() << "started with a missing group";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-group-knoblab"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_NE(::access(cfg.socket_path.c_str(), F_OK), 0) << "no socket file left behind";
}

TEST(ServerSocket, CreatesMissingParentDirectories) {
  TempDir dir;
  RecordingHandler h;
  ServerConfig cfg;
  cfg.socket_path = dir.path() + "/a/b/c/hapticd.sock";
  Server s(cfg, h);
  s.start();
  Client c(cfg.socket_path);
  EXPECT_TRUE(c.request("ping").ok);
}

TEST(ServerSocket, ReplacesAStaleSocketFile) {
  TempDir dir;
  const std::string path = dir.path() + "/hapticd.sock";
  {  // a socket file whose server is gone
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    ::close(fd);
  }
  RecordingHandler h;
  ServerConfig cfg;
  cfg.socket_path = path;
  Server s(cfg, h);
  ASSERT_NO_THROW(s.start());
  Client c(path);
  EXPECT_TRUE(c.request("ping").ok);
}

TEST(ServerSocket, RefusesAPathALiveServerAnswersOn) {
  TempDir dir;
  RecordingHandler h;
  ServerConfig cfg;
  cfg.socket_path = dir.path() + "/hapticd.sock";
  Server first(cfg, h);
  first.start();
  Server second(cfg, h);
  try {
    second.start();
    FAIL() << "two servers on one socket";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("in use"), std::string::npos) << e.what();
  }
  Client c(cfg.socket_path);
  EXPECT_TRUE(c.request("ping").ok) << "the first server keeps its socket";
}

TEST(ServerSocket, RefusesToRemoveSomethingThatIsNotASocket) {
  TempDir dir;
  const std::string path = dir.path() + "/hapticd.sock";
  std::ofstream(path) << "precious";
  RecordingHandler h;
  ServerConfig cfg;
  cfg.socket_path = path;
  Server s(cfg, h);
  EXPECT_THROW(s.start(), std::runtime_error);
  std::ifstream in(path);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "precious");
}

// ---- every error code through the socket -----------------------------------------

struct WireCase {
  const char* name;
  std::string bytes;
  const char* code;
  bool closes;
};

TEST_F(ServerTest, EveryErrorCodeForItsInput) {
  handler.respond = [](const Request& r) -> Reply {
    if (r.command == Command::start_capture) return Reply::failure(ErrorCode::busy, "capture running");
    if (r.command == Command::calibrate) throw std::runtime_error("sensor unplugged");
    return Reply::success();
  };
  const std::vector<WireCase> cases = {
      {"zero-length frame", header_only(0), "bad_frame", false},
      {"non-UTF-8", raw_frame("{\"v\":1,\"id\":1,\"cmd\":\"\xFF\"}"), "bad_frame", false},
      {"length 0xFFFFFFFF", header_only(0xFFFFFFFFu), "oversized", true},
      {"length 64 KiB + 1", header_only(kMaxFramePayload + 1) + std::string(100, ' '), "oversized", true},
      {"not JSON", raw_frame("{nope"), "bad_json", false},
      {"deep JSON", raw_frame(std::string(60000, '[')), "bad_json", false},
      {"array", raw_frame("[]"), "not_an_object", false},
      {"v 2", raw_frame(R"({"v":2,"id":1,"cmd":"ping"})"), "unsupported_version", false},
      {"hello without v1", request_frame(1, "hello", {{"versions", {2, 3}}}), "unsupported_version", false},
      {"unknown command", request_frame(1, "reboot"), "unknown_command", false},
      {"bad args", request_frame(1, "set_mode", {{"mode", "turbo"}}), "bad_args", false},
      {"handler busy", request_frame(1, "start_capture", json::parse(command_spec(Command::start_capture).example_args)),
       "busy", false},
      {"handler throws", request_frame(1, "calibrate", {{"kind", "torque"}}), "internal", false},
  };
  std::set<std::string> codes;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    RawConnection raw(config.socket_path);
    ASSERT_TRUE(raw.send_bytes(c.bytes));
    const auto reply = raw.read_message(2s);
    ASSERT_TRUE(reply.has_value()) << "no reply";
    EXPECT_EQ(outcome(*reply), c.code) << reply->dump();
    EXPECT_EQ((*reply)["v"], 1);
    codes.insert(c.code);
    if (c.closes) {
      EXPECT_TRUE(raw.read_until_closed(2s).empty());
      EXPECT_TRUE(raw.closed()) << "connection must be closed after " << c.code;
    } else {
      ASSERT_TRUE(raw.send_bytes(request_frame(99, "ping")));
      const auto pong = raw.read_message(2s);
      ASSERT_TRUE(pong.has_value()) << "connection must stay open after " << c.code;
      EXPECT_EQ(outcome(*pong), "ok");
      EXPECT_EQ((*pong)["id"], 99);
    }
  }
  EXPECT_EQ(codes.size(), kErrorCodeCount) << "every error code";
  // Only the two valid handler commands reached the handler.
  EXPECT_EQ(handler.request_count(), 2u);
}

TEST_F(ServerTest, BadArgsMessageNamesKeyAndProblem) {
  Client c(config.socket_path);
  const Reply r = c.request("load_model", {{"M_acc", "heavy"}, {"B_vel", 0}, {"A_pos", 0}, {"P_pos", 1}});
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.code, ErrorCode::bad_args);
  EXPECT_EQ(r.error.key, "M_acc");
  EXPECT_NE(r.error.message.find("M_acc"), std::string::npos) << r.error.message;
  EXPECT_NE(r.error.message.find("number"), std::string::npos) << r.error.message;
  EXPECT_EQ(handler.request_count(), 0u);
}

TEST_F(ServerTest, HandlerResultThatIsNotAnObjectBecomesInternal) {
  handler.respond = [](const Request&) { return Reply::success(json::array({1, 2})); };
  Client c(config.socket_path);
  const Reply r = c.request("get_state");
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.code, ErrorCode::internal);
}

TEST_F(ServerTest, ManyRequestsInOneWriteAreAnsweredInOrder) {
  std::string batch;
  for (int i = 0; i < 200; ++i) batch += request_frame(i, i % 2 ? "ping" : "get_state");
  RawConnection raw(config.socket_path);
  ASSERT_TRUE(raw.send_bytes(batch));
  for (int i = 0; i < 200; ++i) {
    const auto m = raw.read_message(2s);
    ASSERT_TRUE(m.has_value()) << i;
    EXPECT_EQ((*m)["id"], i);
    EXPECT_EQ(outcome(*m), "ok");
  }
}

}  // namespace
}  // namespace knoblab::control::test
