#include "knoblab/capture/calibration.hpp"

#include <cstdio>

namespace knoblab::capture {

std::string SensorCalibration::to_json() const {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "{\"counts_per_rev\": %.17g, \"torque_Nm_per_V\": %.17g, "
                "\"torque_offset_V\": %.17g, \"C_cal\": %.17g, "
                "\"gravity\": {\"A\": %.17g, \"B\": %.17g, \"C\": %.17g, \"D\": %.17g}}",
                counts_per_rev, torque_Nm_per_V, torque_offset_V, C_cal, grav_A, grav_B,
                grav_C, grav_D);
  return buf;
}

}  // namespace knoblab::capture
