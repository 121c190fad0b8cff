// The `sim` DAQ backend: the plant simulator behind the Daq interface,
// stepped in lock-step with loop time. Like real hardware, the command written
// in one cycle acts during the next (zero-order hold), and readings arrive as
// raw counts and volts that the loop must scale itself.
#pragma once

#include "knoblab/capture/calibration.hpp"
#include "knoblab/capture/daq.hpp"
#include "knoblab/sim/plant.hpp"

namespace knoblab::capture {

class SimDaq final : public Daq {
 public:
  SimDaq(const sim::PlantConfig& config, double rate_hz);

  void read(DaqInputs& in) override;
  void write(const DaqOutputs& out) override;

  // The calibration a technician would have measured on this (simulated)
  // camera: encoder scale, torque scale, C_cal and the gravity fit of Eq. 2.
  SensorCalibration calibration() const;
  const sim::Plant& plant() const { return plant_; }
  // Setup time only (before the loop runs): add effects to the plant.
  sim::Plant& plant() { return plant_; }

 private:
  sim::Plant plant_;
  double dt_;
  double torque_offset_Nm_;  // what taring the sensor at rest would find
  double command_V_ = 0.0;
};

}  // namespace knoblab::capture
