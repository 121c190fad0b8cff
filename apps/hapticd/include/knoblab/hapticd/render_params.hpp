// What the renderer renders: the rendering model of thesis Eq. 14 with the
// optional Karnopp stick band (Eq. 7), the effect library's renderable terms
// (model/effect_set.hpp), the virtual-mass coupling of §3.3 and prototyper
// tiles by id. SI units.
#pragma once

#include <string>

#include "knoblab/model/effect_set.hpp"

namespace knoblab::hapticd {

struct RenderParams {
  double M_acc = 0.0;   // kg·m², rendered inertia (virtual mass)
  double B_vel = 0.0;   // N·m·s/rad, damping
  double A_pos = 0.0;   // N·m, detent amplitude
  double P_pos = 1.0;   // rad per radian of phase: detents per revolution = 1/P
  // Karnopp stick band; needs the torque sensor to know what the hand applies.
  bool stick = false;
  double dv = 0.0, D_neg = 0.0, D_pos = 0.0;
  // Beyond Eq. 14: what discrepancy discovery found (load_model's "effects").
  model::EffectSet<double> effects;
  // Virtual-mass coupling (§3.3). The thesis prints K_vm = 12 000 and
  // B_vm = 88 "Nm/rad"; read as mN·m that is 12 N·m/rad and 0.088 N·m·s/rad.
  // The coupling's damper acts on the render velocity like any damping, and
  // 0.088 is five times what this loop renders stably (about 0.017 N·m·s/rad
  // at 10 kHz with the 500 Hz velocity filter, model/render_stability.hpp):
  // a mass rendered with it rang the simulated knob at the torque limit (so
  // did 0.01); 0.004 N·m·s/rad settles, with the same K_vm.
  double K_vm = 12.0;
  double B_vm = 0.004;
};

// Why something cannot be rendered: the offending argument's key (as the
// protocol names it) and a sentence for the user.
struct ParamProblem {
  std::string key;
  std::string message;
};

// A time for slider moves to settle: a new value is reached by a linear ramp
// over this time, so a drag never makes a torque step (bumpless).
inline constexpr double kParamRampSeconds = 0.05;

}  // namespace knoblab::hapticd
