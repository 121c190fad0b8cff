#include "knoblab/capture/capture_controller.hpp"

#include <algorithm>
#include <cmath>

namespace knoblab::capture {

double TrackingLimits::threshold_rad(double amplitude_rad) const {
  return std::max(fraction * std::abs(amplitude_rad), floor_rad);
}

CaptureController::CaptureController(const CaptureConfig& cfg)
    : cfg_(cfg),
      pid_(cfg.pid),
      threshold_rad_(cfg.tracking.threshold_rad(cfg.stimulus.c)),
      hold_cycles_(std::max(1LL, std::llround(cfg.tracking.hold_s * cfg.rate_hz))) {}

void CaptureController::update(const SensorReading& in, DaqOutputs& out, Sample& s) {
  const double dt = 1.0 / cfg_.rate_hz;
  const double t = static_cast<double>(cycle_) * dt;
  s.t = t;
  s.theta = in.theta;
  s.omega = in.omega;
  s.alpha = in.alpha;
  s.torque = in.torque;

  if (cfg_.kind == CaptureConfig::Stimulus::Torque) {
    // Open loop: the motor applies τ(t); the knob's response is the record.
    s.command = std::clamp(cfg_.torque_stimulus.torque(t) / cfg_.torque_per_volt, -cfg_.pid.limit_V,
                           cfg_.pid.limit_V);
  } else {
    // The sweep is centred where the knob stands when the capture starts:
    // an absolute reference would first throw the knob back to zero as hard
    // as the PID can (and trip the velocity limit at a slow loop's gains).
    if (cycle_ == 0) theta0_ = in.theta;
    const double ref = theta0_ + cfg_.stimulus.theta(t);
    const double ref_omega = cfg_.stimulus.omega(t);
    s.command = pid_.update(ref, ref_omega, s.theta, s.omega, dt);
    // NaN never counts as off here: the supervisor's non_finite has it.
    off_cycles_ = std::abs(ref - s.theta) > threshold_rad_ ? off_cycles_ + 1 : 0;
    if (off_cycles_ >= hold_cycles_) tracking_lost_ = true;
  }
  out.motor_command_V = s.command;
  out.amp_enable = true;
  ++cycle_;
}

}  // namespace knoblab::capture
