// What the I/O board delivers once per control-loop tick.
#pragma once

#include <cstdint>

#include "knoblab/sim/accelerometer.hpp"
#include "knoblab/sim/encoder.hpp"
#include "knoblab/sim/torque_sensor.hpp"

namespace knoblab::sim {

struct SensorReadings {
  double t = 0.0;                  // s, plant time of the sample
  std::int64_t encoder_counts = 0; // motor shaft, EncoderScale
  double torque_volts = 0.0;       // ADC volts, TorqueSensorScale
  double torque = 0.0;             // N·m = scale.to_torque(torque_volts), offset included
  double accel_volts = 0.0;        // ADC volts, AccelCalibration
};

}  // namespace knoblab::sim
