// Physics beyond the thesis' Eq. 6: the effect library of discrepancy
// discovery (docs/discrepancy.md), one definition per effect, shared by the
// plant simulator (double) and the fitter (ceres::Jet).
//
// Torque terms (same sign convention as terms.hpp: the torque needed to move
// the knob, what the sensor reads):
//   Offset, OncePerRev (gravity), Stribeck, PowerDamping, PositionFriction,
//   FrictionDrift. Detents (harmonics: detent_shape; a second instance:
//   periodic_torque), Spring and Walls (endstop) are in terms.hpp.
// Operators on what is measured rather than torques:
//   Backlash (play between the drive and the knob), DahlFriction (presliding
//   hysteresis), Saturation (sensor clipping), and a delay between the torque
//   and the motion channels (applied where samples are at hand, see
//   discovery/effect_terms.hpp).
#pragma once

#include <cmath>

#include "knoblab/model/terms.hpp"

namespace knoblab::model {

// A constant torque bias (sensor zero, a preload).
template <typename T>
struct Offset {
  T tau0{};  // N·m
  bool operator==(const Offset&) const = default;
  T torque() const { return tau0; }
};

// Once per revolution: an unbalanced mass on a tilted axis, A·sin(θ + φ).
template <typename T>
struct OncePerRev {
  T A{};      // N·m
  T phase{};  // rad
  bool operator==(const OncePerRev&) const = default;
  T torque(const T& theta) const {
    using std::sin;
    return A * sin(theta + phase);
  }
};

// Stribeck friction: above Coulomb near zero speed, falling off over a
// characteristic speed, sgn(ω)·ΔC·exp(−(ω/v_s)²). ΔC = static − kinetic.
template <typename T>
struct Stribeck {
  T excess{};   // N·m, static_excess_Nm
  T v_s{1.0};   // rad/s, stribeck_velocity_rad_s
  bool operator==(const Stribeck&) const = default;
  T torque(const T& omega) const {
    using std::exp;
    if (omega == T(0)) return T(0);
    const T x = omega / v_s;
    return sgn(omega) * excess * exp(-x * x);
  }
};

// Damping not proportional to speed: sgn(ω)·c·|ω|^p (p = 2: fluid drag;
// p < 1: grease). Added to the viscous term.
template <typename T>
struct PowerDamping {
  T c{};       // N·m/(rad/s)^p
  T p{2.0};    // exponent
  bool operator==(const PowerDamping&) const = default;
  T torque(const T& omega) const {
    using std::abs;
    using std::pow;
    if (omega == T(0)) return T(0);
    return sgn(omega) * c * pow(abs(omega), p);
  }
};

// Friction whose level varies with position (a bent shaft, an eccentric
// bearing): sgn(ω)·D·sin(θ/P + φ).
template <typename T>
struct PositionFriction {
  T depth{};    // N·m, modulation amplitude
  T P{1.0};     // rad per radian of phase (period 2πP)
  T phase{};
  T torque(const T& theta, const T& omega) const {
    using std::sin;
    return sgn(omega) * depth * sin(theta / P + phase);
  }
};

// Friction drifting during the recording (warming grease, wear): the Coulomb
// level changes by `rate` N·m per second from t0.
template <typename T>
struct FrictionDrift {
  T rate{};  // N·m/s
  T t0{};    // s
  T torque(const T& omega, const T& t) const { return sgn(omega) * rate * (t - t0); }
};

// Sensor clipping at ±limit.
template <typename T>
T saturate(const T& tau, const T& limit) {
  if (tau > limit) return limit;
  if (tau < -limit) return -limit;
  return tau;
}

// Lost motion between the drive and the knob: the knob follows the drive
// only once the drive has taken up the play (total width). The play operator:
// knob = clamp(knob, drive − width/2, drive + width/2); `contact` tells
// whether the drive pushes the knob (it moves with it) or not (the knob
// stands, and nothing but the gripper's inertia loads the sensor).
struct Backlash {
  double width = 0.0;  // rad, total play
  double knob = 0.0;   // knob position relative to the drive's centre of play
  bool contact = false;

  void reset(double drive) {
    knob = drive;
    contact = false;
  }
  // Moves the drive to `drive`; returns the knob position.
  double update(double drive) {
    const double h = 0.5 * width;
    if (knob < drive - h) {
      knob = drive - h;
      contact = true;
    } else if (knob > drive + h) {
      knob = drive + h;
      contact = true;
    } else {
      contact = width <= 0.0;
    }
    return knob;
  }
};

// Dahl presliding friction: the friction state z ∈ [−1, 1] follows position,
// dz/dθ = (1 − z·sgn(θ̇))/θ_p, so after a reversal friction turns over within
// a few presliding angles θ_p instead of jumping (rate-independent
// hysteresis). Friction is then C·z in place of C·sgn(θ̇).
struct DahlFriction {
  double presliding = 1e-3;  // rad, presliding_angle_rad
  double z = 0.0;

  void reset(double z0 = 0.0) { z = z0; }
  // Advances over a position step dtheta; returns z.
  double update(double dtheta) {
    if (dtheta == 0.0 || presliding <= 0.0) return z;
    const double s = dtheta > 0 ? 1.0 : -1.0;
    // Exact for a step in one direction: z → s + (z − s)·exp(−|dθ|/θ_p).
    z = s + (z - s) * std::exp(-std::abs(dtheta) / presliding);
    return z;
  }
};

}  // namespace knoblab::model
