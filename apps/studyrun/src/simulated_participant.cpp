#include "knoblab/studyrun/simulated_participant.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "knoblab/studyrun/reference_knob.hpp"
#include "knoblab/studyrun/rendering_field.hpp"
#include "knoblab/studyrun/task.hpp"

namespace knoblab::studyrun {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// A stable number in [−1, 1] for a name: how a texture feels to everyone,
// the same for every participant (people agreed on oil, §4.4.2).
double name_score(const std::string& name, std::uint64_t salt) {
  const std::uint64_t h = std::hash<std::string>{}(name) ^ (salt * 0x9E3779B97F4A7C15ull);
  return static_cast<double>(h % 2001) / 1000.0 - 1.0;
}

// A latent rating on 1 … 9 (9: high valence or arousal) put on the scale's
// range and direction.
int on_scale(double latent, const study::Rating& scale) {
  double u = (std::clamp(latent, 1.0, 9.0) - 1.0) / 8.0;
  if (scale.min_is == study::ScaleEnd::High) u = 1.0 - u;
  return static_cast<int>(std::lround(scale.min + u * (scale.max - scale.min)));
}

// The reference knob the matching participant has felt.
study::Rendering felt_reference(const study::Protocol& protocol, const study::Trial& trial) {
  return reference_rendering(study::trial_level(protocol, trial, 0)).value_or(study::Rendering{});
}


// Table 15's novices' own words for each slider (P_pos there is the
// detent count here), a few of each row's.
struct Vocabulary {
  const char* parameter;
  std::vector<const char*> words;
};
const Vocabulary kSliderWords[] = {
    {"M_acc", {"weight", "whoosh", "spinny", "spin faster", "momentum", "slingy", "inertia", "smooth, but heavy"}},
    {"B_vel", {"friction", "heavy", "like moving through mud", "spin slower & stops", "pudding", "buttery",
               "hard to turn", "stiffer"}},
    {"A_pos", {"bump size", "clicks", "bigness of detents", "really bumpy", "feeling bumps", "bump height", "wobbly",
               "big clicky"}},
    {"detents_per_rev", {"how many detents", "bump frequency", "spacing bumps", "# of bumps", "knobbly", "clicky",
                         "frequency of detents"}},
};

}  // namespace

ParticipantModel ParticipantModel::draw(std::uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x5EED5EEDull);
  std::normal_distribution<double> n(0, 1);
  ParticipantModel m;
  m.speed = std::clamp(1.0 + 0.15 * n(rng), 0.7, 1.4);
  m.valence_bias = 0.6 * n(rng);
  m.reaction_s = std::clamp(0.22 + 0.03 * n(rng), 0.15, 0.35);
  return m;
}

SimulatedParticipant::SimulatedParticipant(sim::HandChannel& hand, ParticipantModel model, std::uint64_t seed)
    : hand_(hand), model_(model), seed_(seed), rng_(seed) {}

void SimulatedParticipant::release() {
  hand_.send({hand_target_, 0, 0, 0});
  holding_ = false;
}

void SimulatedParticipant::begin_trial(const study::Protocol& protocol, const study::Trial& trial) {
  protocol_ = &protocol;
  trial_ = trial;
  seen_version_ = 0;
  pending_.reset();
  trial_start_t_ = -1;
  grip_ = model_.grip_stiffness;
  torque_sum_ = 0;
  torque_n_ = 0;
  explore_centre_.reset();
  expected_time_s_ = 0;
  for (const study::Target& t : trial.targets)  // the acquisitions, each a reaction and a reach
    expected_time_s_ += model_.reaction_s + fitts_time(std::abs(t.centre_rad) > 0 ? std::abs(t.centre_rad) : 0.5, t.width_rad);
  if (!trial.targets.empty()) expected_time_s_ /= static_cast<double>(trial.targets.size());
  if (protocol.kind == study::Kind::Matching) {
    const auto& settings = std::get<study::MatchingSettings>(protocol.settings);
    const study::Rendering truth = felt_reference(protocol, trial);
    sliders_ = {};
    slider_goal_ = {};
    match_error_ = 0;
    std::size_t n = 0;
    for (std::size_t i : settings.stage_sliders.at(trial.stage)) {
      const study::Slider& s = settings.sliders[i];
      rendering_field(sliders_, s.parameter) = s.min;
      // Perceived as people perceive magnitudes: off by a ratio (about 25 %).
      double goal = rendering_field(truth, s.parameter) * std::exp(gauss(0.25));
      if (s.parameter == "detents_per_rev") goal = std::round(goal);
      goal = std::clamp(goal, s.min, s.max);
      rendering_field(slider_goal_, s.parameter) = goal;
      match_error_ += std::abs(goal - std::clamp(rendering_field(truth, s.parameter), s.min, s.max)) / (s.max - s.min);
      ++n;
    }
    if (n > 0) match_error_ /= static_cast<double>(n);
    slider_steps_left_ = 4;
    next_slider_t_ = 0;
  }
  if (protocol.kind == study::Kind::Textures) {
    const auto& settings = std::get<study::TexturesSettings>(protocol.settings);
    stroke_s_ = std::uniform_real_distribution<double>(settings.stroke_min_s, settings.stroke_max_s)(rng_);
  }
}

