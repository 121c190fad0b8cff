// A Haptic Camera capture of a simulated knob: the thesis' swept-sine position
// stimulus tracked by the PID through the plant simulator, run through the
// same cycle (read → update → write) the realtime daemon runs.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "knoblab/capture/capture_controller.hpp"
#include "knoblab/fit/run_hooks.hpp"
#include "knoblab/interchange/capture.hpp"
#include "knoblab/sim/library_effects.hpp"
#include "knoblab/sim/plant.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::cli {

struct SimulationRequest {
  std::string knob_name;  // preset id, or a label for a params file
  sim::KnobParams knob;
  double seconds = 5.0;      // thesis §2.2.1: 5 s
  double rate_hz = 5000.0;   // thesis §2.2.1: 5 kHz
  std::uint64_t seed = 1;
  std::string mode = "lab";  // lab: axis horizontal on the lathe bed; tripod: any tilt
  double tilt_rad = 0.0;     // tripod only: axis tilt from vertical
  sim::AmpMode amp = sim::AmpMode::Current;
  capture::PidGains pid{};
  model::SweptSine stimulus = model::SweptSine::spatial();
  // Effects beyond the thesis model, any kind (sim/library_effects.hpp):
  // simulate() folds knob terms into `knob` and rig effects into the plant.
  std::vector<model::EffectSpec> effects;
  // Progress ("simulating", cycles done of all) and cancellation, polled
  // every 1000 cycles: simulate() then removes the capture it began in the
  // store and throws fit::Cancelled.
  fit::RunHooks hooks;
};

struct SimulationResult {
  interchange::Capture capture;  // every sample, with metadata and the loop's flags
  std::optional<std::int64_t> capture_id;  // when written to a store
  double tracking_rms_rad = 0.0;  // PID tracking error over the capture
  double max_command_V = 0.0;
};

// A capture the supervisor stopped (a velocity, tracking or any other fault):
// what() says where, why and what to change; partial() holds the samples up
// to and including the one that latched the fault, with metadata
// `status: incomplete` and `end_reason: fault: …` (in the store, when one
// was given, the capture is marked the same way).
class CaptureFailed : public std::runtime_error {
 public:
  CaptureFailed(const std::string& why, SimulationResult partial)
      : std::runtime_error(why), partial_(std::move(partial)) {}
  const SimulationResult& partial() const { return partial_; }

 private:
  SimulationResult partial_;
};

// Runs the capture; when `db` is given the samples go into it in committed
// batches while the loop runs (as hapticd's writer does). Throws
// CaptureFailed when the capture did not run to its end with the motor
// driven, fit::Cancelled when request.hooks says so.
SimulationResult simulate(const SimulationRequest& request, store::Store* db);

}  // namespace knoblab::cli
