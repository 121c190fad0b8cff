#include "knoblab/capture/sim_daq.hpp"

#include <stdexcept>

namespace knoblab::capture {

SimDaq::SimDaq(const sim::PlantConfig& config, double rate_hz) : plant_(config), dt_(1.0 / rate_hz), torque_offset_Nm_(config.torque_sensor.offset) {
  if (!(rate_hz > 0.0)) throw std::invalid_argument("SimDaq: rate must be positive");
}

IoStatus SimDaq::read(DaqInputs& in) {
  // The plant moves on whether or not its sensors can be read.
  const sim::SensorReadings& r = plant_.step(command_V_, dt_);
  if (fail_reads_.load(std::memory_order_relaxed)) {
    in = last_;
    return IoStatus::error;
  }
  in.encoder_counts = r.encoder_counts;
  in.torque_V = r.torque_volts;
  in.accel_V = r.accel_volts;
  last_ = in;
  return IoStatus::ok;
}

IoStatus SimDaq::write(const DaqOutputs& out) {
  if (fail_writes_.load(std::memory_order_relaxed)) return IoStatus::error;
  // A disabled amplifier drives no current, whatever the DAC says.
  command_V_ = out.amp_enable ? out.motor_command_V : 0.0;
  return IoStatus::ok;
}

SensorCalibration SimDaq::calibration() const {
  SensorCalibration c;
  c.counts_per_rev = static_cast<double>(plant_.encoder_scale().cpr);
  c.torque_Nm_per_V = 1.0 / plant_.torque_scale().volts_per_Nm;
  c.torque_offset_V = plant_.torque_scale().to_volts(torque_offset_Nm_);
  const sim::AccelCalibration a = plant_.accel_calibration();
  c.C_cal = a.C_cal;
  c.grav_A = a.A;
  c.grav_B = a.B;
  c.grav_C = a.C;
  c.grav_D = a.D;
  return c;
}

}  // namespace knoblab::capture
