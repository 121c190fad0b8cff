// Effect specs as JSON, in the shape of a discrepancy finding:
//   {"effect": "stribeck", "params": {"static_excess_Nm": 0.004, …}}
// so a finding (or a model's list of them) can be given back to simulate.
#pragma once

#include <nlohmann/json.hpp>

#include "knoblab/model/effect_table.hpp"

namespace knoblab::model {

// {"static_excess_Nm": 0.004, …}: the parameters given, in the table's order.
nlohmann::ordered_json effect_params_json(const EffectSpec& spec);
// {"effect": id, "params": effect_params_json(spec)}
nlohmann::ordered_json effect_json(const EffectSpec& spec);

// From a params object as discrepancy reports it (effect_from_params: values
// derived beside a parameter are skipped). Throws std::invalid_argument when
// it is not an object of numbers (naming the field) or the table refuses it.
EffectSpec effect_from_json(std::string_view id, const nlohmann::json& params);
// From {"effect": id, "params": {…}} (a finding; its other fields ignored).
EffectSpec effect_from_json(const nlohmann::json& effect);

}  // namespace knoblab::model
