// The largest damping and stiffness hapticd's loop renders stably at its
// rate (apps/model's render_stability.hpp, the bound hapticd refuses tiles
// beyond), for the waveform editor to draw. The loop's dynamics at a rate
// are hapticd's RenderController::loop_dynamics, repeated here: the UI does
// not link hapticd (a model-side `loop_dynamics_at(rate)` would make it one).
#pragma once

namespace knoblab::ui {

struct StabilityBound {
  double max_damping = 0.0;    // N·m·s/rad, with no stiffness
  double max_stiffness = 0.0;  // N·m/rad, with no damping
};

// Throws std::invalid_argument for a rate that is not a loop's.
StabilityBound stability_bound(double rate_hz);

}  // namespace knoblab::ui
