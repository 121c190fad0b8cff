// The knoblab-modbus-sim program as a separate process: it reports its
// ephemeral port, runs its command-line faults, obeys the control registers
// and exits by itself (--duration), so nothing outlives the test.
#include <gtest/gtest.h>

#include <modbus.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <optional>
#include <string>
#include <vector>

#include "knoblab/modbus/poller.hpp"
#include "knoblab/modbus/register_map.hpp"
#include "support.hpp"

extern char** environ;

namespace knoblab::modbus {
namespace {

using namespace test;

// A child process with its stdout on a pipe; killed and reaped on destruction.
class SimProcess {
 public:
  explicit SimProcess(const std::vector<std::string>& args) {
    int out[2];
    if (pipe(out) != 0) return;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    std::vector<std::string> all{KNOBLAB_MODBUS_SIM_PATH};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    out_ = out[0];
  }
  ~SimProcess() {
    if (pid_ > 0 && !exit_code(0ms)) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (out_ != -1) ::close(out_);
  }

  // The first stdout line, within timeout.
  std::optional<std::string> line(std::chrono::milliseconds timeout) {
    std::string s;
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      pollfd p{out_, POLLIN, 0};
      if (poll(&p, 1, 10) <= 0) continue;
      char ch = 0;
      if (read(out_, &ch, 1) != 1) return std::nullopt;
      if (ch == '\n') return s;
      s += ch;
    }
    return std::nullopt;
  }

  // Exit status once it has exited (within timeout).
  std::optional<int> exit_code(std::chrono::milliseconds timeout) {
    if (exited_) return code_;
    const auto deadline = Clock::now() + timeout;
    do {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        return code_;
      }
      std::this_thread::sleep_for(5ms);
    } while (Clock::now() < deadline);
    return std::nullopt;
  }

  void terminate() { kill(pid_, SIGTERM); }
  bool started() const { return pid_ > 0; }

 private:
  pid_t pid_ = -1;
  int out_ = -1;
  bool exited_ = false;
  int code_ = 0;
};

std::uint16_t port_of(const std::string& line) {
  const std::string prefix = "listening 127.0.0.1:";
  if (line.rfind(prefix, 0) != 0) return 0;
  return static_cast<std::uint16_t>(std::stoi(line.substr(prefix.size())));
}

TEST(SimProcess, CommandLineFaultsControlRegistersAndSelfExit) {
  SimProcess sim({"--port", "0", "--seed", "7", "--duration", "6",
                  "--fault", "amp-fault-after=0.6:over-temperature",
                  "--fault", "stale-after=1.2:bio"});
  ASSERT_TRUE(sim.started());
  const auto line = sim.line(5s);
  ASSERT_TRUE(line) << "no 'listening' line";
  const std::uint16_t port = port_of(*line);
  ASSERT_NE(port, 0) << *line;
  const auto started = Clock::now();

  std::atomic<int> samples{0};
  PollerConfig c = local_config(port);
  c.on_sample = [&](const BiometricSample&) { ++samples; };
  Poller poller(c);
  poller.start();
  ASSERT_TRUE(wait_for([&] { return (poller.status() & status::kProblemMask) == 0; }, 2s))
      << status::describe(poller.status());

  // --fault amp-fault-after=0.6: not before, and within ~100 ms after.
  ASSERT_TRUE(wait_for([&] { return has(poller.status(), status::kAmpFault); }, 2s));
  const auto fault_at = Clock::now() - started;
  EXPECT_GE(fault_at, 550ms);
  EXPECT_LE(fault_at, 800ms);
  EXPECT_EQ(poller.amplifier()->faults, amp::fault::kOverTemperature);

  // --fault stale-after=1.2 freezes the box: stale, not lost.
  ASSERT_TRUE(wait_for([&] { return has(poller.status(), status::kBiometricsStale); }, 2s));
  EXPECT_GE(Clock::now() - started, 1200ms);
  EXPECT_FALSE(has(poller.status(), status::kBiometricsLost));
  EXPECT_GT(samples.load(), 20);

  // Runtime control over TCP: exceptions for the biometrics unit.
  modbus_t* ctl = modbus_new_tcp("127.0.0.1", port);
  ASSERT_EQ(modbus_connect(ctl), 0);
  modbus_set_slave(ctl, kDefaultSimControlUnit);
  EXPECT_EQ(modbus_write_register(ctl, simctl::kBioException, MODBUS_EXCEPTION_GATEWAY_TARGET), 1);
  modbus_close(ctl);
  modbus_free(ctl);
  ASSERT_TRUE(wait_for([&] { return has(poller.status(), status::kBiometricsException); }, 500ms));
  poller.stop();

  sim.terminate();
  const auto code = sim.exit_code(2s);
  ASSERT_TRUE(code);
  EXPECT_EQ(*code, 0);
}

TEST(SimProcess, ExitsByItselfAfterDuration) {
  SimProcess sim({"--port", "0", "--duration", "0.3"});
  ASSERT_TRUE(sim.line(5s));
  const auto code = sim.exit_code(3s);
  ASSERT_TRUE(code) << "still running after --duration";
  EXPECT_EQ(*code, 0);
}

TEST(SimProcess, BadFaultSpecIsAUsageError) {
  SimProcess sim({"--port", "0", "--duration", "1", "--fault", "meltdown=now"});
  const auto code = sim.exit_code(3s);
  ASSERT_TRUE(code);
  EXPECT_EQ(*code, 2);
}

}  // namespace
}  // namespace knoblab::modbus
