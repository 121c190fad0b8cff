// The study runner's seam to the haptic knob: render a condition, record a
// trial, and hand over the knob's readings as they come. HapticdApparatus
// speaks hapticd's control protocol and reads its telemetry ring; a test or a
// demo may put anything else behind the same interface.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "knoblab/study/protocol.hpp"

namespace knoblab::studyrun {

// One reading of the knob, SI: loop time (s), angle (rad), velocity (rad/s),
// the torque the knob felt (N·m).
struct KnobReading {
  double t = 0;
  double theta = 0;
  double omega = 0;
  double torque = 0;
};

struct TrialLabel {
  std::string study;
  std::string participant;
  std::string condition;  // study::condition_label, for the capture's metadata
};

// What the apparatus recorded of one trial: the capture hapticd stored (with
// its samples and the biometrics box's), when it stored one.
struct TrialRecording {
  std::optional<std::int64_t> capture_id;
  bool complete = false;
  std::string end_reason;
};

// Thrown when the apparatus is lost (hapticd gone, a fault latched): the
// trial in progress is not committed, and the session resumes there.
class ApparatusError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Apparatus {
 public:
  virtual ~Apparatus() = default;
  // Renders τ = M_acc·θ̈ + B_vel·θ̇ + A_pos·sin(detents_per_rev·θ) from now
  // on (a zero rendering: the bare knob). Called again while a trial runs
  // when the participant moves a slider.
  virtual void render(const study::Rendering& rendering) = 0;
  virtual void start_trial(const TrialLabel& label) = 0;
  virtual TrialRecording stop_trial() = 0;
  // The next reading, in order; waits for it (about 1 ms apart). Throws
  // ApparatusError when the knob is lost.
  virtual KnobReading next() = 0;
};

}  // namespace knoblab::studyrun
