#include "knoblab/sim/accelerometer.hpp"

#include <algorithm>
#include <cmath>

namespace knoblab::sim {

double AccelCalibration::gravity(double theta) const { return A * std::sin(theta / B + C) + D; }

Accelerometer::Accelerometer(const AccelerometerParams& p, const CameraOrientation& o) : p_(p) {
  cal_.C_cal = p_.C_cal;
  cal_.A = o.gravity_amplitude(p_.radius);
  cal_.B = 1.0;
  cal_.C = o.roll;
  cal_.D = p_.offset;
}

void Accelerometer::reset(double theta) { filtered_ = cal_.gravity(theta); }

void Accelerometer::track(double alpha, double theta, double h) {
  const double x = alpha + cal_.gravity(theta);
  if (p_.bandwidth_hz <= 0.0) {
    filtered_ = x;
    return;
  }
  if (h != last_h_) {  // exact first-order hold; exp() only when h changes
    coef_ = 1.0 - std::exp(-2.0 * std::numbers::pi * p_.bandwidth_hz * h);
    last_h_ = h;
  }
  filtered_ += (x - filtered_) * coef_;
}

double Accelerometer::sample(Rng& rng) const {
  const double fs = p_.full_scale();
  const double x = std::clamp(filtered_ + p_.noise_sigma() * rng.normal(), -fs, fs);
  return p_.adc.quantize(x / p_.C_cal);
}

}  // namespace knoblab::sim
