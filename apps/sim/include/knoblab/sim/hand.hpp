// A hand on the simulated knob, for render mode on the `sim` backend (where
// otherwise nothing turns the knob): it moves the knob back and forth along
// θ_h(t) = amplitude·sin(2π·f·t) through a compliant grip, so the knob
// follows while the rendered model pushes back, as a person's would.
//   hand torque = stiffness·(θ_h − θ) + damping·(θ̇_h − θ̇)
// As a KnobEffect its torque is the opposite: the torque needed to move the
// knob (effects.hpp), and the hand supplies it.
#pragma once

#include <memory>

#include "knoblab/sim/effects.hpp"

namespace knoblab::sim {

struct HandParams {
  double amplitude_rad = 0.5;
  double frequency_hz = 0.5;
  double stiffness = 1.0;  // N·m/rad: a firm grip, compliant enough to feel detents
  double damping = 0.01;   // N·m·s/rad
};

std::unique_ptr<KnobEffect> make_hand(const HandParams& p);

}  // namespace knoblab::sim
