#include "knoblab/model/trajectory.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace knoblab::model {

namespace {
constexpr double kPi = std::numbers::pi;
}

double ChirpPhase::phase(double t) const noexcept {
  const double u = (b - a) * t / d + a;
  return kPi * t * (u + a) / d;
}

double ChirpPhase::rate(double t) const noexcept {
  const double u = (b - a) * t / d + a;
  return 2.0 * kPi * u / d;
}

double ChirpPhase::rate_dot() const noexcept { return 2.0 * kPi * (b - a) / (d * d); }

// Frequency u/d Hz means a = f·d.
SweptSine SweptSine::from_hz(double f_start_hz, double f_end_hz, double amplitude_rad,
                             double duration_s) {
  return {f_start_hz * duration_s, f_end_hz * duration_s, amplitude_rad, duration_s};
}

double SweptSine::theta(double t) const noexcept { return c * std::sin(chirp().phase(t)); }

double SweptSine::omega(double t) const noexcept {
  const ChirpPhase p = chirp();
  return c * p.rate(t) * std::cos(p.phase(t));
}

double SweptSine::alpha(double t) const noexcept {
  const ChirpPhase p = chirp();
  const double phi = p.phase(t);
  const double w = p.rate(t);
  return -c * w * w * std::sin(phi) + c * p.rate_dot() * std::cos(phi);
}

double SweptSine::peak_speed(double t) const noexcept { return std::abs(c * chirp().rate(t)); }

double SweptSine::time_at_peak_speed(double speed) const noexcept {
  // c·|φ'(t)| = |c|·2π·|u(t)|/d with u linear in t: |u| reaches the level
  // u* = speed·d / (2π|c|) first at t = 0, or where u crosses ±u* on its way.
  if (peak_speed(0.0) >= speed) return 0.0;
  if (c == 0.0 || a == b) return std::numeric_limits<double>::infinity();
  const double u_star = speed * d / (2.0 * kPi * std::abs(c));
  const double target = b > a ? u_star : -u_star;  // u grows towards +∞ or −∞
  return (target - a) * d / (b - a);
}

Kinematics<double> SweptSine::at(double t) const noexcept {
  const ChirpPhase p = chirp();
  const double phi = p.phase(t);
  const double w = p.rate(t);
  const double s = std::sin(phi), co = std::cos(phi);
  return {c * s, c * w * co, -c * w * w * s + c * p.rate_dot() * co};
}

TorqueSweep TorqueSweep::from_hz(double f_start_hz, double f_end_hz, double amplitude,
                                 double duration_s) {
  return {f_start_hz * duration_s, f_end_hz * duration_s, amplitude, duration_s};
}

double TorqueSweep::torque(double t) const noexcept {
  return amplitude_Nm * std::sin(chirp().phase(t));
}

}  // namespace knoblab::model
