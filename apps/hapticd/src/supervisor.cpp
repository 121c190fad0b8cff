#include "knoblab/hapticd/supervisor.hpp"

#include <algorithm>
#include <cmath>

namespace knoblab::hapticd {

std::string fault_list(std::uint32_t faults) {
  std::string out;
  for (const FaultName& f : kFaultNames) {
    if ((faults & f.bit) == 0) continue;
    if (!out.empty()) out += ',';
    out += f.name;
  }
  return out;
}

bool Supervisor::apply(const SafetyInputs& in, capture::DaqOutputs& out) {
  std::uint32_t now = in.external_faults;
  if (in.estop) now |= kFaultEstop;
  if (std::abs(in.omega) > limits_.velocity_limit_rad_s) now |= kFaultVelocity;
  // NaN compares false with everything: |NaN| > limit and std::clamp would
  // both let it through, so non-finite values are a fault of their own.
  if (!std::isfinite(in.omega) || !in.sensors_finite || !std::isfinite(out.motor_command_V))
    now |= kFaultNonFinite;
  if (in.consecutive_overruns > limits_.max_consecutive_overruns) now |= kFaultOverruns;
  if (in.consecutive_io_errors >= limits_.max_consecutive_io_errors) now |= kFaultIo;
  if (in.tracking_lost) now |= kFaultTracking;

  // A clear succeeds only for causes that are gone; live causes stay latched.
  if (in.clear_requested) latched_ = 0;
  latched_ |= now;

  if (latched_ != 0) {
    out.motor_command_V = 0.0;
    out.amp_enable = false;
    return false;
  }
  const double limit_V = limits_.torque_limit_Nm / limits_.torque_per_volt;
  const double clipped = std::clamp(out.motor_command_V, -limit_V, limit_V);
  const bool limited = clipped != out.motor_command_V;
  out.motor_command_V = clipped;
  return limited;
}

}  // namespace knoblab::hapticd
