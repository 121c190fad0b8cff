#include "knoblab/hapticd/sim_time_loop.hpp"

namespace knoblab::hapticd {

namespace {

CoreConfig core_config(const capture::SimDaq& daq, double rate_hz) {
  CoreConfig c;
  c.rate_hz = rate_hz;
  c.calibration = daq.calibration();
  return c;
}

}  // namespace

SimTimeLoop::SimTimeLoop(const sim::PlantConfig& plant, double rate_hz)
    : daq_(plant, rate_hz), core_(core_config(daq_, rate_hz)) {}

const LoopRecord& SimTimeLoop::step() {
  capture::DaqInputs in;
  capture::DaqOutputs out;
  CycleContext ctx;
  // As the daemon: this cycle's read and the last cycle's write.
  ctx.io_ok = daq_.read(in) == capture::IoStatus::ok && last_write_ok_;
  record_ = LoopRecord{};
  core_.cycle(in, ctx, out, record_);
  last_write_ok_ = daq_.write(out) == capture::IoStatus::ok;
  return record_;
}

}  // namespace knoblab::hapticd
