#include "knoblab/capture/calibration.hpp"

#include "knoblab/interchange/number_text.hpp"

namespace knoblab::capture {

namespace {
std::string num(double x) { return interchange::shortest(x); }
}  // namespace

std::string SensorCalibration::to_json() const {
  return "{\"counts_per_rev\": " + num(counts_per_rev) + ", \"torque_Nm_per_V\": " +
         num(torque_Nm_per_V) + ", \"torque_offset_V\": " + num(torque_offset_V) +
         ", \"C_cal\": " + num(C_cal) + ", \"gravity\": {\"A\": " + num(grav_A) +
         ", \"B\": " + num(grav_B) + ", \"C\": " + num(grav_C) + ", \"D\": " + num(grav_D) + "}}";
}

}  // namespace knoblab::capture
