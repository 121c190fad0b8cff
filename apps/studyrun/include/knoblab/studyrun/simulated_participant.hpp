// A simulated participant: a model of a person's hand and judgement that runs
// any study end to end, for tests and demos. It turns the simulated knob only
// through a hand on it (sim/guided_hand.hpp) — on hapticd's sim backend, over
// the shared-memory hand channel — so the rendered model pushes back on its
// movements as it would on a person's: friction slows them, inertia carries
// the knob past the target, detents pull it into place.
//
// Movements are minimum-jerk reaches begun a reaction time after what they
// answer appears, lasting as Fitts' law says (MT = a + b·log2(D/W + 1)),
// aimed at a point drawn around the target's centre (SD proportional to its
// width); a reach that ends outside the target is followed by a corrective
// one. Ratings come from a latent valence (the participant's bias, a liking
// for some friction and inertia but not much, and how the trial went against
// how it expected it to go) and arousal (how much torque it felt), with
// noise, put on each scale's range and direction. Every draw comes from one
// generator seeded by the participant, so a run is reproducible.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "knoblab/sim/guided_hand.hpp"
#include "knoblab/studyrun/participant.hpp"

namespace knoblab::studyrun {

struct ParticipantModel {
  double reaction_s = 0.22;          // mean reaction time
  double fitts_a_s = 0.12;           // MT = a + b·log2(D/W + 1)
  double fitts_b_s_per_bit = 0.11;
  double aim_sd_per_width = 1.0 / 4.133;  // aim SD as a fraction of the target's width
  double peak_speed_rad_s = 12.0;    // the fastest a wrist turns the knob (about 2 rev/s)
  double grip_stiffness = 1.0;       // N·m/rad
  double grip_damping = 0.01;        // N·m·s/rad
  double speed = 1.0;                // this participant's pace (> 1: slower)
  double valence_bias = 0;           // this participant's leaning, scale points
  // Drawn for participant `index` of a study seeded `seed`: pace and bias
  // vary between participants as people's do.
  static ParticipantModel draw(std::uint64_t seed);
};

class SimulatedParticipant final : public Participant {
 public:
  SimulatedParticipant(sim::HandChannel& hand, ParticipantModel model, std::uint64_t seed);

  void begin_trial(const study::Protocol& protocol, const study::Trial& trial) override;
  Action act(const Display& display, const KnobReading& reading) override;
  nlohmann::json rate(const std::vector<study::Rating>& scales, const nlohmann::json& measures) override;
  // One or two of the words Table 15's novices wrote for the slider's term,
  // drawn from a generator of their own seeded by `seed`, so the words do
  // not shift the draws of the trials.
  std::map<std::string, std::string> slider_tags(const std::vector<study::Slider>& sliders) override;

  // Lets go of the knob (between sessions).
  void release();

 private:
  struct Reach {
    double start_t = 0, target = 0, duration = 0;
  };
  void plan_reach(double now, double aim, double width, double delay);
  void pointing(const Display& d, const KnobReading& r);
  void list(const Display& d, const KnobReading& r);
  Action matching(const Display& d, const KnobReading& r);
  void explore(const KnobReading& r);
  double fitts_time(double distance, double width) const;
  double gauss(double sd) { return std::normal_distribution<double>(0, sd)(rng_); }

  sim::HandChannel& hand_;
  ParticipantModel model_;
  std::uint64_t seed_;
  std::mt19937_64 rng_;
  const study::Protocol* protocol_ = nullptr;
  study::Trial trial_;
  std::uint64_t seen_version_ = 0;
  bool holding_ = false;        // the hand is on the knob
  double grip_ = 1.0;           // the grip's stiffness now, N·m/rad
  double hand_target_ = 0;      // where the last reach sent the hand
  double reach_end_t_ = 0;      // when it ends
  std::optional<double> explore_centre_;  // where this trial's exploring began, rad
  std::optional<Reach> pending_;
  double trial_start_t_ = -1;
  double expected_time_s_ = 0;  // what the trial "should" take, for the ratings
  double torque_sum_ = 0;
  std::size_t torque_n_ = 0;
  // Matching: where the sliders are headed and when the next move is due.
  study::Rendering slider_goal_, sliders_;
  int slider_steps_left_ = 0;
  double next_slider_t_ = 0;
  double match_error_ = 0;
  double stroke_s_ = 0;
};

}  // namespace knoblab::studyrun
