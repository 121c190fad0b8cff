// load_model's "effects" (docs/protocol.md §7): the effect library's terms
// the renderer renders (model/effect_set.hpp), read from the arguments and
// checked as the rest of the model is.
#pragma once

#include <optional>

#include <nlohmann/json_fwd.hpp>

#include "knoblab/hapticd/render_params.hpp"
#include "knoblab/hapticd/supervisor.hpp"

namespace knoblab::hapticd {

// `effects` already checked against the protocol schema.
model::EffectSet<double> effects_from_args(const nlohmann::json& effects);

// Why the device must not render these effects (the key as the protocol
// names it, e.g. "effects.gravity.amplitude_Nm"), or nullopt: every value finite, and
// no term whose size alone exceeds the torque limit.
std::optional<ParamProblem> effects_problem(const model::EffectSet<double>& e, const SafetyLimits& limits);

}  // namespace knoblab::hapticd
