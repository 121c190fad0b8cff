// Render mode: the knob feels like the rendering model of thesis Eq. 14 —
// virtual-mass inertia (§3.3), damping, detents — plus the optional Karnopp
// stick band (Eq. 7) and the effect library's renderable terms (a new set
// fades out the old one, then in, each over half the ramp). Velocity is the front end's rendering filter (the
// 10th-order Butterworth of §1.2.2 at 500 Hz, "Low Pass 1"), τ_acc goes
// through the 3-sample box ("Low Pass 2"). Prototyper tiles cross-fade: a
// new set fades in while the old one fades out, linearly over the ramp.
// Construction allocates; update() and set_params() never do.
#pragma once

#include "knoblab/capture/daq.hpp"
#include "knoblab/capture/sample.hpp"
#include "knoblab/capture/sensor_front_end.hpp"
#include "knoblab/hapticd/handoff.hpp"
#include "knoblab/hapticd/param_ramp.hpp"
#include "knoblab/hapticd/render_params.hpp"
#include "knoblab/hapticd/tile_set.hpp"
#include "knoblab/hapticd/virtual_mass.hpp"
#include "knoblab/model/filters.hpp"
#include "knoblab/model/render_stability.hpp"

namespace knoblab::hapticd {

struct RenderConfig {
  double rate_hz = 10000.0;
  double torque_per_volt = 0.181 / 12.0;  // N·m per command volt (amplifier + motor)
};

class RenderController {
 public:
  explicit RenderController(const RenderConfig& cfg);

  // New targets; reached by a ramp (bumpless) unless `immediately`.
  void set_params(const RenderParams& p, bool immediately = false);
  const RenderParams& target() const { return target_; }

  // Start afresh from where the knob is (entering render mode).
  void reset();

  // Non-realtime: render these tiles on top of the model from the next
  // cycle on (nullptr: none), cross-fading from the set before over
  // kParamRampSeconds (no step in torque while playing). False while the
  // previous set is still being handed over or faded in (`tiles` then stays
  // with the caller); retry a cycle later.
  bool load_tiles(std::unique_ptr<TileSet>&& tiles) { return tiles_.publish(std::move(tiles)); }
  // Realtime, every cycle whatever the mode: takes a set offered by
  // load_tiles, so tiles load (and their time starts) in any mode.
  void take_tiles();

  void update(const capture::SensorReading& in, capture::DaqOutputs& out, capture::Sample& s);

  // The linearised loop this renderer runs (rate, render velocity filter),
  // held by the default grip: what load_tiles' stability check tests.
  static model::LoopDynamics loop_dynamics(double rate_hz);

 private:
  RenderConfig cfg_;
  double dt_;
  int ramp_cycles_;
  RenderParams target_{};
  ParamRamp M_, B_, A_, f_;  // f = detents per revolution = 1/P (0 = none)
  model::EffectSet<double> effects_{}, next_effects_{};
  bool effects_pending_ = false;  // next_effects_ waits for effects_ to fade out
  ParamRamp effects_gain_{1.0};
  model::BoxFilter3 acc_box_;
  VirtualMass vm_;
  bool started_ = false;  // false: the next update places the virtual mass at the knob
  long long cycle_ = 0;
  Handoff<TileSet> tiles_;
  const TileSet* active_tiles_ = nullptr;
  double tiles_start_t_ = 0.0;
  const TileSet* previous_tiles_ = nullptr;  // fading out while tiles_ holds it
  double previous_start_t_ = 0.0;
  ParamRamp tiles_fade_{1.0};  // weight of active_tiles_; the previous set has 1 − it
  double prev_omega_ = 0.0;
  model::BoxFilter3 alpha_box_;  // acceleration for f_acc tiles
};

}  // namespace knoblab::hapticd
