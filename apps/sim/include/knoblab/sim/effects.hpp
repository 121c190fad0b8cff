// Extension point for knob effects beyond the thesis model (Stribeck,
// cogging, hysteresis, drift, …): a KnobEffect adds a torque to the knob.
//
// Contract:
//  * torque() returns the torque needed to move the knob (N·m), with the sign
//    convention of knoblab/model/terms.hpp. It counts as non-frictional: it
//    joins the detents/spring/walls in τ_other of the Karnopp stick test.
//  * It is called once per substep from the realtime loop: no allocation, no
//    locks, no I/O. Build the physics from knoblab_model terms.
//  * advance() lets stateful effects move on after the substep; reset()
//    returns them to t = 0.
// Effects that are not a knob torque get their own seam rather than this
// interface: friction laws and play in KnobParams (presliding hysteresis,
// backlash, walls), compliance in CouplingParams, the torque channel's delay
// and clipping in TorqueSensorParams (library_effects.hpp says which).
#pragma once

#include "knoblab/model/terms.hpp"

namespace knoblab::sim {

using KnobMotion = model::Kinematics<double>;

class KnobEffect {
 public:
  virtual ~KnobEffect() = default;
  virtual double torque(const KnobMotion& knob, double t) const = 0;
  virtual void advance(const KnobMotion& knob, double t, double h) {
    (void)knob;
    (void)t;
    (void)h;
  }
  virtual void reset() {}
};

}  // namespace knoblab::sim
