// hapticd's configuration file as a process sees it: a modbus section that
// really supervises the amplifier (against knoblab-modbus-sim over TCP,
// watched with knoblab ctl), and configurations that must not start.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "process.hpp"

namespace knoblab::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

struct Started {
  std::optional<int> exit_code;
  std::string err;
};

// hapticd with these arguments, expected to refuse them and stop.
Started hapticd_refusing(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), KNOBLAB_HAPTICD_PATH);
  const pid_t pid = spawn(args, (dir / "out").string(), (dir / "err").string());
  Started s;
  s.exit_code = wait_exit(pid, 10s);
  s.err = read_file(dir / "err");
  return s;
}

TEST(HapticdConfig, AnUnknownTopLevelKeyIsRefusedByNameWithExitTwo) {
  ScratchDir dir;
  write_file(dir / "h.json", R"({"daq": {"backend": "sim", "knob": "subtle-detents"}, "modbs": {}})");
  const Started s = hapticd_refusing(dir, {"--config", (dir / "h.json").string(), "--cycles", "10"});
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.err.find("unknown top-level key \"modbs\""), std::string::npos) << s.err;
}

TEST(HapticdConfig, AMistypedModbusSettingIsRefusedWithItsPath) {
  ScratchDir dir;
  write_file(dir / "h.json", R"({"modbus": {"amplifier": {"transport": "tcp", "host": "127.0.0.1", "prot": 1502}}})");
  const Started s = hapticd_refusing(dir, {"--config", (dir / "h.json").string(), "--cycles", "10"});
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.err.find("modbus.amplifier.prot"), std::string::npos) << s.err;
}

// "--rate 1000abc" once ran at 1 kHz and "--modbus HOST:99999" polled port
// 34463: an option is read whole and in range, or refused naming it.
TEST(HapticdConfig, ANumberOptionWithTrailingTextOrOutOfRangeIsRefusedNamingIt) {
  ScratchDir dir;
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--rate", "1000abc"}, "--rate wants a number, got '1000abc'"},
      {{"--rate", "0"}, "--rate must be in"},
      {{"--rate", "nan"}, "--rate wants a number"},
      {{"--modbus", "127.0.0.1:99999"}, "--modbus's port must be in 1 … 65535, got 99999"},
      {{"--modbus", "127.0.0.1:15o2"}, "--modbus's port wants an integer, got '15o2'"},
      {{"--modbus", ":1502"}, "--modbus wants HOST:PORT"},
      {{"--priority", "120"}, "--priority must be in 1 … 99"},
      {{"--cpu", "1x"}, "--cpu wants an integer"},
      {{"--max-overruns", "0"}, "--max-overruns must be in 1 …"},
      {{"--cycles", "10.5"}, "--cycles wants an integer"},
  };
  for (const auto& [args, said] : cases) {
    std::vector<std::string> all = args;
    if (args[0] != "--cycles") all.insert(all.end(), {"--cycles", "10"});
    const Started s = hapticd_refusing(dir, all);
    EXPECT_EQ(s.exit_code, 2) << args[0] << " " << args[1];
    EXPECT_NE(s.err.find(said), std::string::npos) << args[0] << " " << args[1] << ": " << s.err;
  }
}

TEST(HapticdConfig, ARealDaqWithInMemoryLinesIsRefusedUnlessAllowed) {
  ScratchDir dir;
  const std::vector<std::string> comedi = {"--backend", "comedi", "--cycles", "10"};
  const Started refused = hapticd_refusing(dir, comedi);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("no e-stop input"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--allow-memory-lines"), std::string::npos) << refused.err;

  // Allowed, it goes on to the DAQ itself (here a board that is not there).
  std::vector<std::string> allowed = comedi;
  allowed.insert(allowed.end(), {"--daq-config", (dir / "daq.json").string(), "--allow-memory-lines"});
  write_file(dir / "daq.json", R"({"backend": "comedi", "device": "/dev/comedi-absent",
    "torque": {"channel": 0}, "accel": {"channel": 1}, "motor": {"channel": 0}, "encoder": {"channel": 0}})");
  const Started s = hapticd_refusing(dir, allowed);
  EXPECT_NE(s.exit_code, 0);
  EXPECT_EQ(s.err.find("no e-stop input"), std::string::npos) << s.err;
  EXPECT_NE(s.err.find("/dev/comedi-absent"), std::string::npos) << s.err;
}

