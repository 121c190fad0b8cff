// knoblab ctl end to end: the real hapticd (sim backend, a socket in a
// scratch directory) and the real knoblab process. Deadlines are generous and
// only bound a wait for an outcome; nothing asserts how long anything took.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/control/client.hpp"
#include "knoblab/control/schema.hpp"
#include "hapticd_process.hpp"
#include "process.hpp"

extern char** environ;

namespace knoblab::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;


RunResult ctl(const std::string& socket, std::vector<std::string> args) {
  args.insert(args.begin(), {"ctl", "--socket", socket});
  return run_knoblab(args);
}

json parse_stdout(const RunResult& r) {
  const json j = json::parse(r.out, nullptr, false);
  EXPECT_FALSE(j.is_discarded()) << "stdout is not JSON:\n" << r.out << "\nstderr:\n" << r.err;
  return j;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

// `knoblab ctl --watch …` in the background, its output in files.
class Watcher {
 public:
  Watcher(const std::string& socket, std::vector<std::string> extra) {
    std::vector<std::string> args = {KNOBLAB_CLI_PATH, "ctl", "--socket", socket, "--watch"};
    args.insert(args.end(), extra.begin(), extra.end());
    pid_ = spawn(args, out_path(), err_path());
  }
  ~Watcher() {
    if (pid_ > 0) wait_exit(pid_, 0ms);  // kills it if still running
  }
  // It has subscribed: it says so on stderr before it prints anything.
  bool subscribed() const {
    return pid_ > 0 && eventually([&] { return err().find("watching") != std::string::npos; });
  }
  std::optional<int> finish() {
    const auto code = wait_exit(pid_);
    pid_ = -1;
    return code;
  }
  void signal(int sig) const { ::kill(pid_, sig); }
  std::string out() const { return read_file(out_path()); }
  std::string err() const { return read_file(err_path()); }

 private:
  std::string out_path() const { return (dir_ / "out").string(); }
  std::string err_path() const { return (dir_ / "err").string(); }
  ScratchDir dir_;
  pid_t pid_ = -1;
};

// ---- without hapticd --------------------------------------------------------

TEST(Ctl, HelpListsEveryCommandOfTheProtocolSchema) {
  const RunResult r = run_knoblab({"ctl", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("usage: knoblab ctl"), std::string::npos) << r.out;
  for (const auto& c : control::command_table())
    EXPECT_NE(r.out.find("\n  " + std::string(control::to_string(c.command)) + " "), std::string::npos)
        << control::to_string(c.command) << " missing from:\n" << r.out;
  EXPECT_NE(r.out.find("swept_sine.a=NUM"), std::string::npos) << "nested keys are shown dotted:\n" << r.out;
  EXPECT_NE(r.out.find("mode=idle|render|capture|calibrate"), std::string::npos) << r.out;
}

TEST(Ctl, MissingSocketGivesAClearErrorAndExitThree) {
  ScratchDir dir;
  const std::string path = (dir / "nobody.sock").string();
  const RunResult r = ctl(path, {"get_state"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("no control socket at " + path), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("is hapticd running?"), std::string::npos) << r.err;
}

TEST(Ctl, SocketFileWithNobodyListeningGivesExitThree) {
  ScratchDir dir;
  const std::string path = (dir / "stale.sock").string();
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  ::close(fd);  // the file stays, nobody listens: a daemon that died
  const RunResult r = ctl(path, {"get_state"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("cannot reach hapticd"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(path), std::string::npos) << r.err;
}

TEST(Ctl, UsageErrorsExitTwoBeforeAnyConnection) {
  ScratchDir dir;
  const std::string nowhere = (dir / "nobody.sock").string();  // exit 3 would mean it tried to connect
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{}, "name a COMMAND"},
      {{"set_mode", "mode"}, "expected key=value, got 'mode'"},
      {{"get_state", "a=1", "a=2"}, "'a' is given twice"},
      {{"start_capture", "pid=1", "pid.Kp=2"}, "not an object"},
      {{"start_capture", "pid..Kp=2"}, "a key part is empty"},
      {{"--json", "{oops"}, "not valid JSON"},
      {{"--json", R"({"command": "get_state", "extra": 1})"}, "unknown key 'extra'"},
      {{"--json", R"({"command": "get_state"})", "x=1"}, "--json carries the whole request"},
      {{"--count", "2", "get_state"}, "go with --watch"},
      {{"--watch", "--count", "0"}, "--count wants a positive integer"},
      {{"--watch", "--events", ","}, "--events wants"},
  };
  for (const auto& [args, message] : cases) {
    const RunResult r = ctl(nowhere, args);
    EXPECT_EQ(r.exit_code, 2) << message << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
}

// ---- against hapticd ----------------------------------------------------------

TEST(Ctl, GetStatePrintsTheDaemonsStateAsJson) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  const RunResult r = ctl(d.socket(), {"get_state"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const json state = parse_stdout(r);
  EXPECT_EQ(state.value("mode", ""), "idle") << r.out;
  EXPECT_TRUE(state.contains("faults")) << r.out;
}

TEST(Ctl, KnoblabSocketEnvironmentVariableNamesTheSocket) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  ::setenv("KNOBLAB_SOCKET", d.socket().c_str(), 1);
  const RunResult r = run_knoblab({"ctl", "get_state"});
  ::unsetenv("KNOBLAB_SOCKET");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(parse_stdout(r).value("mode", ""), "idle");
}

TEST(Ctl, KeyValueArgumentsReachTheDaemon) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  RunResult r = ctl(d.socket(), {"load_model", "M_acc=1.3e-5", "B_vel=2e-4", "A_pos=0.01", "P_pos=0.05"});
  EXPECT_EQ(r.exit_code, 0) << "numbers must travel as numbers: " << r.err;
  r = ctl(d.socket(), {"set_mode", "mode=render"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = ctl(d.socket(), {"get_state"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(parse_stdout(r).value("mode", ""), "render") << r.out;
}

TEST(Ctl, APrototyperDesignTravelsAsTilesAndABadCurveIsRefusedByItsPath) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  const std::string bump = R"([{"theta_min":-3.1416,"theta_max":3.1416,"f_vel":{"x":[-3.1416,0,3.1416],"y":[0.0005,0.002,0.0005]}}])";
  RunResult r = ctl(d.socket(), {"load_tiles", "position=" + bump});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(parse_stdout(r)["position"], 1) << r.out;
  r = ctl(d.socket(), {"get_state"});
  EXPECT_EQ(parse_stdout(r)["tiles"]["position"], 1) << r.out;
  const std::string backwards = R"([{"theta_min":0,"theta_max":1,"f_vel":{"x":[1,0],"y":[0.001,0.001]}}])";
  r = ctl(d.socket(), {"load_tiles", "position=" + backwards});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("position[0].f_vel"), std::string::npos) << r.err;
  r = ctl(d.socket(), {"get_state"});
  EXPECT_EQ(parse_stdout(r)["tiles"]["position"], 1) << "a refused set leaves the loaded one: " << r.out;
}

TEST(Ctl, DottedKeysBuildNestedObjects) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  // An out-of-range nested value: hapticd names the nested key and its range,
  // which it can only do if swept_sine arrived as an object (a flat
  // "swept_sine.c" key would be refused as unknown).
  const RunResult r = ctl(d.socket(), {"start_capture", "swept_sine.a=0", "swept_sine.b=1.5", "swept_sine.c=99",
                                       "swept_sine.d=3", "seconds=0.2", "knob=ctl-test"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad_args"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'swept_sine.c' must be in"), std::string::npos) << r.err;
}

TEST(Ctl, JsonOptionSendsTheRequestAsGiven) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  RunResult r = ctl(d.socket(), {"--json", R"({"command": "set_mode", "args": {"mode": "render"}})"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = ctl(d.socket(), {"get_state"});
  EXPECT_EQ(parse_stdout(r).value("mode", ""), "render") << r.out;
}

TEST(Ctl, ErrorReplyExitsOneWithTheDaemonsError) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  RunResult r = ctl(d.socket(), {"frobnicate"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("frobnicate: unknown_command"), std::string::npos) << r.err;
  r = ctl(d.socket(), {"set_mode", "mode=sideways"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad_args"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'mode'"), std::string::npos) << r.err;
}

TEST(Ctl, WatchPrintsEventsAsJsonLinesAfterAStateChange) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  Watcher w(d.socket(), {"--events", "state", "--count", "2"});
  ASSERT_TRUE(w.subscribed()) << w.err();
  ASSERT_EQ(ctl(d.socket(), {"set_mode", "mode=render"}).exit_code, 0);
  // The daemon reports changes, not every mode it passed through: wait for
  // the first before making the second.
  ASSERT_TRUE(eventually([&] { return !w.out().empty(); })) << w.err() << d.log();
  ASSERT_EQ(ctl(d.socket(), {"set_mode", "mode=idle"}).exit_code, 0);
  EXPECT_EQ(w.finish(), 0) << w.err();
  const auto lines = lines_of(w.out());
  ASSERT_EQ(lines.size(), 2u) << w.out();
  for (const auto& line : lines) {
    const json j = json::parse(line, nullptr, false);
    ASSERT_TRUE(j.is_object()) << line;
    EXPECT_EQ(j.value("event", ""), "state") << line;
    EXPECT_TRUE(j["data"].contains("mode")) << line;
  }
  EXPECT_EQ(json::parse(lines[0])["data"]["mode"], "render") << lines[0];
}

TEST(Ctl, ATrialIsAnnouncedWhenItStartsAndStopsAndStoredWithItsMetadata) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  Watcher w(d.socket(), {"--events", "trial,stats", "--count", "3"});
  ASSERT_TRUE(w.subscribed()) << w.err();
  ASSERT_EQ(ctl(d.socket(), {"start_trial", "study=S1", "participant=7", "condition=detents-12"}).exit_code, 0);
  const RunResult again = ctl(d.socket(), {"start_trial", "study=S1", "participant=7", "condition=x"});
  EXPECT_EQ(again.exit_code, 1) << again.err;  // one recording at a time
  std::this_thread::sleep_for(300ms);
  ASSERT_EQ(ctl(d.socket(), {"stop_trial"}).exit_code, 0);
  ASSERT_TRUE(eventually([&] { return w.out().find("\"stopped\"") != std::string::npos; })) << w.out() << d.log();
  EXPECT_EQ(ctl(d.socket(), {"stop_trial"}).exit_code, 1);  // none running now
  // Loop statistics arrive once a second.
  EXPECT_TRUE(eventually([&] { return w.out().find("\"stats\"") != std::string::npos; })) << w.out();
  w.signal(SIGTERM);
  w.finish();
  json started, stopped;
  bool stats = false;
  std::string last_stats;
  for (const auto& line : lines_of(w.out())) {
    const json j = json::parse(line, nullptr, false);
    ASSERT_TRUE(j.is_object()) << line;
    if (j.value("event", "") == "stats") {
      // The wake-up histogram counts the timed cycles on doubling bins (none
      // yet when the loop has not published its first statistics).
      const json& h = j["data"]["wakeup_histogram_us"];
      std::uint64_t counted = 0;
      for (const auto& c : h["counts"]) counted += c.get<std::uint64_t>();
      const auto cycles = j["data"]["cycles"].get<std::uint64_t>();
      stats = h["counts"].size() == h["upper"].size() + 1 && h["upper"][0] == 1.0 && counted <= cycles &&
              (cycles < 2 || counted > 0);
      last_stats = j["data"].dump();
    }
    if (j.value("event", "") != "trial") continue;
    (j["data"]["state"] == "started" ? started : stopped) = j["data"];
  }
  EXPECT_TRUE(stats) << last_stats;
  ASSERT_TRUE(started.is_object()) << w.out();
  EXPECT_EQ(started["trial"]["study"], "S1");
  EXPECT_EQ(started["trial"]["participant"], 7);
  ASSERT_TRUE(stopped.is_object()) << w.out();
  EXPECT_EQ(stopped["trial"]["condition"], "detents-12");
  EXPECT_TRUE(stopped.value("complete", false)) << stopped.dump();
  EXPECT_GT(stopped.value("samples", 0), 100);  // 0.3 s at 1 kHz

  // The store row carries the trial's metadata.
  const RunResult exported = run_knoblab({"export", std::to_string(stopped.value("capture_id", 0)), "--db",
                                          d.db(), "--out", d.db() + ".csv"});
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const std::string csv = read_file(d.db() + ".csv");
  EXPECT_NE(csv.find("S1"), std::string::npos) << csv.substr(0, 600);
  EXPECT_NE(csv.find("detents-12"), std::string::npos) << csv.substr(0, 600);
}

TEST(Ctl, WatchEndsCleanlyOnSigintAndSigterm) {
  Hapticd d;
  ASSERT_TRUE(d.ready()) << d.log();
  for (const int sig : {SIGINT, SIGTERM}) {
    Watcher w(d.socket(), {});
    ASSERT_TRUE(w.subscribed()) << w.err();
    w.signal(sig);
    EXPECT_EQ(w.finish(), 0) << strsignal(sig) << ": " << w.err();
  }
}

TEST(Ctl, WatchWithTelemetryPrintsTheRingsRecords) {
  const std::string shm = "/knoblab-ctl-test-" + std::to_string(::getpid());
  Hapticd d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  Watcher w(d.socket(), {"--events", "fault_latched", "--telemetry", "--count", "5"});
  EXPECT_EQ(w.finish(), 0) << w.err() << d.log();
  const auto lines = lines_of(w.out());
  ASSERT_EQ(lines.size(), 5u) << w.out();
  for (const auto& line : lines) {
    const json j = json::parse(line, nullptr, false);
    ASSERT_TRUE(j.is_object()) << line;
    if (j.contains("event") || j.contains("telemetry_lost")) continue;  // a fault or a lap: allowed
    ASSERT_TRUE(j.contains("telemetry")) << line;
    for (const char* key : {"seq", "t", "theta", "omega", "torque", "mode", "fault_bits"})
      EXPECT_TRUE(j["telemetry"].contains(key)) << key << " missing: " << line;
  }
  EXPECT_NE(w.err().find(shm), std::string::npos) << "names the ring it reads: " << w.err();
}

}  // namespace
}  // namespace knoblab::test
