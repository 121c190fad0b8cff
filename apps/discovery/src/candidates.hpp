// Candidate effects: starting values from the current residual, the joint
// fit, the parameters reported and the sentence that explains a finding.
// Internal to knoblab_discovery.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "extended_model.hpp"
#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::discovery::detail {

// The current model with effect `id` added and fitted on the training rows
// (all parameters jointly), in each of its forms (compliance has two: the
// twist read off the torque, the knob simulated behind the coupling; the
// rest one); none when the effect cannot apply (no detents for a detent
// shape, no flat tops for clipping, …). The caller judges the forms on
// held-out rows.
std::vector<ExtendedModel> candidate_forms(EffectId id, const ExtendedModel& current, const fit::FitData& d,
                                           std::span<const std::size_t> train, const std::vector<double>& residual);

// Whether a detent term of period P (rad of travel per rad of phase) is
// detents over `travel` rad: at least 1.5 cycles per revolution and two
// periods over the travel. Slower, it is a trend over position (a spring,
// gravity).
bool repeats_as_detents(double P, double travel);

// An effect's parameters as reported (SI; periods also as cycles/rev: on a
// linear axis per 2π m).
Params report_params(const ActiveEffect& e, const ExtendedModel& m);

// What a finding's sentences may say of the recording: whether it reverses
// (motion.hpp), where the effect changed the model's torque most, and its
// axis (the units the sentences speak in).
struct Motion {
  bool reverses = true;
  std::string span;  // "t 0.02–0.31 s, θ −57…−40°" (motion.hpp)
  fit::Axis axis = fit::Axis::Rotary;
};

// Where the residual was structured, and a sentence of what the effect is,
// with its parameters (presentation units of the axis, fit/axis_units.hpp:
// mN·m, degrees, cycles/rev; N, mm, mm per cycle; the held-out figures are
// added by discover()).
struct Explanation {
  std::string where, sentence;
};
Explanation explain(const ActiveEffect& e, const ExtendedModel& m, const Motion& motion);

}  // namespace knoblab::discovery::detail
