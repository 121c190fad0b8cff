#include "knoblab/discovery/effects.hpp"

#include <vector>

#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::discovery {

std::string_view effect_name(EffectId id) { return model::effect_row(id).id; }

std::optional<EffectId> parse_effect(std::string_view name) {
  if (const model::EffectRow* r = model::find_effect(name)) return r->effect;
  return std::nullopt;
}

std::vector<EffectId> implemented_effects(fit::Axis axis) {
  std::vector<EffectId> out = implemented_effects();
  if (axis == fit::Axis::Linear) std::erase(out, EffectId::Gravity);
  return out;
}

}  // namespace knoblab::discovery
