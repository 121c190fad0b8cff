// Calibrate mode: the sensor verification and calibration runs of thesis
// §2.2.1 (Table 3 swept sines, Table 4 statistics, Eq. 12 C_cal) and the
// gravity compensation of §1.2.3 (Eq. 2), as a loop controller with the same
// update(in, out, sample) contract as capture::CaptureController.
//
//   spatial     Table 3 spatial sweep (0, 1.5, 1.0, 3.0) tracked by the PID
//               (Eq. 4) on a free shaft: Table 4 θ, ω, α errors.
//   accel_gain  the same run; C_cal by least squares (Eq. 12) of the
//               commanded acceleration on the raw accelerometer volts.
//   torque      Table 3 torque sweep (0, 1.5, 0.02, 3.0) with the gripper
//               anchored: commanded torque (previous cycle's command volts ×
//               torque-per-volt, the DAC's zero-order hold) vs measured.
//   gravity     one slow constant-velocity revolution each way (thesis:
//               ~16 s), PID-tracked; Eq. 2 fitted to C_cal·V − α_ref.
//
// Where the fit happens: nowhere in the loop. update() only folds each sample
// into fixed-size sufficient statistics (running moments and normal
// equations: the fitting core's accumulators, knoblab/fit/calibration.hpp)
// held inside the controller itself, so there is no sample buffer, nothing
// allocates, and the controller stays trivially copyable (it travels in a
// CoreCommand). When the run ends, the core publishes data() through a
// seqlock; non-realtime code turns it into fitted values, with their 95%
// confidence intervals, by evaluate() (which solves the small systems and
// reports "too little data").
//
// All references are relative to the angle the shaft is at when the run
// starts (θ₀); gravity phases are in absolute encoder angle.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "knoblab/capture/calibration.hpp"
#include "knoblab/capture/daq.hpp"
#include "knoblab/capture/pid.hpp"
#include "knoblab/capture/sample.hpp"
#include "knoblab/capture/sensor_front_end.hpp"
#include "knoblab/fit/calibration.hpp"
#include "knoblab/model/trajectory.hpp"

namespace knoblab::hapticd {

enum class CalibrationKind : std::uint8_t { Spatial, Torque, AccelGain, Gravity };
const char* to_string(CalibrationKind k);
// "spatial" | "torque" | "accel_gain" | "gravity"; nullopt otherwise.
std::optional<CalibrationKind> parse_calibration_kind(std::string_view s);

struct CalibrationConfig {
  CalibrationKind kind = CalibrationKind::Spatial;
  double rate_hz = 10000.0;
  capture::SensorCalibration calibration{};  // the constants in use (C_cal, Eq. 2 …)
  capture::PidGains pid{};
  double torque_per_volt = 0.181 / 12.0;  // N·m per command volt (amplifier, current mode)
  double sweep_seconds = 5.0;             // spatial / torque / accel_gain (thesis: 5 s)
  double gravity_seconds = 16.0;          // per direction: one revolution in this time
  double gravity_ramp_seconds = 0.5;      // velocity ramps (+ as long settling), not fitted
};

// What a run accumulated (trivially copyable; published by the loop).
struct CalibrationData {
  CalibrationKind kind = CalibrationKind::Spatial;
  bool complete = false;          // ran all its cycles (false: stopped early)
  std::uint32_t flags_seen = 0;   // OR of the samples' interchange flags
  std::int64_t cycles = 0;        // cycles run
  double theta0 = 0.0;            // rad, where the run started
  capture::SensorCalibration calibration{};  // the constants in use during the run
  fit::RunningStats theta{}, omega{}, alpha{}, torque{};  // commanded − measured
  fit::AccelGainAccumulator accel{true};
  fit::GravityAccumulator gravity{};
};

// The fitted values, for non-realtime code.
struct CalibrationResult {
  CalibrationKind kind = CalibrationKind::Spatial;
  bool complete = false;
  bool fault = false;          // the supervisor latched a fault during the run
  bool torque_limited = false; // some command was clipped by the torque limit
  std::int64_t cycles = 0;
  fit::Table4 table4{};        // channels the run did not measure have n = 0
  std::optional<fit::AccelGainFit> accel;  // accel_gain
  std::optional<fit::GravityFit> gravity;  // gravity
  capture::SensorCalibration in_use{};   // the constants during the run
  capture::SensorCalibration updated{};  // the run's constants with the fitted ones put in
  std::string error;           // empty when the run and its fits are usable
  bool ok() const { return error.empty(); }
};

// Non-realtime: solve the fits. Never throws; problems go to `error`.
CalibrationResult evaluate(const CalibrationData& d);

class CalibrationController {
 public:
  // An empty controller (no run): cheap, so a default CoreCommand costs nothing.
  CalibrationController() = default;
  // May throw std::invalid_argument (bad rate or durations): call it
  // outside the loop.
  explicit CalibrationController(const CalibrationConfig& cfg);

  // One cycle: the front end's readings in, command out, the cycle's sample
  // recorded.
  void update(const capture::SensorReading& in, capture::DaqOutputs& out, capture::Sample& sample);
  // After the supervisor: what was really sent (the next cycle's commanded
  // torque) and the sample's flags.
  void after_output(const capture::DaqOutputs& out, std::uint32_t flags);

  // How many cycles the run takes; the core then returns to Idle.
  std::int64_t cycles() const { return total_cycles_; }
  double seconds() const { return static_cast<double>(total_cycles_) / cfg_.rate_hz; }
  const CalibrationConfig& config() const { return cfg_; }
  // The accumulated statistics so far; complete once cycles() have run.
  CalibrationData data() const;

  struct Reference {
    double theta = 0.0, omega = 0.0, alpha = 0.0;  // relative to θ₀
    bool fit = false;   // gravity: inside a fitted window
    bool ccw = false;   // gravity: θ decreasing
  };
  // The reference at time t (s) since the start (exposed for tests).
  Reference reference(double t) const;

 private:
  CalibrationConfig cfg_;
  model::SweptSine stimulus_{};
  capture::Pid pid_;
  std::int64_t total_cycles_ = 0;
  std::int64_t cycle_ = 0;
  double last_command_V_ = 0.0;
  CalibrationData data_{};
};

}  // namespace knoblab::hapticd
