// Gripper coupling between the motor shaft and the knob (thesis §1.4): the
// torque sensor, the 3D-printed ABS gripper and its VHB tape, lumped into one
// torsional spring + damper. The torque sensor reads the coupling torque
//   τ_c = k·(θ_m − θ_k) + c·(ω_m − ω_k),
// i.e. the torque driving everything on the knob side (gripper + knob).
//
// Defaults: k = 100 N·m/rad, c = 0.07 N·m·s/rad.
//  * Stiff: full sensor torque (0.18 N·m) twists it by 1.8 mrad (~180 encoder
//    counts, 0.1°), small against the narrowest detent (2π/30 = 0.21 rad).
//  * With the motor held by a position loop the knob rings at
//    f_n = √(k/J_k)/2π: 270 Hz (subtle-detents), 230 Hz (moderate-detents),
//    95 Hz (high-inertia), with ζ = c/(2√(k·J_k)) = 0.6, 0.5, 0.2 — the
//    "oscillations" the thesis blames on the gripper (§2.4.1), but well
//    above the 1.5 Hz capture sweep and the 500 Hz analysis filters.
//  * Free–free, the light rotor (J = 1e-6) makes the relative mode
//    overdamped (ζ ≈ 3.5 at 1.6 kHz): it never rings on its own.
// The plant integrates the coupling implicitly, so any k, c is stable.
#pragma once

#include <cmath>
#include <numbers>

namespace knoblab::sim {

struct CouplingParams {
  double stiffness = 100.0;     // N·m/rad
  double damping = 0.07;        // N·m·s/rad
  // Gripper inertia on the knob side. 0 by default: Table 7's M_acc was
  // fitted through the real gripper, so it already contains it.
  double gripper_inertia = 0.0; // kg·m²

  double torque(double twist, double twist_rate) const {
    return stiffness * twist + damping * twist_rate;
  }

  // Coupling that makes a knob of inertia J ring at f_n with damping ratio
  // zeta against a held motor.
  static CouplingParams tuned(double f_n_hz, double zeta, double knob_inertia) {
    const double wn = 2.0 * std::numbers::pi * f_n_hz;
    CouplingParams c;
    c.stiffness = knob_inertia * wn * wn;
    c.damping = 2.0 * zeta * knob_inertia * wn;
    return c;
  }
};

}  // namespace knoblab::sim
