// What the UI derives from hapticd's replies, kept apart from Qt so it can
// be tested on its own: the loop rate measured from the cycle counter, and
// the status strip's reading of the fault list.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace knoblab::ui {

// The loop's rate as it runs: cycles counted between two get_state replies
// over the time between them (the configured rate_hz says what was asked
// for, this says the loop is turning). Smoothed over about a second.
class LoopRateMeter {
 public:
  // `cycles` from get_state, `seconds` a steady clock reading. Returns the
  // current estimate (nullopt until two readings a useful interval apart).
  std::optional<double> update(std::uint64_t cycles, double seconds);
  void reset() { last_.reset(), rate_.reset(); }

 private:
  struct Reading {
    std::uint64_t cycles;
    double seconds;
  };
  std::optional<Reading> last_;
  std::optional<double> rate_;
};

// The status strip's one-word readings of the fault list get_state gives.
struct FaultReading {
  bool estop = false;      // the e-stop line (pressed, or its circuit open)
  bool amplifier = false;  // the amplifier reports a fault or its link is lost
  std::vector<std::string> others;
};
FaultReading read_faults(const std::vector<std::string>& faults);

// get_state's `modbus`: the poller's status flags joined by '|' ("running",
// "running|amp-enabled", "running|biometrics-stale"; "ok" when no poller
// runs). The strip says "ok" while it runs without a problem, "off" without
// a poller, else the problems in words.
struct ModbusReading {
  bool ok = true;
  std::string text;
};
ModbusReading read_modbus(const std::string& status);

}  // namespace knoblab::ui
