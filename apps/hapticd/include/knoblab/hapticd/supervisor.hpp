// Safety first: every cycle, after the active mode has computed its outputs,
// the supervisor may override them. Any fault puts the motor in the safe state
// — zero torque command and amplifier disabled — in that same cycle, and the
// fault latches until a clear request arrives while its cause is gone.
#pragma once

#include <cstdint>
#include <string>

#include "knoblab/capture/daq.hpp"

namespace knoblab::hapticd {

// Why the supervisor holds the safe state (bits; several may be set).
enum Fault : std::uint32_t {
  kFaultNone = 0,
  kFaultEstop = 1u << 0,          // e-stop line asserted (or its cable pulled)
  kFaultAmplifier = 1u << 1,      // amplifier reports a fault over Modbus
  kFaultAmpComms = 1u << 2,       // amplifier not answering over Modbus
  kFaultWatchdog = 1u << 3,       // the supervising client went silent
  kFaultOverruns = 1u << 4,       // too many consecutive loop overruns
  kFaultVelocity = 1u << 5,       // knob faster than the velocity limit
  kFaultCommanded = 1u << 6,      // a client asked for the safe state
  kFaultIo = 1u << 7,             // DAQ or GPIO reads/writes failed several cycles running
  kFaultNonFinite = 1u << 8,      // NaN or ±Inf in a command or the estimated velocity
  kFaultRecording = 1u << 9,      // a capture could not be stored: it stops, the motor goes safe
  kFaultTracking = 1u << 10,      // a position capture lost the knob (capture_controller.hpp)
};

// Each fault's name in the protocol, the store and logs: the one table.
struct FaultName {
  Fault bit;
  const char* name;
};
inline constexpr FaultName kFaultNames[] = {
    {kFaultEstop, "estop"},         {kFaultAmplifier, "amplifier"}, {kFaultAmpComms, "amp_comms"},
    {kFaultWatchdog, "watchdog"},   {kFaultOverruns, "overruns"},   {kFaultVelocity, "velocity"},
    {kFaultCommanded, "commanded"}, {kFaultIo, "io"},               {kFaultNonFinite, "non_finite"},
    {kFaultRecording, "recording"}, {kFaultTracking, "tracking"}};

// "estop,velocity" ("" for none), in kFaultNames order.
std::string fault_list(std::uint32_t faults);

struct SafetyLimits {
  double torque_limit_Nm = 0.180;      // continuous (thesis §5.2.3: 180 mN·m)
  double velocity_limit_rad_s = 50.0;  // ≈ 8 rev/s: far above any hand or stimulus
  int max_consecutive_overruns = 10;
  // This many cycles running with a failed DAQ or GPIO read/write latch `io`:
  // one glitch is tolerated, a dead encoder (frozen angle, velocity 0, the
  // velocity limit blind) is not.
  int max_consecutive_io_errors = 3;
  double torque_per_volt = 0.181 / 12.0;  // to turn the torque limit into volts
};

// What the world says this cycle.
struct SafetyInputs {
  bool estop = false;
  std::uint32_t external_faults = 0;  // kFaultAmplifier / kFaultAmpComms / kFaultWatchdog …
  double omega = 0.0;                 // rad/s
  bool sensors_finite = true;         // θ, α and torque of this cycle are all finite
  int consecutive_overruns = 0;
  int consecutive_io_errors = 0;      // cycles running with a failed read or write
  bool tracking_lost = false;         // the running capture no longer follows its sweep
  bool clear_requested = false;
};

class Supervisor {
 public:
  explicit Supervisor(const SafetyLimits& limits = {}) : limits_(limits) {}

  // Applies the limits to `out` in place. Returns true when the command had
  // to be clipped to the torque limit.
  bool apply(const SafetyInputs& in, capture::DaqOutputs& out);

  std::uint32_t latched() const { return latched_; }
  bool safe_state() const { return latched_ != 0; }
  const SafetyLimits& limits() const { return limits_; }

 private:
  SafetyLimits limits_;
  std::uint32_t latched_ = 0;
};

}  // namespace knoblab::hapticd
