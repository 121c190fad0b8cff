// Small test scaffolding: a PD position loop on the encoder, as hapticd's
// controller would close it around the plant.
#pragma once

#include "knoblab/sim/plant.hpp"

namespace knoblab::sim::test {

struct PositionLoop {
  double kp = 300.0;  // V/rad   (≈ 4.5 N·m/rad through 0.0151 N·m/V)
  double kd = 1.0;    // V·s/rad
  double prev = 0.0;
  double omega = 0.0;  // filtered encoder velocity

  // Command for the plant to follow theta_ref / omega_ref, from readings.
  double command(const Plant& p, double theta_ref, double omega_ref, double dt) {
    const double theta = p.encoder_scale().to_angle(p.readings().encoder_counts);
    const double raw = (theta - prev) / dt;
    prev = theta;
    omega += (raw - omega) * 0.2;  // ~300 Hz low-pass at 10 kHz
    return kp * (theta_ref - theta) + kd * (omega_ref - omega);
  }
};

inline PlantConfig quiet(PlantConfig c) {
  c.torque_sensor.noise_sigma = 0.0;
  c.accel.noise_pp_fraction = 0.0;
  return c;
}

}  // namespace knoblab::sim::test
