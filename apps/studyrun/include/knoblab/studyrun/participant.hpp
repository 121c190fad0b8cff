// The participant as the runner sees one: a person at the participant view
// or the simulated participant (simulated_participant.hpp) — both answer the
// same calls.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/study/plan.hpp"
#include "knoblab/study/protocol.hpp"
#include "knoblab/studyrun/apparatus.hpp"
#include "knoblab/studyrun/display.hpp"

namespace knoblab::studyrun {

// What the participant does besides turning the knob: moves the matching
// study's sliders, says they are done (a matched knob, a stroked texture).
struct Action {
  std::optional<study::Rendering> sliders;
  bool done = false;
};

class Participant {
 public:
  virtual ~Participant() = default;
  virtual void begin_trial(const study::Protocol& protocol, const study::Trial& trial) = 0;
  // With every reading, what the screen shows then.
  virtual Action act(const Display& display, const KnobReading& reading) = 0;
  // The trial's ratings, one per scale of the protocol: {"appropriateness": 3}
  // or, for the affect grid, {"affect_grid": {"valence": 6, "arousal": 2}}.
  // `measures` is the trial's result (what the task measured).
  virtual nlohmann::json rate(const std::vector<study::Rating>& scales, const nlohmann::json& measures) = 0;
  // The matching study's familiarization (§3.4.1.3): having explored each
  // slider, the novice's words for what it does, by slider parameter (their
  // sticky notes, Table 15). Asked once, before a novice's first trial; a
  // participant with nothing to say (a person, whose words the experimenter
  // types in the experimenter view) gives none.
  virtual std::map<std::string, std::string> slider_tags(const std::vector<study::Slider>& /*sliders*/) {
    return {};
  }
};

}  // namespace knoblab::studyrun
