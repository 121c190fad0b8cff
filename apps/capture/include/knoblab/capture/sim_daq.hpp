// The `sim` DAQ backend: the plant simulator behind the Daq interface,
// stepped in lock-step with loop time. Like real hardware, the command written
// in one cycle acts during the next (zero-order hold), and readings arrive as
// raw counts and volts that the loop must scale itself.
#pragma once

#include <atomic>

#include "knoblab/capture/calibration.hpp"
#include "knoblab/capture/daq.hpp"
#include "knoblab/sim/plant.hpp"

namespace knoblab::capture {

class SimDaq final : public Daq {
 public:
  SimDaq(const sim::PlantConfig& config, double rate_hz);

  IoStatus read(DaqInputs& in) override;
  IoStatus write(const DaqOutputs& out) override;

  // A pulled cable, simulated: while set, read() reports an error and keeps
  // the last readings (as a real board's driver does), or write() reports an
  // error and the amplifier keeps the last command. Any thread may call these.
  void set_read_failure(bool fail) { fail_reads_.store(fail, std::memory_order_relaxed); }
  void set_write_failure(bool fail) { fail_writes_.store(fail, std::memory_order_relaxed); }

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
  DaqInputs last_{};
  std::atomic<bool> fail_reads_{false}, fail_writes_{false};
};

}  // namespace knoblab::capture
