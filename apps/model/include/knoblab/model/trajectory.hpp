// Swept-sine stimuli (thesis Eq. 8) with exact derivatives.
//
//   u(t) = (b−a)·t/d + a
//   φ(t) = π/(b−a)·(u² − a²)  =  π·t·(u + a)/d      (second form: no 0/0 at a = b)
//   θ(t) = c·sin φ
//   θ̇(t) = c·φ'·cos φ,                 φ' = 2π·u/d
//   θ̈(t) = −c·φ'²·sin φ + c·φ''·cos φ,  φ'' = 2π·(b−a)/d²
// The thesis prints θ̈ with u instead of u² in the first term; this is the
// derivative of its θ.
//
// Units as printed: the instantaneous frequency is φ'/2π = u/d Hz, so it
// runs from a/d Hz at t = 0 to b/d Hz at t = d — a and b are in Hz only when
// d = 1 s. (Table 3's spatial sweep, a=0, b=1.5, d=3, reaches 0.5 Hz at 3 s
// and 1 Hz at the 6 s end of Eq. 9.) from_hz() builds a sweep between given
// frequencies in Hz.
//
// Eq. 8 has no end: past t = d the frequency keeps rising at the same rate,
// (b−a)/d² Hz per second. Table 3's sweep runs at t/6 Hz, so a minute of it
// ends at 10 Hz, where θ̇ peaks at c·2π·10 = 63 rad/s and θ̈ at 3950 rad/s².
// peak_speed() and time_at_peak_speed() say how fast a sweep gets, and when.
#pragma once

#include <numbers>

#include "knoblab/model/terms.hpp"

namespace knoblab::model {

// Phase of Eq. 8 and its time derivatives. d > 0 is required.
struct ChirpPhase {
  double a = 0.0, b = 0.0, d = 1.0;
  double phase(double t) const noexcept;      // rad
  double rate(double t) const noexcept;       // rad/s
  double rate_dot() const noexcept;           // rad/s², constant
  double frequency_hz(double t) const noexcept { return rate(t) / (2.0 * std::numbers::pi); }
};

// Position sweep θ = c·sin φ(t); c in rad.
struct SweptSine {
  double a = 0.0, b = 0.0, c = 0.0, d = 1.0;

  // Thesis Table 3.
  static constexpr SweptSine spatial() { return {0.0, 1.5, 1.0, 3.0}; }
  static constexpr SweptSine torque_test() { return {0.0, 1.5, 0.02, 3.0}; }
  // Sweep from f_start_hz at t = 0 to f_end_hz at t = duration_s.
  static SweptSine from_hz(double f_start_hz, double f_end_hz, double amplitude_rad,
                           double duration_s);

  double theta(double t) const noexcept;         // rad
  double omega(double t) const noexcept;         // rad/s
  double alpha(double t) const noexcept;         // rad/s²
  double frequency_hz(double t) const noexcept { return chirp().frequency_hz(t); }
  // θ̇'s envelope around t, c·|φ'(t)| (rad/s): the fastest the sweep moves
  // in the cycle it runs at t.
  double peak_speed(double t) const noexcept;
  // The first t ≥ 0 at which that envelope reaches `speed` (rad/s): 0 when
  // it starts there, +∞ when it never does.
  double time_at_peak_speed(double speed) const noexcept;
  Kinematics<double> at(double t) const noexcept;
  ChirpPhase chirp() const noexcept { return {a, b, d}; }
};

// Torque stimulus with the same chirp: τ = amplitude_Nm·sin φ(t).
struct TorqueSweep {
  double a = 0.0, b = 0.0, amplitude_Nm = 0.0, d = 1.0;

  static TorqueSweep from_hz(double f_start_hz, double f_end_hz, double amplitude_Nm,
                             double duration_s);
  double torque(double t) const noexcept;        // N·m
  double frequency_hz(double t) const noexcept { return chirp().frequency_hz(t); }
  ChirpPhase chirp() const noexcept { return {a, b, d}; }
};

}  // namespace knoblab::model
