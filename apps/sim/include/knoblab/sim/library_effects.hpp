// The effect library (knoblab/model/effects.hpp) on the simulated knob, so a
// capture can carry physics the thesis model leaves out: what discrepancy
// discovery must find (issue 5's concealed-effect captures).
//
//   "stribeck:excess=0.002,v_s=0.1"   → a KnobEffect with those parameters
//   "spring:K=0.01"                   → folded into KnobParams (a model term)
//
// Effects and parameters (SI):
//   offset            tau0
//   gravity           A, phase                       A·sin(θ + phase)
//   stribeck          excess, v_s
//   nonlinear_damping c, p                           sgn(ω)·c·|ω|^p
//   position_friction depth, P, phase                sgn(ω)·depth·sin(θ/P + phase)
//   periodic_torque   A, P, S                        A·sin(θ/P + S)
//   drift             rate, t0                       sgn(ω)·rate·(t − t0)
//   spring            K, K3, theta0                  (KnobParams::spring)
//   detent_shape      a2, b2, a3, b3, a4, b4         (KnobParams::detents harmonics)
//   backlash          width                          (KnobParams::backlash, total play)
// Missing parameters default to 0 (P to 1, v_s to 1, p to 2).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/sim/effects.hpp"
#include "knoblab/sim/knob.hpp"

namespace knoblab::sim {

struct EffectSpec {
  std::string id;
  std::map<std::string, double> params;
  std::string text() const;  // back to "id:k=v,…"
};

// "id:k=v,k=v"; several separated by ';'. Throws std::invalid_argument on an
// unknown id or parameter, or a value that is not a finite number.
std::vector<EffectSpec> parse_effect_specs(std::string_view text);

// Folds a spec into the knob when it is one of its terms (spring,
// detent_shape, backlash) and returns true; false for the others.
bool apply_to_knob(const EffectSpec& spec, KnobParams& knob);

// The KnobEffect of a torque spec (not spring / detent_shape). Setup time only.
std::unique_ptr<KnobEffect> make_knob_effect(const EffectSpec& spec);

}  // namespace knoblab::sim
