// A second plant for the discrepancy benchmark: a two-body rig written from
// the physics, not from knoblab's simulator.
//
// Why it exists: apps/sim's plant and discovery's effect library share one
// set of definitions (apps/model), so a benchmark on the simulator cannot
// catch a mistake both make. This file uses neither: it takes only the
// Table 3 stimulus (model::SweptSine), the interchange Capture it writes and
// the difference quotient the CSV reader derives ω and α with.
//
// The rig (SI units throughout: rad, rad/s, rad/s², N·m, kg·m², s):
//
//   motor ── coupling (k, c, play w) ── torque sensor ── knob (J)
//
// * Motor: stiff and position-controlled, so its angle is the stimulus
//   exactly (no PID): θm(t) = the Table 3 swept sine, or a slow triangle
//   sweep whose legs run at constant speeds (a ladder from slow to fast, for
//   low-speed friction) with turns at a finite acceleration.
// * Coupling (gripper): twist e = θm − θk, ė = ωm − ωk. Without play
//   τc = k·e + c·ė. With a dead zone of total width w the faces touch only
//   beyond ±w/2, and a contact only pushes:
//     e >  w/2:  τc = max(0, k·(e − w/2) + c·ė)
//     e < −w/2:  τc = min(0, k·(e + w/2) + c·ė)
//     otherwise: τc = 0.
//   k = +∞ is a rigid coupling (θk = θm; play needs a finite k).
// * Knob: J·α_k = τc − F(ω_k) − τ_pos(θ_k, ω_k), with
//     τ_pos  = detents  A·sin φ + Σ_{n=2..4} (a_n·sin nφ + b_n·cos nφ), φ = θ/P + S
//            + a second periodic torque  A₂·sin(2π·θ/period + φ₂)
//            + spring  K·θ + K₃·θ³
//            + gravity  A_g·sin(θ + φ_g)           (an unbalanced mass)
//            + endstops beyond ±θ_e: K_e·(θ ∓ θ_e) + B_e·ω, pushing outward only
//     F(ω)   = sgn ω·(C± + ΔC·exp(−(ω/v_s)²)) + B±·ω + c_d·ω·|ω|
//              (Stribeck: kinetic level C, static excess ΔC over the speed v_s;
//               quadratic drag c_d)
//   Stick–slip is Karnopp's switch with an event-detected zero band: a
//   stuck knob (ω = 0) stays stuck while |τc − τ_pos| is at most the
//   breakaway level C± + ΔC in that direction (static friction balances it
//   exactly); above it the knob slides, starting from the breakaway level.
//   A sliding knob whose speed would cross zero in a substep sticks there
//   if the torque on it is under the breakaway level, and turns back
//   otherwise.
// * Integration: semi-implicit (symplectic) Euler at a fixed substep, at
//   least `substep_hz` and fine enough that h·√(k/J) ≤ 0.2 and h·c/J ≤ 0.2
//   (explicit damping and a stiff spring are stable well inside 2); the
//   knob rests 0.25 s against the held motor before the first sample.
// * Camera, at rate_hz: t, θ = the motor encoder (floor to counts; 0 counts
//   per rev: exact), the coupling torque as the sensor between motor and
//   coupling reads it plus white noise of RMS torque_noise_rms; ω and α are
//   left to the reader's rule (differences of θ), as a CSV without those
//   columns would be read: the encoder is on the motor side. Optionally α
//   is a knob-side accelerometer's instead: the knob's acceleration plus
//   white noise.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "knoblab/interchange/capture.hpp"
#include "knoblab/model/trajectory.hpp"

namespace knoblab::bench {

// Back and forth over ±amplitude around the start: the first leg from the
// start to +amplitude, then full legs alternating direction. Leg speeds
// climb a geometric ladder from slowest to fastest and back down, over and
// over; each leg starts and ends at rest, accelerating at turn_accel.
struct TriangleSweep {
  double amplitude_rad = 0.5;
  double slowest_rad_s = 0.05;
  double fastest_rad_s = 2.0;
  int rungs = 5;  // speeds on the ladder (1: every leg at slowest)
  double turn_accel_rad_s2 = 20.0;
};

struct MotorStimulus {
  enum class Kind { SweptSine, Triangle } kind = Kind::SweptSine;
  model::SweptSine sine = model::SweptSine::spatial();  // thesis Table 3
  TriangleSweep triangle{};
};

struct Coupling {
  double stiffness = 2000.0;  // N·m/rad; +∞: rigid
  double damping = 0.0;       // N·m·s/rad
  double play = 0.0;          // rad, total width of the dead zone

