// One loop cycle: read → update → write → record. The future realtime daemon
// paces this with clock_nanosleep; `knoblab simulate` runs it back to back in
// simulated time. Same function, so there is one loop implementation.
#pragma once

#include <cstdint>

#include "knoblab/capture/daq.hpp"
#include "knoblab/capture/sample.hpp"

namespace knoblab::capture {

template <class Controller, class Sink>
void run_cycle(Daq& daq, Controller& controller, Sink&& sink) {
  DaqInputs in;
  DaqOutputs out;
  Sample sample;
  daq.read(in);
  controller.update(in, out, sample);
  daq.write(out);
  sink(sample);
}

template <class Controller, class Sink>
void run_cycles(Daq& daq, Controller& controller, std::int64_t cycles, Sink&& sink) {
  for (std::int64_t i = 0; i < cycles; ++i) run_cycle(daq, controller, sink);
}

}  // namespace knoblab::capture
