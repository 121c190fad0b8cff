// The apparatus as hapticd's own core (HapticCore: the modes, the renderer,
// the supervisor) driving the sim plant in simulated time, cycle after cycle
// with no clock — as `knoblab simulate` runs it — for a dry run of a whole
// protocol with many simulated participants in minutes rather than hours.
// The guided hand is on the plant, its channel in this process. Trials are
// not recorded as captures (a trial's row keeps its 100 ms trace); a fault
// the supervisor latches is an ApparatusError, as with hapticd.
#pragma once

#include <memory>
#include <string>

#include "knoblab/sim/guided_hand.hpp"
#include "knoblab/studyrun/apparatus.hpp"

namespace knoblab::studyrun {

class CoreApparatus final : public Apparatus {
 public:
  // `knob`: the sim preset on the motor (the study knob: study3-not-rendered).
  // Throws std::invalid_argument for an unknown preset or rate.
  explicit CoreApparatus(const std::string& knob = "study3-not-rendered", double rate_hz = 5000.0);
  ~CoreApparatus() override;
  CoreApparatus(const CoreApparatus&) = delete;
  CoreApparatus& operator=(const CoreApparatus&) = delete;

  sim::HandChannel& hand();
  void render(const study::Rendering& rendering) override;
  void start_trial(const TrialLabel& label) override;
  TrialRecording stop_trial() override;
  KnobReading next() override;  // every 1 ms of simulated time

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace knoblab::studyrun