// Acceptance: hapticd started with only --config (as the systemd unit starts
// it) supervises the amplifier through the file's modbus section.
TEST(HapticdConfig, TheModbusSectionSupervisesTheAmplifierAsSeenThroughKnoblabCtl) {
  ScratchDir dir;
  // The amplifier reports over-temperature 6 s after the simulator starts.
  const pid_t sim = spawn({KNOBLAB_MODBUS_SIM_PATH, "--port", "0", "--fault", "amp-fault-after=6:over-temperature"},
                          (dir / "sim.out").string(), (dir / "sim.err").string());
  ASSERT_GT(sim, 0);
  int port = 0;
  ASSERT_TRUE(eventually([&] {
    const std::string out = read_file(dir / "sim.out");
    const auto colon = out.rfind(':');
    if (out.find("listening") == std::string::npos || colon == std::string::npos) return false;
    port = std::stoi(out.substr(colon + 1));
    return true;
  })) << read_file(dir / "sim.err");

  // Watchdogs as on the appliance would trip on a busy CI host; the rule
  // (timeout + period below the watchdog) still holds.
  const json config = {
      {"daq", {{"backend", "sim"}, {"knob", "moderate-detents"}}},
      {"lines", {{"backend", "memory"}, {"estop", "released"}}},
      {"modbus",
       {{"amplifier", {{"transport", "tcp"}, {"host", "127.0.0.1"}, {"port", port}, {"unit", 1}}},
        {"biometrics", {{"transport", "tcp"}, {"host", "127.0.0.1"}, {"port", port}, {"unit", 2}}},
        {"comms_timeout_ms", 400},
        {"biometrics_timeout_ms", 400}}}};
  write_file(dir / "hapticd.json", config.dump(2));
  const std::string socket = (dir / "h.sock").string();
  const pid_t hapticd = spawn({KNOBLAB_HAPTICD_PATH, "--config", (dir / "hapticd.json").string(), "--rate", "1000",
                               "--socket", socket},
                              (dir / "hapticd.out").string(), (dir / "hapticd.err").string());
  ASSERT_GT(hapticd, 0);
  auto state = [&]() -> json {
    const RunResult r = run_knoblab({"ctl", "--socket", socket, "get_state"});
    if (r.exit_code != 0) return json::object();
    return json::parse(r.out, nullptr, false);
  };
  auto faults_hold = [&](const char* name) {
    const json s = state();
    if (!s.is_object() || !s.contains("faults")) return false;
    for (const auto& f : s["faults"])
      if (f == name) return true;
    return false;
  };

  // The poller reads the amplifier: the status names it running, enabled or not.
  ASSERT_TRUE(eventually([&] {
    const json s = state();
    return s.is_object() && s.value("modbus", std::string()).find("amp-comms-lost") == std::string::npos &&
           s.contains("mode");
  })) << read_file(dir / "hapticd.err");

  EXPECT_TRUE(eventually(
      [&] { return faults_hold("amplifier"); }, 30s))
      << state().dump() << read_file(dir / "hapticd.err");

  ::kill(sim, SIGKILL);  // the amplifier's link is gone
  wait_exit(sim, 5s);
  EXPECT_TRUE(eventually([&] { return faults_hold("amp_comms"); }))
      << state().dump() << read_file(dir / "hapticd.err");

  ::kill(hapticd, SIGTERM);
  EXPECT_EQ(wait_exit(hapticd, 10s), 0) << read_file(dir / "hapticd.err");
}

}  // namespace
}  // namespace knoblab::test
