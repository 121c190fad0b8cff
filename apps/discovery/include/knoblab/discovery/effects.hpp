// The effect library's ids and parameter names (the table in docs/discrepancy.md), as the
// discrepancy JSON reports them. The physics is in knoblab/model/effects.hpp.
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <vector>

namespace knoblab::discovery {

enum class EffectId {
  Offset,
  Gravity,
  Spring,
  PeriodicTorque,
  DetentShape,
  Stribeck,
  NonlinearDamping,
  PositionFriction,
  Drift,
  TimeDelay,
  Saturation,
  Backlash,
  Hysteresis,
  Endstop,
  Compliance,
};

inline constexpr std::array kAllEffects = {
    EffectId::Offset,           EffectId::Gravity,          EffectId::Spring,
    EffectId::PeriodicTorque,   EffectId::DetentShape,      EffectId::Stribeck,
    EffectId::NonlinearDamping, EffectId::PositionFriction, EffectId::Drift,
    EffectId::TimeDelay,        EffectId::Saturation,       EffectId::Backlash,
    EffectId::Hysteresis,       EffectId::Endstop,          EffectId::Compliance,
};

// "stribeck", "backlash", … (the JSON's "effect").
std::string_view effect_name(EffectId id);
std::optional<EffectId> parse_effect(std::string_view name);

}  // namespace knoblab::discovery
