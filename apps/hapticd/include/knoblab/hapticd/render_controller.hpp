// Render mode: the knob feels like the rendering model of thesis Eq. 14 —
// virtual-mass inertia (§3.3), damping, detents — plus the optional Karnopp
// stick band (Eq. 7). Velocity through the 10th-order Butterworth of §1.2.2
// ("Low Pass 1"), τ_acc through the 3-sample box ("Low Pass 2").
// Construction allocates; update() and set_params() never do.
#pragma once

#include "knoblab/capture/calibration.hpp"
#include "knoblab/capture/daq.hpp"
#include "knoblab/capture/sample.hpp"
#include "knoblab/hapticd/param_ramp.hpp"
#include "knoblab/hapticd/render_params.hpp"
#include "knoblab/hapticd/virtual_mass.hpp"
#include "knoblab/model/filters.hpp"

namespace knoblab::hapticd {

struct RenderConfig {
  double rate_hz = 10000.0;
  capture::SensorCalibration calibration{};
  double torque_per_volt = 0.181 / 12.0;  // N·m per command volt (amplifier + motor)
  int velocity_filter_order = 10;
  double velocity_cutoff_hz = 500.0;  // Study 3 (§4.6): 500 Hz
};

class RenderController {
 public:
  explicit RenderController(const RenderConfig& cfg);

  // New targets; reached by a ramp (bumpless) unless `immediately`.
  void set_params(const RenderParams& p, bool immediately = false);
  const RenderParams& target() const { return target_; }

  // Forget the motion history (entering render mode).
  void reset();

  void update(const capture::DaqInputs& in, capture::DaqOutputs& out, capture::Sample& s);

  // The model torque of the last cycle (sensor convention), for tests.
  double last_model_torque() const { return last_model_torque_; }

 private:
  RenderConfig cfg_;
  double dt_;
  int ramp_cycles_;
  RenderParams target_{};
  ParamRamp M_, B_, A_, f_;  // f = detents per revolution = 1/P (0 = none)
  model::SosCascade velocity_filter_;
  model::BoxFilter3 acc_box_;
  VirtualMass vm_;
  bool have_prev_ = false;
  double prev_theta_ = 0.0;
  long long cycle_ = 0;
  double last_model_torque_ = 0.0;
};

}  // namespace knoblab::hapticd
