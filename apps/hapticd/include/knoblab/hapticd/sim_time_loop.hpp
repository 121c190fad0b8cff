// hapticd's cycle run back to back in simulated time on the simulated
// camera: the same core, modes and supervisor the realtime daemon runs,
// without its threads, clock or ring. knoblab simulate, knoblab design
// render and the in-process study apparatus each step one of these.
#pragma once

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hapticd/core.hpp"

namespace knoblab::hapticd {

class SimTimeLoop {
 public:
  // The core reads the simulated DAQ through the DAQ's own calibration.
  SimTimeLoop(const sim::PlantConfig& plant, double rate_hz);

  // The plant, to add a hand or effects before the first step.
  capture::SimDaq& daq() { return daq_; }
  HapticCore& core() { return core_; }

  // Queues a command for the next cycle; false when the queue is full.
  bool post(const CoreCommand& c) { return core_.post(c); }

  // One cycle: read the DAQ, run the core, write its outputs. A failed DAQ
  // read or write reaches the core as an I/O error, as in the daemon.
  const LoopRecord& step();

 private:
  capture::SimDaq daq_;
  HapticCore core_;
  LoopRecord record_;
  bool last_write_ok_ = true;
};

}  // namespace knoblab::hapticd
