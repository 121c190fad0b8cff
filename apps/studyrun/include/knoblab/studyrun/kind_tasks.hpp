// The tasks of the other three study kinds (pointing_task.hpp has rotary
// pointing).
//
// List selection (thesis §4.5, Fig. 50): the knob moves a counter through a
// list, items_per_rev steps per revolution from the value shown at onset.
// Freeform exploration: the display is off and the task ends after
// exploration_s. Target finding: the counter and a target value are shown;
// the target is selected when the counter has shown it, the knob at rest,
// for `dwell_s`. Measures: time to select, how often the counter passed the
// target.
//
// Matching (§3.4.1): the participant moves the stage's sliders, which change
// the rendering live, until the rendered knob feels like the reference knob,
// and says so. Measures: the final slider values (SI), time, slider moves.
//
// Textures (§4.4.1): the experimenter presents the texture; the participant
// strokes it and says when done (or the task ends at stroke_max_s).
// Measures: the stroke's length.
#pragma once

#include <cstdint>

#include "knoblab/studyrun/task.hpp"

namespace knoblab::studyrun {

class ListTask final : public Task {
 public:
  static constexpr double kDwellS = 0.5;
  static constexpr double kTimeoutS = 60;
  ListTask(const study::Protocol& protocol, const study::Trial& trial, std::uint64_t trial_seed);
  const Display& display() const override { return display_; }
  Step feed(const KnobReading& reading, const Action& action) override;
  std::optional<study::Rendering> rendering_change() override;
  nlohmann::json result() const override;

 private:
  long counter_at(double theta) const;
  study::ListSelectionSettings settings_;
  study::Rendering rendering_;
  bool freeform_ = false;
  long start_value_ = 0, target_ = 0;
  double onset_theta_ = 0, onset_t_ = -1, at_target_since_ = -1, end_t_ = 0;
  long passes_ = 0, last_counter_ = 0;
  bool onset_pending_ = false, selected_ = false, done_ = false;
  Display display_;
};

class MatchingTask final : public Task {
 public:
  static constexpr double kTimeoutS = 300;
  MatchingTask(const study::Protocol& protocol, const study::Trial& trial);
  const Display& display() const override { return display_; }
  Step feed(const KnobReading& reading, const Action& action) override;
  std::optional<study::Rendering> rendering_change() override;
  nlohmann::json result() const override;

 private:
  std::vector<study::Slider> sliders_;  // the stage's
  study::Rendering rendering_;
  double onset_t_ = -1, end_t_ = 0;
  long moves_ = 0;
  bool changed_ = false, done_ = false, timed_out_ = false;
  Display display_;
};

class TextureTask final : public Task {
 public:
  TextureTask(const study::Protocol& protocol, const study::Trial& trial);
  const Display& display() const override { return display_; }
  Step feed(const KnobReading& reading, const Action& action) override;
  std::optional<study::Rendering> rendering_change() override { return std::nullopt; }
  nlohmann::json result() const override;

 private:
  double stroke_max_s_ = 0;
  double onset_t_ = -1, end_t_ = 0;
  bool done_ = false;
  Display display_;
};

}  // namespace knoblab::studyrun
