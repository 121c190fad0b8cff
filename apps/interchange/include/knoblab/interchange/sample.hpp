// One recorded sample in SI units: a row of the interchange CSV, a row of the
// store's samples table, and what the loop produces each cycle.
#pragma once

namespace knoblab::interchange {

struct Sample {
  double t = 0.0;        // s since capture start
  double theta = 0.0;    // rad, encoder
  double omega = 0.0;    // rad/s (the loop's causal velocity estimate)
  double alpha = 0.0;    // rad/s², accelerometer, calibrated, gravity removed
  double torque = 0.0;   // N·m, torque sensor, offset removed
  double command = 0.0;  // V, amplifier command written this cycle
};

}  // namespace knoblab::interchange