  // Damping for a ratio ζ against a knob of inertia J on a held motor.
  static double damping_for(double zeta, double stiffness, double inertia);
  bool rigid() const { return stiffness == std::numeric_limits<double>::infinity(); }
};

struct TwoBodyKnob {
  double inertia = 5e-5;  // kg·m², knob and the gripper's knob side
  // Friction (magnitudes): kinetic Coulomb and viscous per direction, the
  // static excess over the Stribeck speed, and quadratic drag.
  double coulomb_pos = 1e-3, coulomb_neg = 1e-3;  // N·m
  double viscous_pos = 5e-4, viscous_neg = 5e-4;  // N·m·s/rad
  double static_excess = 0.0;                     // ΔC, N·m
  double stribeck_speed = 0.01;                   // v_s, rad/s (> 0)
  double drag = 0.0;                              // c_d, N·m·s²/rad²
  // Detents (thesis Eq. 6's form): A·sin(θ/P + S) and harmonics 2…4.
  double detent_amplitude = 0.0, detent_period = 1.0, detent_phase = 0.0;  // N·m, rad/rad, rad
  std::array<double, 3> detent_sin{}, detent_cos{};  // a_n, b_n for n = 2, 3, 4 (N·m)
  // A second periodic torque over position (cogging, a second track).
  double periodic_amplitude = 0.0, periodic_period_rad = 1.0, periodic_phase = 0.0;
  double spring = 0.0, spring_cubic = 0.0;         // K N·m/rad, K₃ N·m/rad³
  double gravity = 0.0, gravity_phase = 0.0;       // A_g N·m, rad
  double endstop_angle = 0.0;                      // rad; 0: no stops
  double endstop_stiffness = 0.0, endstop_damping = 0.0;  // N·m/rad, N·m·s/rad
};

struct Camera {
  double rate_hz = 5000.0;
  double torque_noise_rms = 0.1e-3;         // N·m, white
  std::int64_t encoder_counts_per_rev = 640000;  // 0: the exact angle
  // A knob-side accelerometer, as the Haptic Camera has one: α recorded as
  // the knob's acceleration plus white noise (rad/s² RMS). Without it α is
  // derived from the motor encoder, like ω.
  bool accelerometer = false;
  double accelerometer_noise_rms = 0.0;
  std::uint64_t seed = 1;                   // noise only; the motion never depends on it
};

struct TwoBodyConfig {
  std::string knob_name = "two-body knob";  // for the capture's metadata
  TwoBodyKnob knob{};
  Coupling coupling{};
  MotorStimulus stimulus{};
  Camera camera{};
  double seconds = 8.0;
  double substep_hz = 50000.0;  // the least substep rate; stiff couplings get more
};

// The true motion and torques at each recorded sample, for tests.
struct TwoBodyTruth {
  std::vector<double> motor_theta, knob_theta, knob_omega;  // rad, rad/s
  std::vector<double> coupling_torque;  // N·m, what the sensor reads before noise
  std::vector<char> stuck;              // 1: static friction holds the knob
  std::vector<char> in_play;            // 1: the coupling's faces do not touch
};

struct TwoBodyRun {
  interchange::Capture capture;  // what discovery reads
  TwoBodyTruth truth;
  int substeps = 0;              // per sample
};

// Throws std::invalid_argument naming the field and what it must be.
void validate(const TwoBodyConfig& config);
TwoBodyRun run_two_body(const TwoBodyConfig& config);

// The motor's prescribed motion at t (s from the first sample).
struct MotorState {
  double theta = 0.0, omega = 0.0, alpha = 0.0;
};
class MotorPath {
 public:
  MotorPath(const MotorStimulus& stimulus, double seconds);
  MotorState at(double t) const;

 private:
  struct Leg {
    double start_s, from_rad, to_rad, speed, accel;
  };
  MotorStimulus stimulus_;
  std::vector<Leg> legs_;
};

}  // namespace knoblab::bench
