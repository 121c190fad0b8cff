#include "knoblab/capture/calibration.hpp"

#include <charconv>

namespace knoblab::capture {

namespace {
// Shortest text that reads back as the same double.
std::string num(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}
}  // namespace

std::string SensorCalibration::to_json() const {
  return "{\"counts_per_rev\": " + num(counts_per_rev) + ", \"torque_Nm_per_V\": " +
         num(torque_Nm_per_V) + ", \"torque_offset_V\": " + num(torque_offset_V) +
         ", \"C_cal\": " + num(C_cal) + ", \"gravity\": {\"A\": " + num(grav_A) +
         ", \"B\": " + num(grav_B) + ", \"C\": " + num(grav_C) + ", \"D\": " + num(grav_D) + "}}";
}

}  // namespace knoblab::capture
