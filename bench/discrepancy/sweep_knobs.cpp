#include "knoblab/sim/presets.hpp"
#include "sweep_plant.hpp"

namespace knoblab::bench {

namespace {

// A return-to-centre knob (a spring-loaded selector or a joystick-like
// knob): no detents, light friction, a spring over the ±1 rad sweep of
// 20 mN·m/rad stiffening by 10 mN·m/rad³.
sim::KnobParams spring_return() {
  sim::KnobParams k;
  k.inertia.M = 0.05e-3;
  k.friction = {2e-3, 0.3e-3, 2e-3, 0.3e-3};
  k.stick = {0.01, 6e-3, 6e-3};
  k.spring.K = 20e-3;
  k.spring.K3 = 10e-3;
  return k;
}

}  // namespace

std::vector<SweepKnob> sweep_knobs(bool quick) {
  std::vector<std::string> thesis{"moderate-detents"};
  if (!quick) thesis = {"moderate-detents", "subtle-detents", "high-inertia", "high-friction"};
  std::vector<SweepKnob> knobs;
  for (const std::string& name : thesis) knobs.push_back({name, *sim::presets::knob(name), "none"});
  knobs.push_back({"spring-return", spring_return(), "spring"});
  return knobs;
}

}  // namespace knoblab::bench
