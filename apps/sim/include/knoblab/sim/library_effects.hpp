// The effect library (knoblab/model/effects.hpp) on the simulated knob, so a
// capture can carry physics the thesis model leaves out: what discrepancy
// discovery must find (the concealed-effect benchmark's captures).
//
//   "stribeck:excess=0.002,v_s=0.1"   → a KnobEffect with those parameters
//   "spring:K=0.01"                   → folded into KnobParams (a model term)
//   "time_delay:delay=0.001"          → folded into PlantConfig (rig, not knob)
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
//   hysteresis        presliding > 0                 Dahl C·z for Coulomb (KnobParams::presliding)
//   endstop           position > 0, stiffness > 0,   walls at ±position
//                     damping                        (KnobParams::walls)
//   compliance        stiffness | frequency,         softer gripper coupling
//                     damping | zeta                 (PlantConfig::coupling)
//   time_delay        delay ≥ 0                      torque channel delay s behind the
//                                                    motion (TorqueSensorParams::delay)
//   saturation        limit > 0                      torque sensor clips at ±limit
//                                                    (TorqueSensorParams::saturation)
// Missing parameters default to 0 (P to 1, v_s to 1, p to 2). compliance
// takes exactly one of stiffness (N·m/rad) and frequency (Hz: the knob
// ringing against a held motor, k = J·(2πf)², J = M + gripper) and at most
// one of damping (N·m·s/rad) and zeta (damping ratio there); without either
// the coupling keeps its damping ratio. time_delay's sign is discovery's
// delay_s: positive = the torque behind the motion (a negative one would
// need the motion channels delayed, which the plant does not model).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/sim/effects.hpp"
#include "knoblab/sim/knob.hpp"
#include "knoblab/sim/plant.hpp"

namespace knoblab::sim {

struct EffectSpec {
  std::string id;
  std::map<std::string, double> params;
  std::string text() const;  // back to "id:k=v,…"
};

// "id:k=v,k=v"; several separated by ';'. Throws std::invalid_argument on an
// unknown id or parameter, a value that is not a finite number, or one out
// of its effect's range (the message says which and why).
std::vector<EffectSpec> parse_effect_specs(std::string_view text);

// One spec from its id and parameters (a model file's effect, docs/
// discrepancy.md), checked as parse_effect_specs checks one.
EffectSpec make_effect_spec(const std::string& id, const std::map<std::string, double>& params);

// Folds a spec into the knob when it is one of its terms (spring,
// detent_shape, backlash, hysteresis, endstop) and returns true; false for
// the others.
bool apply_to_knob(const EffectSpec& spec, KnobParams& knob);

// Folds a spec into the rig when it acts there (compliance, time_delay,
// saturation) and returns true; false for the others. Call it once the knob
// is in `plant` (compliance:frequency reads its inertia). Throws
// std::invalid_argument when the knob side has no inertia to ring with.
bool apply_to_plant(const EffectSpec& spec, PlantConfig& plant);

// The KnobEffect of a torque spec (not one apply_to_knob or apply_to_plant
// takes). Setup time only.
std::unique_ptr<KnobEffect> make_knob_effect(const EffectSpec& spec);

}  // namespace knoblab::sim
