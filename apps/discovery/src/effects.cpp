#include "knoblab/discovery/effects.hpp"

namespace knoblab::discovery {

std::string_view effect_name(EffectId id) { return model::effect_row(id).id; }

std::optional<EffectId> parse_effect(std::string_view name) {
  if (const model::EffectRow* r = model::find_effect(name)) return r->effect;
  return std::nullopt;
}

}  // namespace knoblab::discovery
