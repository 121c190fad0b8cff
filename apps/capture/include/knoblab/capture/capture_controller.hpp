// Capture mode: drive the knob along the swept sine of thesis Eq. 8 with the
// PID of Eq. 4 (position stimulus), or push it with a swept-sine torque open
// loop (torque stimulus), and turn each cycle's raw readings into a Sample.
// Runs inside the loop: construction allocates, update() never does.
#pragma once

#include "knoblab/capture/calibration.hpp"
#include "knoblab/capture/daq.hpp"
#include "knoblab/capture/pid.hpp"
#include "knoblab/capture/sample.hpp"
#include "knoblab/model/filters.hpp"
#include "knoblab/model/trajectory.hpp"

namespace knoblab::capture {

struct CaptureConfig {
  enum class Stimulus { Position, Torque };
  double rate_hz = 5000.0;
  Stimulus kind = Stimulus::Position;
  model::SweptSine stimulus = model::SweptSine::spatial();  // Position: θ_ref(t)
  model::TorqueSweep torque_stimulus{};                      // Torque: τ(t), N·m
  double torque_per_volt = 0.181 / 12.0;  // amplifier + motor, N·m per command volt
  PidGains pid{};
  SensorCalibration calibration{};
  // Velocity: difference of encoder angle, then a 10th-order Butterworth
  // (thesis §1.2.2). Cutoff 1 kHz as Table 6, or lower at slow loop rates.
  int velocity_filter_order = 10;
  double velocity_cutoff_hz = 1000.0;
};

class CaptureController {
 public:
  explicit CaptureController(const CaptureConfig& cfg = {});

  // One cycle: raw inputs in, command out, the cycle's sample recorded.
  void update(const DaqInputs& in, DaqOutputs& out, Sample& sample);

  const CaptureConfig& config() const { return cfg_; }

 private:
  CaptureConfig cfg_;
  Pid pid_;
  model::SosCascade velocity_filter_;
  long long cycle_ = 0;
  double prev_theta_ = 0.0;
};

}  // namespace knoblab::capture
