// The effect library's ids as discrepancy discovery uses them: the effect
// table's (knoblab/model/effect_table.hpp), as the JSON reports them. The
// physics is in knoblab/model/effects.hpp.
#pragma once

#include <optional>
#include <string_view>

#include "knoblab/model/effect_table.hpp"

namespace knoblab::discovery {

using EffectId = model::Effect;
using model::kAllEffects;

// "stribeck", "backlash", … (the JSON's "effect").
std::string_view effect_name(EffectId id);
std::optional<EffectId> parse_effect(std::string_view name);

}  // namespace knoblab::discovery
