#include "knoblab/sim/amplifier.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace knoblab::sim {

Amplifier::Amplifier(const AmplifierParams& p, const MotorParams& m) : p_(p), m_(m) {
  // Pole–zero cancellation: PI zero on the winding pole R/L leaves a
  // first-order closed loop at the requested bandwidth.
  const double wc = 2.0 * std::numbers::pi * p_.current_bandwidth_hz;
  kp_ = m_.L * wc;
  ki_ = m_.R * wc;
}

void Amplifier::reset() {
  i_ = v_ = integral_ = mean_sq_ = 0.0;
  folded_ = false;
}

double Amplifier::rms() const { return std::sqrt(mean_sq_); }

double Amplifier::limit() const { return folded_ ? p_.continuous_current : p_.peak_current; }

double Amplifier::current_mode(double command, double omega, double h) {
  const double lim = limit();
  const double i_ref = std::clamp(command * amps_per_volt(), -lim, lim);
  // PI and winding solved together, implicitly in the new current, so the
  // loop is stable for any substep.
  const double lh = m_.L / h;
  double i = (lh * i_ + kp_ * i_ref + integral_ - m_.K * omega) / (lh + kp_ + m_.R);
  double v = kp_ * (i_ref - i) + integral_;
  if (std::abs(v) > p_.bus_voltage) {
    // Saturated: the bus voltage is all there is; the integrator holds
    // (conditional integration, no wind-up).
    v = std::clamp(v, -p_.bus_voltage, p_.bus_voltage);
    i = m_.winding_step(i_, v, omega, h);
  } else {
    integral_ += ki_ * (i_ref - i) * h;
  }
  v_ = v;
  return i;
}

double Amplifier::step(double command_volts, double motor_omega, double h) {
  const double command = std::clamp(command_volts, -p_.dac_range, p_.dac_range);
  double i = 0.0;
  if (p_.mode == AmpMode::Current) {
    i = current_mode(command, motor_omega, h);
  } else {
    v_ = std::clamp(command, -p_.bus_voltage, p_.bus_voltage);
    i = m_.winding_step(i_, v_, motor_omega, h);
  }
  const double lim = limit();
  if (std::abs(i) > lim) {
    i = std::clamp(i, -lim, lim);
    v_ = m_.L * (i - i_) / h + m_.R * i + m_.K * motor_omega;  // what the limiter applied
  }
  i_ = i;

  const double a = std::min(1.0, h / p_.rms_time_constant);
  mean_sq_ += (i_ * i_ - mean_sq_) * a;
  const double ic = p_.continuous_current;
  if (mean_sq_ > ic * ic) {
    folded_ = true;
  } else if (folded_ && mean_sq_ < (p_.release_fraction * ic) * (p_.release_fraction * ic)) {
    folded_ = false;
  }
  return i_;
}

}  // namespace knoblab::sim
