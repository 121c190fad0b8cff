// What the realtime loop reports each cycle, and what the display receives
// after decimation. SI units throughout.
#pragma once

#include <cstdint>

namespace knoblab::control {

// One loop cycle (e.g. 10 kHz).
struct TelemetrySample {
  double t = 0.0;          // s, daemon monotonic time
  double theta = 0.0;      // rad
  double omega = 0.0;      // rad/s
  double torque = 0.0;     // N·m, measured
  double command = 0.0;    // N·m, commanded
  std::uint32_t mode = 0;  // 0 idle, 1 render, 2 capture, 3 calibrate (set_mode order)
  std::uint32_t fault_bits = 0;
};

// One decimation window (e.g. 10 cycles → 1 kHz). The window's last sample,
// plus what a plain subsample would hide: the torque extremes and every
// fault bit seen in the window.
struct TelemetryRecord {
  double t = 0.0;
  double theta = 0.0;
  double omega = 0.0;
  double torque = 0.0;      // last sample's
  double torque_min = 0.0;  // over the window
  double torque_max = 0.0;  // over the window
  double command = 0.0;
  std::uint32_t mode = 0;
  std::uint32_t fault_bits = 0;  // OR over the window
};
static_assert(sizeof(TelemetryRecord) == 64);

}  // namespace knoblab::control
