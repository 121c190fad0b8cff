// One trial's task, fed the knob's readings: what the screen shows, when the
// condition's rendering starts (the stimulus onset), when the task is over
// and what it measured. One class per study kind (pointing_task.hpp,
// list_task.hpp, matching_task.hpp, texture_task.hpp); make_task picks it.
#pragma once

#include <memory>

#include <nlohmann/json.hpp>

#include "knoblab/study/plan.hpp"
#include "knoblab/study/protocol.hpp"
#include "knoblab/studyrun/apparatus.hpp"
#include "knoblab/studyrun/display.hpp"
#include "knoblab/studyrun/participant.hpp"

namespace knoblab::studyrun {

enum class Step {
  Continue,  // feed the next reading
  Onset,     // render the condition from now on (the biometrics' marker), then go on
  Done,      // the task is over; result() holds its measures
};

class Task {
 public:
  virtual ~Task() = default;
  virtual const Display& display() const = 0;
  virtual Step feed(const KnobReading& reading, const Action& action) = 0;
  // The rendering to apply now, when it changed since the last call (the
  // condition's at onset; the matching sliders' while they move).
  virtual std::optional<study::Rendering> rendering_change() = 0;
  virtual nlohmann::json result() const = 0;
};

// The kind's task for this trial. `trial_seed` draws what the plan leaves
// open (a list-selection target).
std::unique_ptr<Task> make_task(const study::Protocol& protocol, const study::Trial& trial, std::uint64_t trial_seed);

// The condition's rendering: the level that gives one (zero when none does).
study::Rendering condition_rendering(const study::Protocol& protocol, const study::Trial& trial);

}  // namespace knoblab::studyrun