double SimulatedParticipant::fitts_time(double distance, double width) const {
  const double fitts = model_.speed * (model_.fitts_a_s + model_.fitts_b_s_per_bit * std::log2(distance / width + 1.0));
  // A long turn is limited by how fast a wrist turns a knob, not by Fitts'
  // law: a minimum-jerk reach peaks at 1.875·D/T.
  return std::max(fitts, 1.875 * distance / model_.peak_speed_rad_s);
}

void SimulatedParticipant::plan_reach(double now, double aim, double width, double delay) {
  const double duration = std::max(0.08, fitts_time(std::abs(aim - hand_target_), width));
  pending_ = Reach{now + delay, aim, duration};
}

void SimulatedParticipant::pointing(const Display& d, const KnobReading& r) {
  if (d.version != seen_version_) {
    seen_version_ = d.version;
    pending_.reset();
    grip_ = model_.grip_stiffness;
    if (d.disk) {
      const double reaction = std::max(0.1, model_.reaction_s * model_.speed + gauss(0.03));
      plan_reach(r.t, d.disk->centre_rad + gauss(model_.aim_sd_per_width * d.disk->width_rad), d.disk->width_rad,
                 reaction);
    }
    return;
  }
  // Missed: once the knob has come to rest outside the disk, a corrective
  // reach, with a firmer grip each time (people stiffen to place a knob
  // against a detent's pull).
  if (d.disk && !pending_ && r.t > reach_end_t_ + 0.08 && !d.disk->contains(r.theta) && std::abs(r.omega) < 0.3) {
    const double aim = d.disk->centre_rad + gauss(0.5 * model_.aim_sd_per_width * d.disk->width_rad);
    grip_ = std::min(grip_ * 2.0, 8.0 * model_.grip_stiffness);
    plan_reach(r.t, aim, d.disk->width_rad, 0.15);
  }
}

void SimulatedParticipant::explore(const KnobReading& r) {
  if (pending_ || r.t < reach_end_t_ + 0.05) return;
  // Back and forth across where this trial's exploring began. The knob has
  // no zero a hand knows: one that target finding has left revolutions away
  // is explored there, not first turned all the way back (a reach of tens of
  // radians in under a second, faster than any wrist and than hapticd's
  // velocity limit).
  if (!explore_centre_) explore_centre_ = r.theta;
  const double side = hand_target_ > *explore_centre_ ? -1.0 : 1.0;
  const double aim = *explore_centre_ + side * std::uniform_real_distribution<double>(0.6, 1.5)(rng_);
  const double duration = std::uniform_real_distribution<double>(0.5, 0.9)(rng_) * model_.speed;
  // No faster than the wrist turns (a minimum-jerk reach peaks at 1.875·D/T).
  pending_ = Reach{r.t, aim, std::max(duration, 1.875 * std::abs(aim - hand_target_) / model_.peak_speed_rad_s)};
}

void SimulatedParticipant::list(const Display& d, const KnobReading& r) {
  const auto& settings = std::get<study::ListSelectionSettings>(protocol_->settings);
  if (!d.counter || !d.target_value) {
    // The display is off: explore the knob in freeform exploration; in
    // target finding, wait for the counter and the target to appear.
    if (trial_.levels.at(settings.context_factor) == settings.freeform_level) explore(r);
    return;
  }
  const double step = kTwoPi / settings.items_per_rev;
  const long off = *d.target_value - *d.counter;
  const bool fresh = d.version != seen_version_ && seen_version_ == 0;
  seen_version_ = d.version;
  if (off == 0 || pending_) return;
  if (fresh || (r.t > reach_end_t_ + 0.1 && std::abs(r.omega) < 0.2)) {
    const double aim = r.theta + static_cast<double>(off) * step + gauss(0.12 * step);
    plan_reach(r.t, aim, step, fresh ? model_.reaction_s : 0.15);
  }
}

