// Accepting a calibration: the thesis ran each calibration three times and
// used the average (§2.2.1: "three independent accelerometer calibrations
// … an averaged C_cal"). average_runs() takes the latest good runs of one
// kind made with the constants in use now, and gives the constants with
// their average put in, with the spread across runs for the record.
#pragma once

#include <span>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "knoblab/capture/calibration.hpp"
#include "knoblab/hapticd/calibration_controller.hpp"

namespace knoblab::hapticd {

struct AveragedValue {
  std::string name;  // "C_cal", "grav_A", …
  double mean = 0.0;
  double sd = 0.0;   // across runs (0 for one run)
  std::vector<double> runs;
};

struct AcceptedCalibration {
  CalibrationKind kind = CalibrationKind::AccelGain;
  capture::SensorCalibration before{}, after{};
  std::vector<AveragedValue> values;
  double unix_time = 0.0;  // when it was accepted
};

// Kinds whose fit changes the constants: accel_gain (C_cal) and gravity
// (Eq. 2's A, C, D; B = 1). spatial and torque only verify (Table 4).
bool changes_constants(CalibrationKind kind);

// `history`: ended runs, oldest first. Runs that failed, were stopped,
// latched a fault, or used other constants than `in_use` are skipped. The
// averaged calibration, or why there is none (a sentence for the user).
std::variant<AcceptedCalibration, std::string> average_runs(std::span<const CalibrationResult> history,
                                                            CalibrationKind kind, int repetitions,
                                                            const capture::SensorCalibration& in_use);

// As the protocol and the calibration file write it.
nlohmann::json to_json(const AcceptedCalibration& a);

}  // namespace knoblab::hapticd
