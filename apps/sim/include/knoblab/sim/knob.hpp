// The knob under test, as a composition of knoblab_model terms (thesis Eq. 6
// and Eq. 7) — the same definitions the fitter and the renderer use. SI units:
// kg·m², N·m, N·m·s/rad, rad, rad/s.
//
// Equation of motion on the knob side of the gripper coupling:
//   (M + J_gripper)·θ̈ = τ_c − friction(θ̇, τ_other) − τ_pos(θ, θ̇) − Σ effects
// where τ_pos = detents + spring + walls and τ_other = τ_c − τ_pos − effects
// is what the Karnopp stick band balances (inside |θ̇| < dv the knob sticks
// while −D_neg ≤ τ_other ≤ D_pos).
//
// More effects: add a field here when it is a new knoblab_model term shared
// with the fitter, or a KnobEffect (effects.hpp) on the Plant otherwise.
#pragma once

#include <string_view>

#include "knoblab/model/models.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::sim {

struct KnobParams {
  model::Inertia<double> inertia{};        // M_acc
  model::CoulombViscous<double> friction{};// C_neg, B_neg, C_pos, B_pos ≥ 0
  model::KarnoppStick<double> stick{};     // dv = 0: no stick band
  model::Detents<double> detents{};        // A = 0: none
  model::Spring<double> spring{};          // K = K3 = 0: none
  model::Walls<double> walls{};            // K = B = 0: none (endstops)
  // Play between the gripper and the detent mechanism (rad, total): after a
  // reversal the drive turns this far before it pushes the knob again, and
  // the sensor reads nothing meanwhile. Applied in Plant::step_knob.
  double backlash = 0.0;
  // Presliding hysteresis (rad, Dahl's θ_p; 0: none): while sliding, the
  // Coulomb part is C·z with z the model::DahlFriction state driven by the
  // mechanism's travel, so friction turns over within a few θ_p after a
  // reversal instead of jumping. The Karnopp band still holds the knob (z
  // stands with it). Applied in Plant::step_knob.
  double presliding = 0.0;
};

// Detents + spring + walls: the knob's non-frictional, non-inertial torque.
inline double position_torque(const KnobParams& k, double theta, double omega) {
  return k.detents.torque(theta) + k.spring.torque(theta) + k.walls.torque(theta, omega);
}

// "" when the parameters describe a passive, physical knob; otherwise why not.
std::string_view check(const KnobParams& k);

// The Eq. 6 part (what the thesis fitter estimates) of a knob.
model::ThesisModel<double> thesis_model(const KnobParams& k);

}  // namespace knoblab::sim
