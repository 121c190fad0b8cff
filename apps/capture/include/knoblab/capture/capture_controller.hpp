// Capture mode: drive the knob along the swept sine of thesis Eq. 8, centred
// where the knob stands at the start, with the PID of Eq. 4 (position stimulus), or push it with a swept-sine torque open
// loop (torque stimulus), and turn each cycle's raw readings into a Sample.
// Runs inside the loop: construction allocates, update() never does.
#pragma once

#include "knoblab/capture/calibration.hpp"
#include "knoblab/capture/daq.hpp"
#include "knoblab/capture/pid.hpp"
#include "knoblab/capture/sample.hpp"
#include "knoblab/capture/sensor_front_end.hpp"
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
};

class CaptureController {
 public:
  explicit CaptureController(const CaptureConfig& cfg = {});

  // One cycle: the front end's readings in (sensor_front_end.hpp), command
  // out, the cycle's sample recorded (t counted from the capture's start).
  void update(const SensorReading& in, DaqOutputs& out, Sample& sample);

  const CaptureConfig& config() const { return cfg_; }

 private:
  CaptureConfig cfg_;
  Pid pid_;
  long long cycle_ = 0;
  double theta0_ = 0.0;  // rad, where the knob stood at the first cycle
};

}  // namespace knoblab::capture
