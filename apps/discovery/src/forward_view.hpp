// The forward view: does the model, driven by the measured torque, move the
// knob the way the recording did? Complements the inverse view (measured
// torque against the model's torque from the measured motion): a term that
// barely changes the torque RMS can still change where the knob goes.
// Internal to knoblab_discovery.
#pragma once

#include <cstddef>
#include <span>

#include "extended_model.hpp"
#include "knoblab/fit/fit_data.hpp"

namespace knoblab::discovery::detail {

struct ForwardError {
  double rms_theta_rad = 0.0;   // simulated − measured angle, over every window sample
  double rms_omega_rad_s = 0.0;
  // 0: not available (inertia not positive, too short, or the model runs
  // away: a radian off within a window).
  std::size_t windows = 0;
};

// Short windows of `horizon_s` starting at the rows `starts` (in time
// order; a window that overlaps the previous one is skipped), each begun
// from the measured θ, θ̇ and integrated (semi-implicit Euler on the
// samples' own time steps, the model's damping implicit) under  M·θ̈ = τ_measured − τ_model(θ, θ̇)  with
// the model's other terms and effects. Short, as MATLAB's compare with a
// prediction horizon: over seconds any friction model drifts off. The
// model's operators (backlash, Dahl state, delay) keep their state from
// the measured motion.
ForwardError forward_error(const ExtendedModel& m, const fit::FitData& d,
                           std::span<const std::size_t> starts, double horizon_s = 0.02);

}  // namespace knoblab::discovery::detail
