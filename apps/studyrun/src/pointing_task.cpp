#include "knoblab/studyrun/pointing_task.hpp"

#include <cmath>
#include <numbers>

namespace knoblab::studyrun {

namespace {

// Degrees at the edge, rounded to a nano-degree: 30° read as radians and
// turned back is 29.999999999999996°, and tables group by these values.
double deg(double rad) { return std::round(rad * 180.0 / std::numbers::pi * 1e9) / 1e9; }

}  // namespace

PointingTask::PointingTask(const study::Protocol& protocol, const study::Trial& trial, PointingTiming timing)
    : timing_(timing), rendering_(condition_rendering(protocol, trial)) {
  const auto& settings = std::get<study::PointingSettings>(protocol.settings);
  home_ = {0.0, settings.home_width_rad};  // the home position is θ = 0
  for (const study::Target& target : trial.targets) acq_.push_back({target});
  if (acq_.empty()) throw std::invalid_argument("a pointing trial needs targets");
  set_disk(home_, "Put the needle on the small disk");
  display_.needle = true;
}

void PointingTask::set_disk(std::optional<Disk> disk, std::string instruction) {
  display_.disk = disk;
  display_.instruction = std::move(instruction);
  ++display_.version;
}

void PointingTask::show(std::size_t k, double t) {
  current_ = k;
  acq_[k].shown_t = t;
  set_disk(Disk{acq_[k].target.centre_rad, acq_[k].target.width_rad}, "Move the needle onto the disk");
}

Step PointingTask::feed(const KnobReading& r, const Action&) {
  switch (phase_) {
    case Phase::Homing:
      if (start_t_ < 0) start_t_ = r.t;
      if (!home_.contains(r.theta) || std::abs(r.omega) > timing_.rest_speed_rad_s) {
        settled_since_ = -1;
        if (r.t - start_t_ <= timing_.home_timeout_s) return Step::Continue;
        timed_out_ = true;
        phase_ = Phase::Done;
        set_disk(std::nullopt, "");
        return Step::Done;
      }
      if (settled_since_ < 0) settled_since_ = r.t;
      if (r.t - settled_since_ < timing_.home_settle_s) return Step::Continue;
      onset_t_ = r.t;
      onset_pending_ = true;
      phase_ = Phase::Moving;
      show(0, r.t);
      return Step::Onset;
    case Phase::Moving:
    case Phase::Finishing:
      break;
    case Phase::Done:
      return Step::Done;
  }
  // Each entered movement ends where the knob first stops or turns back.
  bool all_ended = true;
  for (Acquisition& a : acq_) {
    if (a.entered_t < 0 || a.ended) {
      all_ended = all_ended && a.ended;
      continue;
    }
    const double along = r.theta * a.target.direction;
    if (along > a.extreme) a.extreme = along;
    // Stopped or turned back for a while, not a dip of a rendering's ringing.
    if (r.omega * a.target.direction > timing_.rest_speed_rad_s) {
      a.slow_since = -1;
    } else {
      if (a.slow_since < 0) a.slow_since = r.t;
      if (r.t - a.slow_since >= timing_.stop_s) a.ended = true;
    }
    all_ended = all_ended && a.ended;
  }
  if (phase_ == Phase::Moving) {
    Acquisition& a = acq_[current_];
    if (Disk{a.target.centre_rad, a.target.width_rad}.contains(r.theta)) {
      a.entered_t = r.t;
      a.extreme = r.theta * a.target.direction;
      if (current_ + 1 < acq_.size()) {
        show(current_ + 1, r.t);
      } else {
        phase_ = Phase::Finishing;
        set_disk(std::nullopt, "");
      }
    } else if (r.t - a.shown_t > timing_.acquisition_timeout_s) {
      timed_out_ = true;
      phase_ = Phase::Done;
      set_disk(std::nullopt, "");
      return Step::Done;
    }
    return Step::Continue;
  }
  if (all_ended || r.t - acq_.back().entered_t > timing_.last_end_timeout_s) {
    phase_ = Phase::Done;
    return Step::Done;
  }
  return Step::Continue;
}

std::optional<study::Rendering> PointingTask::rendering_change() {
  if (!onset_pending_) return std::nullopt;
  onset_pending_ = false;
  return rendering_;
}

nlohmann::json PointingTask::result() const {
  nlohmann::json list = nlohmann::json::array();
  double previous_centre = home_.centre_rad;
  for (const Acquisition& a : acq_) {
    nlohmann::json j{{"acquisition", a.target.acquisition},
                     {"direction", a.target.direction},
                     {"target_deg", deg(a.target.centre_rad)},
                     {"amplitude_deg", deg(std::abs(a.target.centre_rad - previous_centre))},
                     {"width_deg", deg(a.target.width_rad)}};
    previous_centre = a.target.centre_rad;
    if (a.entered_t >= 0) {
      const double endpoint = a.extreme - a.target.centre_rad * a.target.direction;
      j["movement_time_s"] = a.entered_t - a.shown_t;
      j["endpoint_deg"] = deg(endpoint);
      j["overshoot_deg"] = deg(std::max(0.0, endpoint - a.target.width_rad / 2));
    } else {
      j["movement_time_s"] = nullptr;  // not acquired: the trial timed out
      j["endpoint_deg"] = nullptr;
      j["overshoot_deg"] = nullptr;
    }
    list.push_back(std::move(j));
  }
  return {{"onset_s", onset_t_}, {"timed_out", timed_out_}, {"acquisitions", std::move(list)}};
}

}  // namespace knoblab::studyrun
