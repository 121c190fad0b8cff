// Conversion of raw DAQ readings to SI, with the constants a capture stores
// so that it can be undone or redone later.
//   θ = counts · 2π / CPR
//   τ = (V − offset) · (175.5 mN·m / 5 V)                      (thesis §1.2.4)
//   θ̈ = C_cal · V − [A·sin(θ/B + C) + D]                       (Eq. 12, Eq. 2)
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

namespace knoblab::capture {

struct SensorCalibration {
  double counts_per_rev = 640000.0;
  double torque_Nm_per_V = 0.1755 / 5.0;
  double torque_offset_V = 0.0;
  double C_cal = 1148.0;  // (rad/s²)/V
  // Gravity compensation, Eq. 2, in rad/s² (after C_cal).
  double grav_A = 0.0, grav_B = 1.0, grav_C = 0.0, grav_D = 0.0;

  double theta(std::int64_t counts) const {
    return static_cast<double>(counts) * (2.0 * std::numbers::pi / counts_per_rev);
  }
  double torque(double volts) const { return (volts - torque_offset_V) * torque_Nm_per_V; }
  double gravity(double theta) const { return grav_A * std::sin(theta / grav_B + grav_C) + grav_D; }
  double alpha(double volts, double theta) const { return C_cal * volts - gravity(theta); }

  std::string to_json() const;
  bool operator==(const SensorCalibration&) const = default;
};

}  // namespace knoblab::capture