Action SimulatedParticipant::matching(const Display&, const KnobReading& r) {
  explore(r);  // keeps feeling the knob while moving the sliders
  Action a;
  if (next_slider_t_ == 0) next_slider_t_ = r.t + 1.0;
  if (r.t < next_slider_t_) return a;
  if (slider_steps_left_ > 0) {
    const double k = 1.0 / slider_steps_left_;
    for (const char* p : {"M_acc", "B_vel", "A_pos", "detents_per_rev"})
      rendering_field(sliders_, p) += (rendering_field(slider_goal_, p) - rendering_field(sliders_, p)) * k;
    --slider_steps_left_;
    a.sliders = sliders_;
    next_slider_t_ = r.t + std::uniform_real_distribution<double>(0.8, 1.6)(rng_) * model_.speed;
  } else {
    a.done = true;  // felt it once more after the last move: that is the match
  }
  return a;
}

Action SimulatedParticipant::act(const Display& d, const KnobReading& r) {
  if (trial_start_t_ < 0) trial_start_t_ = r.t;
  // A hand not yet on the knob takes hold where the knob is: its first
  // reach is planned from there (the guided hand starts from there too).
  if (!holding_) {
    hand_target_ = r.theta;
    reach_end_t_ = r.t;
    holding_ = true;
  }
  torque_sum_ += std::abs(r.torque);
  ++torque_n_;
  Action a;
  switch (protocol_->kind) {
    case study::Kind::Pointing: pointing(d, r); break;
    case study::Kind::ListSelection: list(d, r); break;
    case study::Kind::Matching: a = matching(d, r); break;
    case study::Kind::Textures: a.done = r.t - trial_start_t_ >= stroke_s_; break;
  }
  if (pending_ && r.t >= pending_->start_t) {
    hand_.send({pending_->target, pending_->duration, grip_, model_.grip_damping * grip_ / model_.grip_stiffness});
    hand_target_ = pending_->target;
    reach_end_t_ = r.t + pending_->duration;
    pending_.reset();
  }
  return a;
}

std::map<std::string, std::string> SimulatedParticipant::slider_tags(const std::vector<study::Slider>& sliders) {
  std::mt19937_64 rng(seed_ ^ 0x7A65A7A65A7A65A7ull);
  std::map<std::string, std::string> out;
  for (const study::Slider& s : sliders)
    for (const Vocabulary& v : kSliderWords) {
      if (s.parameter != v.parameter) continue;
      const std::size_t n = v.words.size();
      const std::size_t first = rng() % n;
      std::string words = v.words[first];
      if (rng() % 3 == 0) words += std::string(", ") + v.words[(first + 1 + rng() % (n - 1)) % n];  // a second, another
      out[s.parameter] = words;
    }
  return out;
}

nlohmann::json SimulatedParticipant::rate(const std::vector<study::Rating>& scales, const nlohmann::json& measures) {
  const study::Rendering rendering = condition_rendering(*protocol_, trial_);
  // Some friction and a little inertia are liked, much of either is not
  // (the thesis' "sweet spot", §4.6.3).
  double valence = 5.0 + model_.valence_bias - 0.8 * std::pow((rendering.B_vel - 3e-3) / 4e-3, 2) -
                   0.8 * std::pow((rendering.M_acc - 3e-5) / 1e-4, 2);
  double arousal = 3.0 + 40.0 * (torque_n_ ? torque_sum_ / static_cast<double>(torque_n_) : 0.0);
  switch (protocol_->kind) {
    case study::Kind::Pointing: {
      double sum = 0;
      std::size_t n = 0;
      for (const auto& a : measures.at("acquisitions"))
        if (a.at("movement_time_s").is_number()) sum += a.at("movement_time_s").get<double>(), ++n;
      const double mean = n ? sum / static_cast<double>(n) : 2 * expected_time_s_;
      valence += std::clamp(2.0 * (1.0 - mean / expected_time_s_), -3.0, 2.0);
      break;
    }
    case study::Kind::ListSelection:
      if (measures.contains("time_s") && measures["time_s"].is_number())
        valence += std::clamp(1.5 - measures["time_s"].get<double>() / 2.0, -2.0, 1.5);
      break;
    case study::Kind::Matching:
      valence = 5.0 + model_.valence_bias + 3.0 - 8.0 * match_error_;
      break;
    case study::Kind::Textures: {
      const std::string& texture = measures.value("texture", "");
      valence = 5.0 + model_.valence_bias + 3.0 * name_score(texture, 1);
      arousal = 5.0 + 3.0 * name_score(texture, 2);
      break;
    }
  }
  valence += gauss(0.8);
  arousal += gauss(0.8);
  nlohmann::json out = nlohmann::json::object();
  for (const study::Rating& s : scales) {
    const std::string name(study::scale_name(s.scale));
    if (s.scale == study::Scale::AffectGrid)
      out[name] = {{"valence", on_scale(valence, s)}, {"arousal", on_scale(arousal, s)}};
    else
      out[name] = on_scale(s.scale == study::Scale::SamArousal ? arousal : valence, s);
  }
  return out;
}

}  // namespace knoblab::studyrun
