// hapticd as a child process for end-to-end tests: the sim backend at a
// gentle rate, serving a socket in a scratch directory (and a telemetry
// ring when asked). Deadlines only bound a wait for an outcome.
#pragma once

#include <signal.h>
#include <sys/mman.h>

#include <chrono>
#include <exception>
#include <string>
#include <vector>

#include "knoblab/control/client.hpp"
#include "process.hpp"

namespace knoblab::test {

class Hapticd {
 public:
  // `extra` options come last, so they override (e.g. --daq-config FILE).
  explicit Hapticd(std::string telemetry_shm = {}, const std::vector<std::string>& extra = {})
      : telemetry_(std::move(telemetry_shm)) {
    // This host is not realtime: a run of late cycles must not latch the
    // overruns fault (it would send the daemon to idle mid-test).
    std::vector<std::string> args = {KNOBLAB_HAPTICD_PATH, "--backend", "sim",    "--knob",
                                     "moderate-detents",   "--rate",    "1000",   "--socket",
                                     socket(),             "--db",      (dir_ / "lab.sqlite").string(),
                                     "--max-overruns",     "1000000"};
    if (!telemetry_.empty()) args.insert(args.end(), {"--telemetry", telemetry_});
    args.insert(args.end(), extra.begin(), extra.end());
    pid_ = spawn(args, (dir_ / "hapticd.out").string(), (dir_ / "hapticd.err").string());
  }
  ~Hapticd() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      wait_exit(pid_, std::chrono::seconds(10));
    }
    if (!telemetry_.empty()) ::shm_unlink(telemetry_.c_str());
  }
  Hapticd(const Hapticd&) = delete;
  Hapticd& operator=(const Hapticd&) = delete;

  // Up and answering get_state.
  bool ready() const {
    return pid_ > 0 && eventually([&] {
             try {
               control::Client c(socket());
               return c.call("get_state").contains("mode");
             } catch (const std::exception&) {
               return false;
             }
           });
  }
  std::string socket() const { return (dir_ / "h.sock").string(); }
  std::string db() const { return (dir_ / "lab.sqlite").string(); }
  std::string dir() const { return dir_.path().string(); }
  std::string log() const { return read_file(dir_ / "hapticd.out") + read_file(dir_ / "hapticd.err"); }

 private:
  ScratchDir dir_;
  std::string telemetry_;
  pid_t pid_ = -1;
};

}  // namespace knoblab::test
