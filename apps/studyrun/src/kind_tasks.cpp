#include "knoblab/studyrun/kind_tasks.hpp"
#include "knoblab/studyrun/rendering_field.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace knoblab::studyrun {

namespace {

// The trial's level of the factor whose levels are the things presented.
const study::Level& level_of(const study::Protocol& p, const study::Trial& t, std::size_t factor) {
  return study::trial_level(p, t, factor);
}


}  // namespace

// List selection --------------------------------------------------------------

ListTask::ListTask(const study::Protocol& protocol, const study::Trial& trial, std::uint64_t trial_seed)
    : settings_(std::get<study::ListSelectionSettings>(protocol.settings)),
      rendering_(condition_rendering(protocol, trial)) {
  freeform_ = trial.levels[settings_.context_factor] == settings_.freeform_level;
  const long length = static_cast<long>(settings_.list_length);
  start_value_ = length / 2;
  // The target is one to three items away, either way: far enough to need a
  // movement, near enough that a trial takes seconds, not minutes.
  std::mt19937_64 rng(trial_seed);
  const long distance = 1 + static_cast<long>(rng() % 3);
  const long sign = (rng() & 1u) != 0 ? 1 : -1;
  target_ = std::clamp(start_value_ + sign * distance, 0L, length - 1);
  if (target_ == start_value_) target_ = start_value_ - sign * distance;
  display_.instruction = freeform_ ? "Explore the knob" : "Turn the knob until the counter shows the target";
  display_.version = 1;
}

long ListTask::counter_at(double theta) const {
  const double steps = (theta - onset_theta_) * settings_.items_per_rev / (2 * std::numbers::pi);
  return std::clamp(start_value_ + std::lround(steps), 0L, static_cast<long>(settings_.list_length) - 1);
}

Step ListTask::feed(const KnobReading& r, const Action&) {
  if (done_) return Step::Done;
  if (onset_t_ < 0) {
    onset_t_ = r.t;
    onset_theta_ = r.theta;
    onset_pending_ = true;
    last_counter_ = start_value_;
    if (!freeform_) {
      display_.counter = start_value_;
      display_.target_value = target_;
      ++display_.version;
    }
    return Step::Onset;
  }
  const double elapsed = r.t - onset_t_;
  if (freeform_) {
    if (elapsed >= settings_.exploration_s) done_ = true;
  } else {
    const long c = counter_at(r.theta);
    if (c != last_counter_) {
      // Passing over the target (not stopping on it) counts as a pass.
      if ((last_counter_ < target_ && c > target_) || (last_counter_ > target_ && c < target_) ||
          (last_counter_ == target_ && c != target_))
        ++passes_;
      last_counter_ = c;
      display_.counter = c;
      ++display_.version;
    }
    if (c == target_ && std::abs(r.omega) < 0.1) {
      if (at_target_since_ < 0) at_target_since_ = r.t;
      if (r.t - at_target_since_ >= kDwellS) selected_ = done_ = true;
    } else {
      at_target_since_ = -1;
    }
    if (elapsed >= kTimeoutS) done_ = true;
  }
  if (!done_) return Step::Continue;
  end_t_ = selected_ ? at_target_since_ : r.t;
  display_.counter.reset();
  display_.target_value.reset();
  display_.instruction.clear();
  ++display_.version;
  return Step::Done;
}

std::optional<study::Rendering> ListTask::rendering_change() {
  if (!onset_pending_) return std::nullopt;
  onset_pending_ = false;
  return rendering_;
}

nlohmann::json ListTask::result() const {
  nlohmann::json j{{"onset_s", onset_t_}, {"context", freeform_ ? "freeform" : "target"}};
  if (freeform_) {
    j["exploration_s"] = end_t_ - onset_t_;
  } else {
    j["start_value"] = start_value_;
    j["target_value"] = target_;
    j["selected"] = selected_;
    j["time_s"] = selected_ ? nlohmann::json(end_t_ - onset_t_) : nlohmann::json(nullptr);
    j["passes"] = passes_;
  }
  return j;
}

// Matching --------------------------------------------------------------------

MatchingTask::MatchingTask(const study::Protocol& protocol, const study::Trial& trial) {
  const auto& settings = std::get<study::MatchingSettings>(protocol.settings);
  for (std::size_t i : settings.stage_sliders.at(trial.stage)) sliders_.push_back(settings.sliders[i]);
  // Every slider starts at its lowest value: the bare knob.
  for (const study::Slider& s : sliders_) rendering_field(rendering_, s.parameter) = s.min;
  display_.reference = level_of(protocol, trial, 0).name;
  display_.sliders = rendering_;
  display_.instruction = "Move the sliders until the knob feels like knob " + display_.reference;
  display_.version = 1;
}

Step MatchingTask::feed(const KnobReading& r, const Action& action) {
  if (done_) return Step::Done;
  if (onset_t_ < 0) {
    onset_t_ = r.t;
    changed_ = true;
    return Step::Onset;
  }
  if (action.sliders) {
    study::Rendering next = rendering_;
    for (const study::Slider& s : sliders_) {
      rendering_field(next, s.parameter) = std::clamp(rendering_field(*action.sliders, s.parameter), s.min, s.max);
    }
    // Without detents there is no detent amplitude to feel.
    if (next.detents_per_rev < 1) next.A_pos = 0;
    if (!(next == rendering_)) {
      rendering_ = next;
      changed_ = true;
      ++moves_;
      display_.sliders = rendering_;
      ++display_.version;
    }
  }
  if (action.done || r.t - onset_t_ >= kTimeoutS) {
    timed_out_ = !action.done;
    done_ = true;
    end_t_ = r.t;
    return Step::Done;
  }
  return Step::Continue;
}

std::optional<study::Rendering> MatchingTask::rendering_change() {
  if (!changed_) return std::nullopt;
  changed_ = false;
  study::Rendering r = rendering_;
  if (r.detents_per_rev < 1) r.A_pos = 0;
  return r;
}

nlohmann::json MatchingTask::result() const {
  nlohmann::json sliders = nlohmann::json::object();
  for (const study::Slider& s : sliders_) sliders[s.parameter] = rendering_field(rendering_, s.parameter);
  return {{"onset_s", onset_t_}, {"reference", display_.reference}, {"sliders", sliders},
          {"time_s", end_t_ - onset_t_}, {"slider_moves", moves_}, {"timed_out", timed_out_}};
}

// Textures --------------------------------------------------------------------

TextureTask::TextureTask(const study::Protocol& protocol, const study::Trial& trial) {
  const auto& settings = std::get<study::TexturesSettings>(protocol.settings);
  stroke_max_s_ = settings.stroke_max_s;
  display_.reference = level_of(protocol, trial, settings.factor).name;
  display_.instruction = "Stroke the surface";
  display_.version = 1;
}

Step TextureTask::feed(const KnobReading& r, const Action& action) {
  if (done_) return Step::Done;
  if (onset_t_ < 0) {
    onset_t_ = r.t;
    return Step::Onset;
  }
  if (action.done || r.t - onset_t_ >= stroke_max_s_) {
    done_ = true;
    end_t_ = r.t;
    return Step::Done;
  }
  return Step::Continue;
}

nlohmann::json TextureTask::result() const {
  return {{"onset_s", onset_t_}, {"texture", display_.reference}, {"stroke_s", end_t_ - onset_t_}};
}

}  // namespace knoblab::studyrun
