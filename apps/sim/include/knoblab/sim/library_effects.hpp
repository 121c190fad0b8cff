// The effect library (knoblab/model/effects.hpp) on the simulated knob, so a
// capture can carry physics the thesis model leaves out: what discrepancy
// discovery must find (the concealed-effect benchmark's captures). The specs,
// their parameters, ranges and defaults are the effect table's
// (knoblab/model/effect_table.hpp, docs/discrepancy.md "Effects"): the names
// discrepancy reports, so a finding's params can be given back.
//
//   "stribeck:static_excess_Nm=0.002,stribeck_velocity_rad_s=0.1"
//                                      → a KnobEffect with those parameters
//   "spring:stiffness_Nm_per_rad=0.01" → folded into KnobParams (a model term)
//   "time_delay:delay_s=0.001"         → folded into PlantConfig (rig, not knob)
//
// Where each goes is the table's `acts`: knob torques become KnobEffects,
// knob structure (spring, detent_shape, backlash, hysteresis, endstop) folds
// into KnobParams, the coupling (compliance) and the torque sensor
// (time_delay, saturation) into PlantConfig. compliance takes stiffness or
// frequency_hz (the knob ringing against a held motor, k = J·(2πf)²,
// J = M + gripper) and at most one of damping and zeta (the damping ratio
// there); without either the coupling keeps its damping ratio.
#pragma once

#include <memory>

#include "knoblab/model/effect_table.hpp"
#include "knoblab/sim/effects.hpp"
#include "knoblab/sim/knob.hpp"
#include "knoblab/sim/plant.hpp"

namespace knoblab::sim {

// Folds a spec into the knob when it is one of its terms (the table's
// Acts::KnobStructure) and returns true; false for the others.
bool apply_to_knob(const model::EffectSpec& spec, KnobParams& knob);

// Folds a spec into the rig when it acts there (Acts::Coupling,
// Acts::TorqueSensor) and returns true; false for the others. Call it once
// the knob is in `plant` (compliance:frequency_hz reads its inertia). Throws
// std::invalid_argument when the knob side has no inertia to ring with.
bool apply_to_plant(const model::EffectSpec& spec, PlantConfig& plant);

// The KnobEffect of a torque spec (Acts::KnobTorque). Setup time only.
std::unique_ptr<KnobEffect> make_knob_effect(const model::EffectSpec& spec);

}  // namespace knoblab::sim
