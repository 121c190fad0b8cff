#include "knoblab/studyrun/reference_knob.hpp"

#include <cmath>
#include <variant>

#include "knoblab/sim/presets.hpp"
#include "knoblab/studyrun/rendering_field.hpp"

namespace knoblab::studyrun {

std::optional<study::Rendering> reference_rendering(const study::Level& level) {
  if (level.rendering) return *level.rendering;
  const auto* p = sim::presets::find(level.preset);
  if (!p) return std::nullopt;
  study::Rendering r;
  r.M_acc = p->knob.inertia.M;
  r.B_vel = (p->knob.friction.B_pos + p->knob.friction.B_neg) / 2;
  if (p->knob.detents.A != 0 && p->knob.detents.P > 0) {
    r.A_pos = std::abs(p->knob.detents.A);
    r.detents_per_rev = 1.0 / p->knob.detents.P;
  }
  return r;
}

std::map<std::string, std::map<std::string, double>> matching_references(const study::Protocol& protocol) {
  std::map<std::string, std::map<std::string, double>> out;
  const auto* m = std::get_if<study::MatchingSettings>(&protocol.settings);
  if (!m || protocol.factors.empty()) return out;
  for (const study::Level& level : protocol.factors.front().levels)
    if (const auto r = reference_rendering(level))
      for (const study::Slider& s : m->sliders) out[level.name][s.parameter] = rendering_field(*r, s.parameter);
  return out;
}

}  // namespace knoblab::studyrun
