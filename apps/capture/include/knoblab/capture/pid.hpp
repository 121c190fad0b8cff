// The Haptic Camera's position controller (thesis §1.7, Eq. 4):
//   D(s) = (Kd·s² + Kp·s + Ki) / s,   command volts = D(s)·(θ_ref − θ)
// Defaults are the thesis' root-locus design: Kp = 200 V/rad,
// Ki = 5000 V/(rad·s), Kd = 1.0 V·s/rad. The derivative acts on the velocity
// error (ω_ref is known exactly from the trajectory), and the integrator stops
// while the output is saturated in the same direction (anti-windup).
#pragma once

#include <algorithm>

namespace knoblab::capture {

struct PidGains {
  double Kp = 200.0;
  double Ki = 5000.0;
  double Kd = 1.0;
  double limit_V = 12.0;  // DAC range of the amplifier command
};

class Pid {
 public:
  explicit Pid(PidGains gains = {}) : g_(gains) {}

  void reset() { integral_ = 0.0; }
  const PidGains& gains() const { return g_; }

  // One control period dt (s). Returns the saturated command in volts.
  double update(double theta_ref, double omega_ref, double theta, double omega, double dt) {
    const double e = theta_ref - theta;
    const double unsat = g_.Kp * e + g_.Ki * integral_ + g_.Kd * (omega_ref - omega);
    const double out = std::clamp(unsat, -g_.limit_V, g_.limit_V);
    const bool pushing_further = (out >= g_.limit_V && e > 0) || (out <= -g_.limit_V && e < 0);
    if (!pushing_further) integral_ += e * dt;
    return out;
  }

 private:
  PidGains g_;
  double integral_ = 0.0;
};

}  // namespace knoblab::capture
