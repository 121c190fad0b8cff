// One recorded sample in SI units: a row of the interchange CSV, a row of the
// store's samples table, and what the loop produces each cycle.
#pragma once

#include <cstdint>

namespace knoblab::interchange {

struct Sample {
  double t = 0.0;        // s since capture start
  double theta = 0.0;    // rad, encoder
  double omega = 0.0;    // rad/s (the loop's causal velocity estimate)
  double alpha = 0.0;    // rad/s², accelerometer, calibrated, gravity removed
  double torque = 0.0;   // N·m, torque sensor, offset removed
  double command = 0.0;  // V, amplifier command written this cycle
  std::uint32_t flags = 0;  // loop state (SampleFlag bits); the CSV's optional flags column
};

// Bits of Sample::flags: what the loop did and why, sample by sample.
enum SampleFlag : std::uint32_t {
  kAmpEnabled = 1u << 0,     // amplifier enable line driven high this cycle
  kEstopActive = 1u << 1,    // e-stop input asserted
  kFaultLatched = 1u << 2,   // the safety supervisor holds the safe state
  kTorqueLimited = 1u << 3,  // the command was clipped to the torque limit
};

}  // namespace knoblab::interchange
