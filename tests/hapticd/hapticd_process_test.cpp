// hapticd as a process: its control socket under hostile input, and a capture
// requested over the protocol.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "knoblab/control/client.hpp"
#include "knoblab/control/framing.hpp"
#include "knoblab/store/store.hpp"

extern char** environ;

namespace knoblab::hapticd {
namespace {

namespace fs = std::filesystem;

class Hapticd {
 public:
  explicit Hapticd(std::vector<std::string> extra) {
    std::string tmpl = "/tmp/knoblab-hapticd-XXXXXX";
    dir_ = mkdtemp(tmpl.data());
    socket_ = (dir_ / "h.sock").string();
    std::vector<std::string> args = {KNOBLAB_HAPTICD_PATH, "--backend", "sim", "--knob", "moderate-detents",
                                     "--socket", socket_, "--db", (dir_ / "lab.sqlite").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    const std::string log = (dir_ / "hapticd.log").string();
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    if (posix_spawn(&pid_, argv[0], &fa, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&fa);
    for (int i = 0; i < 500 && !fs::exists(socket_); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ~Hapticd() {
    if (pid_ > 0 && alive()) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    fs::remove_all(dir_);
  }
  bool alive() const { return ::waitpid(pid_, nullptr, WNOHANG) == 0; }
  // SIGTERM and the exit status (0 = clean shutdown).
  int terminate() {
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  const std::string& socket() const { return socket_; }
  fs::path db() const { return dir_ / "lab.sqlite"; }
  std::string log() const {
    std::ifstream in(dir_ / "hapticd.log");
    return {std::istreambuf_iterator<char>(in), {}};
  }

 private:
  fs::path dir_;
  std::string socket_;
  pid_t pid_ = -1;
};

// Writes raw bytes on a fresh connection, reads whatever comes back for a
// moment, and hangs up (mid-frame, often: that is the point).
void send_raw(const std::string& path, const std::string& bytes) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path.c_str());
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) {
    (void)!::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    timeval tv{0, 20000};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    char buf[4096];
    while (::recv(fd, buf, sizeof buf, 0) > 0) {
    }
  }
  ::close(fd);
}

bool answers(const std::string& socket) {
  try {
    control::Client c(socket);
    c.hello();
    return c.call("get_state").contains("mode");
  } catch (const std::exception&) {
    return false;
  }
}

// Acceptance: fuzzed control-socket input (a fixed corpus plus seeded random
// cases) never crashes hapticd, and it keeps serving a good client.
TEST(HapticdProcess, FuzzedControlInputNeverCrashesIt) {
  Hapticd d({"--rate", "1000"});
  ASSERT_TRUE(answers(d.socket())) << d.log();
  int cases = 0;
  for (const auto& entry : fs::directory_iterator(KNOBLAB_CONTROL_CORPUS)) {
    if (entry.path().extension() != ".bin") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    send_raw(d.socket(), {std::istreambuf_iterator<char>(in), {}});
    ++cases;
    ASSERT_TRUE(d.alive()) << entry.path() << "\n" << d.log();
  }
  EXPECT_GT(cases, 10);
  std::mt19937_64 rng(20261122);
  const std::vector<std::string> valid = {
      R"({"v":1,"id":1,"cmd":"get_state","args":{}})",
      R"({"v":1,"id":2,"cmd":"load_model","args":{"M_acc":1e-5,"B_vel":0.001,"A_pos":0.01,"P_pos":0.08}})",
      R"({"v":1,"id":3,"cmd":"set_mode","args":{"mode":"render"}})",
      R"({"v":1,"id":4,"cmd":"start_capture","args":{"seconds":0.1,"knob":"k","swept_sine":{"a":0,"b":1.5,"c":1,"d":3}}})",
      R"({"v":1,"id":5,"cmd":"set_params","args":{"A_pos":0.02}})",
      R"({"v":1,"id":6,"cmd":"clear_fault","args":{}})"};
  for (int i = 0; i < 400; ++i) {
    std::string bytes;
    switch (i % 4) {
      case 0:  // random bytes
        for (std::size_t n = rng() % 300; n > 0; --n) bytes.push_back(static_cast<char>(rng()));
        break;
      case 1: {  // a valid frame with bytes flipped
        bytes = control::encode_frame(valid[rng() % valid.size()]);
        for (int k = 0; k < 1 + static_cast<int>(rng() % 4); ++k) bytes[rng() % bytes.size()] = static_cast<char>(rng());
        break;
      }
      case 2:  // a valid frame cut short
        bytes = control::encode_frame(valid[rng() % valid.size()]);
        bytes.resize(rng() % bytes.size());
        break;
      default:  // valid frames, then garbage
        bytes = control::encode_frame(valid[rng() % valid.size()]) + control::encode_frame(valid[rng() % valid.size()]);
        bytes += std::string(1 + rng() % 8, static_cast<char>(0xff));
    }
    send_raw(d.socket(), bytes);
    if (i % 50 == 49) {
      ASSERT_TRUE(d.alive() && answers(d.socket())) << "case " << i << "\n" << d.log();
    }
  }
  EXPECT_TRUE(answers(d.socket()));
  EXPECT_EQ(d.terminate(), 0) << d.log();
}

// A tab in a knob's name was answered "ok", then the store thread threw and
// hapticd aborted; a capture too short for one cycle was taken and never
// finished. Both are refused at the request, naming the key, and hapticd
// goes on serving.
TEST(HapticdProcess, UnstorableTextAndACaptureOfNoCycleAreRefusedAndHapticdLivesOn) {
  Hapticd d({"--rate", "20"});  // 0.01 s, the shortest capture the schema takes, is no cycle at 20 Hz
  control::Client c(d.socket(), std::chrono::seconds(5));
  c.hello();
  const nlohmann::json sweep = {{"a", 0}, {"b", 1.5}, {"c", 1}, {"d", 3}};
  const std::vector<std::pair<nlohmann::json, std::string>> refused = {
      {{{"seconds", 1.0}, {"knob", "a\tb"}, {"swept_sine", sweep}}, "knob"},
      {{{"seconds", 1.0}, {"knob", "k"}, {"notes", "line 1\nline 2"}, {"swept_sine", sweep}}, "notes"},
      {{{"seconds", 0.01}, {"knob", "k"}, {"swept_sine", sweep}}, "seconds"},
  };
  for (const auto& [args, key] : refused) {
    try {
      c.call("start_capture", args);
      ADD_FAILURE() << "start_capture " << args.dump() << " was accepted";
    } catch (const control::RemoteError& e) {
      EXPECT_EQ(e.code(), control::ErrorCode::bad_args) << e.what();
      EXPECT_EQ(e.error().key, key) << e.what();
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_TRUE(d.alive()) << d.log();
  EXPECT_EQ(c.call("get_state").at("recording"), false);
  EXPECT_EQ(d.terminate(), 0) << d.log();
}

// A desktop user saw the overruns fault latch and clear_fault not stick,
// with nothing in get_state to say why: it carries the evidence and the limit.
TEST(HapticdProcess, GetStateShowsTheOverrunsTheLongestRunOfThemAndTheLimit) {
  Hapticd d({"--rate", "1000", "--max-overruns", "7"});
  control::Client c(d.socket(), std::chrono::seconds(5));
  c.hello();
  const nlohmann::json o = c.call("get_state").at("overruns");
  EXPECT_EQ(o.at("limit"), 7) << o.dump();
  EXPECT_GE(o.at("total").get<std::int64_t>(), o.at("max_consecutive").get<std::int64_t>()) << o.dump();
  EXPECT_EQ(d.terminate(), 0) << d.log();
}

// Runs one capture over the protocol, checks that the reply promises
// `samples`, and returns its capture_finished event. This host is not
// realtime: eleven cycles in a row whose work outlasts its 100 µs period under
// a loaded `ctest -j` are too many overruns at 10 kHz, and the supervisor rightly latches a fault (before
// the request, or mid-capture, ending it incomplete). The test is about the
// protocol and the store, not the host's latency, so an *overruns-only* fault is
// cleared and the capture asked for again (a few times at most); any other
// fault fails the test.
std::optional<control::Event> capture(control::Client& c, const nlohmann::json& args, int samples,
                                      int& overrun_retries) {
  for (int attempt = 0; attempt < 4; ++attempt) {
    const auto faults = c.call("get_state").at("faults");
    if (!faults.empty()) {
      EXPECT_EQ(faults, nlohmann::json::array({"overruns"})) << "only overruns are expected on this host";
      if (faults != nlohmann::json::array({"overruns"})) return std::nullopt;
      c.call("clear_fault");
      ++overrun_retries;
      continue;
    }
    try {
      EXPECT_EQ(c.call("start_capture", args).at("samples"), samples);
    } catch (const control::RemoteError& e) {
      // The fault latched between get_state and start_capture: look again.
      if (std::string(e.what()).find("fault is latched") == std::string::npos) throw;
      continue;
    }
    auto ev = c.wait_event(std::chrono::seconds(10));
    if (!ev || ev->data.value("complete", false)) return ev;
    ++overrun_retries;  // ended early by a fault; the loop above checks which
  }
  return std::nullopt;
}

// A capture asked for over the protocol lands in the store, complete.
TEST(HapticdProcess, CaptureOverTheProtocolLandsInTheStore) {
  Hapticd d({"--rate", "10000"});
  control::Client c(d.socket(), std::chrono::seconds(5));
  c.hello();
  c.call("subscribe", {{"events", {"capture_finished"}}});
  int retries = 0;
  const auto ev = capture(c, {{"seconds", 1.0}, {"knob", "moderate-detents"},
                              {"swept_sine", {{"a", 0}, {"b", 1.5}, {"c", 1.0}, {"d", 3}}}}, 10000, retries);
  ASSERT_TRUE(ev) << d.log();
  EXPECT_EQ(ev->name, "capture_finished");
  EXPECT_EQ(ev->data.at("samples"), 10000);
  // The open-loop torque stimulus, too.
  const auto ev2 = capture(c, {{"seconds", 0.5}, {"knob", "moderate-detents"},
                               {"torque_sweep", {{"a", 2}, {"b", 10}, {"c", 0.02}, {"d", 2}}}}, 5000, retries);
  ASSERT_TRUE(ev2) << d.log();
  EXPECT_EQ(ev2->data.at("samples"), 5000);
  EXPECT_EQ(d.terminate(), 0) << d.log();
  if (retries) std::printf("note: %d capture(s) re-asked after an overrun fault (host latency)\n", retries);
  // Captures a fault cut short are kept, marked incomplete; the two that ran
  // to the end are complete and hold every sample.
  store::Store s = store::Store::open(d.db());
  std::vector<store::CaptureInfo> complete;
  for (const auto& cap : s.list_captures()) {
    if (cap.status == "complete") complete.push_back(cap);
    else EXPECT_EQ(cap.status, "incomplete");
  }
  ASSERT_EQ(complete.size(), 2u);
  EXPECT_EQ(complete[0].sample_count, 10000);
  EXPECT_NE(complete[0].stimulus.find("swept_sine"), std::string::npos);
  EXPECT_NE(complete[1].stimulus.find("torque_sweep"), std::string::npos);
  EXPECT_EQ(complete[1].sample_count, 5000);
}

}  // namespace
}  // namespace knoblab::hapticd
