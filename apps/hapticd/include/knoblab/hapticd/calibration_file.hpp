// The sensor calibration hapticd starts with and keeps (hapticd
// --calibration FILE, on the data partition in the image): the constants of
// capture::SensorCalibration, and what was accepted when. Read strictly (an
// unknown key or a missing constant is an error naming it, so a typo never
// leaves a default in use silently); written atomically, so a power cut
// during an accept leaves the previous file.
//
//   {"counts_per_rev": 640000, "torque_Nm_per_V": 0.0351, "torque_offset_V": 0,
//    "C_cal": 1148, "gravity": {"A": 0, "B": 1, "C": 0, "D": 0},
//    "accepted": {"accel_gain": {…as accept_calibration replies…}}}
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "knoblab/capture/calibration.hpp"

namespace knoblab::hapticd {

struct CalibrationFile {
  capture::SensorCalibration constants{};
  nlohmann::json accepted = nlohmann::json::object();  // kind → accept record
};

// Throws hal::ConfigError (a std::runtime_error) naming the file or the key
// ("calibration.gravity.B: …") and the problem.
CalibrationFile read_calibration_file(const std::filesystem::path& path);
void write_calibration_file(const std::filesystem::path& path, const CalibrationFile& file);

}  // namespace knoblab::hapticd
