#include "knoblab/discovery/effects.hpp"

namespace knoblab::discovery {

std::string_view effect_name(EffectId id) {
  switch (id) {
    case EffectId::Offset: return "offset";
    case EffectId::Gravity: return "gravity";
    case EffectId::Spring: return "spring";
    case EffectId::PeriodicTorque: return "periodic_torque";
    case EffectId::DetentShape: return "detent_shape";
    case EffectId::Stribeck: return "stribeck";
    case EffectId::NonlinearDamping: return "nonlinear_damping";
    case EffectId::PositionFriction: return "position_friction";
    case EffectId::Drift: return "drift";
    case EffectId::TimeDelay: return "time_delay";
    case EffectId::Saturation: return "saturation";
    case EffectId::Backlash: return "backlash";
    case EffectId::Hysteresis: return "hysteresis";
    case EffectId::Endstop: return "endstop";
    case EffectId::Compliance: return "compliance";
  }
  return "?";
}

std::optional<EffectId> parse_effect(std::string_view name) {
  for (const EffectId id : kAllEffects)
    if (effect_name(id) == name) return id;
  return std::nullopt;
}

}  // namespace knoblab::discovery
