// The knob behind the camera's coupling, simulated from the motor's motion:
// what the encoder (on the motor) cannot show when the gripper is soft.
// Internal to knoblab_discovery.
//
//   motor ── coupling (k, c) ── torque sensor reading ── knob (J)
//
// The motor's angle and speed are the recording's (linear between samples);
// the coupling's torque is k·e + c·ė on the twist e = θm − θk; the knob turns
// under it against the model's own torques (friction, detents, effects) and
// sticks where its speed crosses zero until the net torque exceeds the
// breakaway level. The coupling torque is what the sensor reads.
//
// Why simulate rather than read the knob's motion off the measured torque
// (θk = θm − τ/k): the knob's acceleration is then the second derivative of
// the torque, whose noise (J·τ̈/k) swamps a light knob's inertia when α is
// the encoder's. The simulation's own weak spot is the encoder: a count of
// twist is k·2π/counts of torque, so it suits soft couplings (tens of
// N·m/rad ring at tens of Hz), where the twist form fails.
#pragma once

#include <functional>
#include <span>
#include <vector>

namespace knoblab::discovery::detail {

struct CouplingSpec {
  double stiffness = 0.0;  // k, N·m/rad (> 0)
  double lag_s = 0.0;      // c/k, s
};

struct KnobDynamics {
  double inertia = 0.0;    // J, kg·m² (> 0)
  double breakaway = 0.0;  // N·m: static friction holds a stuck knob up to this
  // The knob's torque except its inertia's, at (θ, ω): friction and
  // position torques, as the model has them. At ω = 0 friction is nil.
  std::function<double(double theta, double omega)> torque;
};

// Per recorded sample: the knob's motion and the coupling's torque.
struct CoupledMotion {
  std::vector<double> theta, omega, alpha;  // the knob's
  std::vector<double> torque;               // the coupling's, as the sensor reads it
  std::vector<char> stuck;                  // static friction holds the knob
};

// Throws std::invalid_argument when k or J is not positive, or the sizes differ.
CoupledMotion simulate_coupled_knob(std::span<const double> t, std::span<const double> motor_theta,
                                    std::span<const double> motor_omega, const CouplingSpec& coupling,
                                    const KnobDynamics& knob);

}  // namespace knoblab::discovery::detail
