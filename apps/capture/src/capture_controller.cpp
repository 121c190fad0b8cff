#include "knoblab/capture/capture_controller.hpp"

#include <algorithm>

namespace knoblab::capture {

namespace {
double velocity_cutoff(const CaptureConfig& cfg) {
  // Keep the cutoff well below Nyquist so slow loop rates stay well defined.
  return std::min(cfg.velocity_cutoff_hz, 0.2 * cfg.rate_hz);
}
}  // namespace

CaptureController::CaptureController(const CaptureConfig& cfg)
    : cfg_(cfg),
      pid_(cfg.pid),
      velocity_filter_(model::design_butterworth_lowpass(cfg.velocity_filter_order,
                                                         velocity_cutoff(cfg), cfg.rate_hz)) {}

void CaptureController::update(const DaqInputs& in, DaqOutputs& out, Sample& s) {
  const double dt = 1.0 / cfg_.rate_hz;
  const double t = static_cast<double>(cycle_) * dt;
  const SensorCalibration& cal = cfg_.calibration;

  s.t = t;
  s.theta = cal.theta(in.encoder_counts);
  // Eq. 1: backward difference; the first cycle has no predecessor.
  const double raw_omega = cycle_ == 0 ? 0.0 : (s.theta - prev_theta_) / dt;
  prev_theta_ = s.theta;
  s.omega = velocity_filter_.process(raw_omega);
  s.alpha = cal.alpha(in.accel_V, s.theta);
  s.torque = cal.torque(in.torque_V);

  if (cfg_.kind == CaptureConfig::Stimulus::Torque) {
    // Open loop: the motor applies τ(t); the knob's response is the record.
    s.command = std::clamp(cfg_.torque_stimulus.torque(t) / cfg_.torque_per_volt, -cfg_.pid.limit_V,
                           cfg_.pid.limit_V);
  } else {
    const double ref = cfg_.stimulus.theta(t);
    const double ref_omega = cfg_.stimulus.omega(t);
    s.command = pid_.update(ref, ref_omega, s.theta, s.omega, dt);
  }
  out.motor_command_V = s.command;
  out.amp_enable = true;
  ++cycle_;
}

}  // namespace knoblab::capture
