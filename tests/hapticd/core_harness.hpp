// HapticCore on the simulated camera, cycle by cycle, with every record kept:
// the state-machine and fault-matrix tests drive it into a state, send one
// event and look at the record of that cycle and the state after it.
#pragma once

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hapticd/core.hpp"
#include "knoblab/sim/presets.hpp"

namespace knoblab::hapticd::testing {

inline sim::PlantConfig plant_with(const char* knob) {
  sim::PlantConfig p;
  p.knob = *sim::presets::knob(knob);
  return p;
}

// The camera with nothing in its gripper (calibration runs). The unloaded
// camera still turns its gripper and sensor flange: with the bare 1e-6 kg·m²
// rotor of Eq. 3 the thesis PID (Kd = 1 V·s/rad) is unstable.
inline sim::PlantConfig free_shaft() {
  sim::PlantConfig p;
  p.load = sim::Load::Free;
  p.motor.extra_inertia = sim::presets::kHapticKnobInertia;
  return p;
}

class CoreHarness {
 public:
  static constexpr double kRate = 10000.0;

  explicit CoreHarness(const sim::PlantConfig& plant = plant_with("moderate-detents"))
      : daq_(plant, kRate), core_(core_config(daq_)) {}

  capture::SimDaq& daq() { return daq_; }
  HapticCore& core() { return core_; }
  CycleContext ctx;  // what the lines, Modbus and timing say from now on
  bool torque_channel_nan = false;  // a broken conversion on the torque channel

  void post(const CoreCommand& c) {
    if (!core_.post(c)) throw std::runtime_error("core command queue full");
  }
  void command(CoreCommand::Kind kind, Mode mode = Mode::Idle) {
    CoreCommand c;
    c.kind = kind;
    c.mode = mode;
    post(c);
  }
  void set_render(double B_vel, double A_pos) {
    CoreCommand c;
    c.kind = CoreCommand::SetRender;
    c.immediate = true;
    c.render.B_vel = B_vel;
    c.render.A_pos = A_pos;
    c.render.P_pos = 1.0 / 12.0;
    post(c);
  }
  CoreCommand capture_command(std::int64_t cycles) const {
    CoreCommand c;
    c.kind = CoreCommand::StartCapture;
    capture::CaptureConfig cc;
    cc.rate_hz = kRate;
    c.capture = capture::CaptureController(cc);
    c.capture_cycles = cycles;
    return c;
  }
  // `seconds`: the sweep's length, or for gravity one revolution's.
  CoreCommand calibration_command(double seconds, CalibrationKind kind = CalibrationKind::Spatial) const {
    CoreCommand c;
    c.kind = CoreCommand::StartCalibration;
    CalibrationConfig cc;
    cc.kind = kind;
    cc.rate_hz = kRate;
    cc.calibration = daq_.calibration();
    cc.sweep_seconds = seconds;
    cc.gravity_seconds = seconds;
    c.calibration = CalibrationController(cc);
    return c;
  }
  void start_capture(std::int64_t cycles) { post(capture_command(cycles)); }
  void start_calibration(double seconds) { post(calibration_command(seconds)); }

  // One cycle as the daemon runs it: read, cycle, write.
  LoopRecord step() {
    capture::DaqInputs in;
    CycleContext c = ctx;
    c.io_ok = ctx.io_ok && daq_.read(in) == capture::IoStatus::ok && writes_ok_;
    if (torque_channel_nan) in.torque_V = std::numeric_limits<double>::quiet_NaN();
    capture::DaqOutputs out;
    LoopRecord rec;
    core_.cycle(in, c, out, rec);
    writes_ok_ = daq_.write(out) == capture::IoStatus::ok;  // judged next cycle, as the daemon does
    last_out = out;
    records.push_back(rec);
    return rec;
  }
  void run(int cycles) {
    for (int i = 0; i < cycles; ++i) step();
  }

  capture::DaqOutputs last_out{};
  std::vector<LoopRecord> records;

 private:
  static CoreConfig core_config(const capture::SimDaq& daq) {
    CoreConfig c;
    c.rate_hz = kRate;
    c.calibration = daq.calibration();
    return c;
  }

  capture::SimDaq daq_;
  HapticCore core_;
  bool writes_ok_ = true;
};

}  // namespace knoblab::hapticd::testing
