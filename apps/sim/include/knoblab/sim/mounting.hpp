// How the Haptic Camera is mounted (thesis §1.5), for the accelerometer's
// gravity term (§1.2.3, Eq. 2). Gravity's component in the plane of rotation
// is g·sin(tilt); the tangential accelerometer at radius r reads it as an
// angular acceleration of (g/r)·sin(tilt)·sin(θ + roll).
#pragma once

#include <cmath>
#include <numbers>

namespace knoblab::sim {

inline constexpr double kGravity = 9.80665;  // m/s²

struct CameraOrientation {
  double tilt = std::numbers::pi / 2;  // rad, rotation axis from vertical
  double roll = 0.0;                   // rad, sensor angle vs. gravity at θ = 0

  // Lab: on the lathe bed, the axis is horizontal (§1.5) — full gravity.
  static CameraOrientation lab(double roll = 0.0) { return {std::numbers::pi / 2, roll}; }
  // Field: on a tripod or clamp at any tilt (e.g. a dashboard knob).
  static CameraOrientation tripod(double tilt, double roll = 0.0) { return {tilt, roll}; }
  // Axis along gravity: no gravity signal at all.
  static CameraOrientation vertical() { return {0.0, 0.0}; }

  // A_g of the gravity term, rad/s², for a sensor at radius r (m).
  double gravity_amplitude(double radius) const { return kGravity / radius * std::sin(tilt); }
};

}  // namespace knoblab::sim
