// The loop's one sensor chain, run every cycle before the mode, whatever the
// mode (as ros2_control's state interfaces are read before any controller):
// encoder counts → θ; Eq. 1's backward difference → a 10th-order Butterworth
// → ω (thesis §1.2.2); accelerometer volts → α (C_cal, gravity of Eq. 2);
// torque-sensor volts → τ. Because it never restarts, a mode change does not
// reset the velocity filter, and idle mode records the knob turned by hand.
//
// Two velocity filters run side by side: the analysis cutoff of Table 6
// (1 kHz; captures, calibration, the velocity limit) and the rendering
// cutoff of Study 3 (500 Hz, §4.6), so switching mode never starts a filter
// from rest. Construction designs the filters (allocates); update() never does.
#pragma once

#include "knoblab/capture/calibration.hpp"
#include "knoblab/capture/daq.hpp"
#include "knoblab/model/filters.hpp"

namespace knoblab::capture {

struct SensorConfig {
  double rate_hz = 10000.0;
  SensorCalibration calibration{};
  int velocity_filter_order = 10;
  double velocity_cutoff_hz = 1000.0;        // Table 6
  double render_velocity_cutoff_hz = 500.0;  // Study 3
};

// One cycle's readings in SI units.
struct SensorReading {
  double theta = 0.0;         // rad
  double omega = 0.0;         // rad/s, analysis filter
  double omega_render = 0.0;  // rad/s, rendering filter
  double alpha = 0.0;         // rad/s², accelerometer, gravity removed
  double torque = 0.0;        // N·m
  double accel_V = 0.0;       // the accelerometer's raw volts (calibration fits C_cal on them)
};

class SensorFrontEnd {
 public:
  explicit SensorFrontEnd(const SensorConfig& cfg);

  // The first reading ever has no predecessor: its raw velocity is 0.
  const SensorReading& update(const DaqInputs& in);
  const SensorReading& last() const { return reading_; }
  const SensorConfig& config() const { return cfg_; }
  // New constants from the next update on (an accepted calibration). The
  // filters keep running: only the scale of what they are fed changes.
  void set_calibration(const SensorCalibration& c) noexcept { cfg_.calibration = c; }

 private:
  SensorConfig cfg_;
  double dt_;
  model::SosCascade velocity_filter_;
  model::SosCascade render_velocity_filter_;
  bool have_prev_ = false;
  double prev_theta_ = 0.0;
  SensorReading reading_{};
};

}  // namespace knoblab::capture
