#include "knoblab/hapticd/calibration_file.hpp"

#include "knoblab/hal/config_reader.hpp"
#include "knoblab/hal/factory.hpp"
#include "knoblab/interchange/atomic_file.hpp"

namespace knoblab::hapticd {

CalibrationFile read_calibration_file(const std::filesystem::path& path) {
  const nlohmann::json j = hal::load_config_file(path);
  hal::detail::ConfigReader r(j, "calibration");
  // A misspelt key is named before the key it was meant to be is missed.
  for (const char* key : {"counts_per_rev", "torque_Nm_per_V", "torque_offset_V", "C_cal", "gravity", "accepted"})
    (void)r.has(key);
  r.finish();
  CalibrationFile f;
  capture::SensorCalibration& c = f.constants;
  c.counts_per_rev = r.number("counts_per_rev");
  c.torque_Nm_per_V = r.number("torque_Nm_per_V");
  c.torque_offset_V = r.number("torque_offset_V");
  c.C_cal = r.number("C_cal");
  if (!(c.counts_per_rev > 0.0)) r.fail("counts_per_rev", "must be positive");
  hal::detail::ConfigReader g = r.object("gravity");
  for (const char* key : {"A", "B", "C", "D"}) (void)g.has(key);
  g.finish();
  c.grav_A = g.number("A");
  c.grav_B = g.number("B");
  c.grav_C = g.number("C");
  c.grav_D = g.number("D");
  if (c.grav_B == 0.0) g.fail("B", "must not be 0 (Eq. 2 divides by it)");
  if (const nlohmann::json* accepted = r.find("accepted")) {
    if (!accepted->is_object()) r.fail("accepted", "must be an object");
    f.accepted = *accepted;
  }
  return f;
}

void write_calibration_file(const std::filesystem::path& path, const CalibrationFile& file) {
  nlohmann::json j = nlohmann::json::parse(file.constants.to_json());
  j["accepted"] = file.accepted;
  interchange::write_file_atomically(path, j.dump(2) + "\n");
}

}  // namespace knoblab::hapticd
