// The plan rules of plan.hpp. One engine is threaded through the whole plan
// in run order, so a plan depends only on the protocol, the participant code
// (the seed) and the participant index (the Williams row).
#include "knoblab/study/plan.hpp"

#include <stdexcept>

#include "knoblab/study/latin_square.hpp"
#include "knoblab/study/participant.hpp"
#include "knoblab/study/shuffle.hpp"

namespace knoblab::study {

namespace {

using Condition = std::vector<std::size_t>;  // a level index per factor

// The stage's conditions with the first factor varying slowest.
std::vector<Condition> listed_conditions(const Stage& stage) {
  std::vector<Condition> out;
  Condition c(stage.allowed.size());
  std::vector<std::size_t> digit(stage.allowed.size(), 0);
  for (;;) {
    for (std::size_t f = 0; f < c.size(); ++f) c[f] = stage.allowed[f][digit[f]];
    out.push_back(c);
    std::size_t f = c.size();
    while (f > 0 && ++digit[f - 1] == stage.allowed[f - 1].size()) digit[--f] = 0;
    if (f == 0) return out;
  }
}

class Planner {
 public:
  Planner(const Protocol& protocol, Plan& plan)
      : protocol_(protocol), plan_(plan), engine_(plan.seed) {}

  void run() {
    for (std::size_t s = 0; s < protocol_.stages.size(); ++s) {
      conditions_.push_back(listed_conditions(protocol_.stages[s]));
      if (protocol_.order.scheme == OrderScheme::LatinSquare) {
        const std::size_t levels = protocol_.stages[s].allowed[protocol_.order.factor].size();
        plan_.latin_rows.push_back(plan_.participant_index % williams_rows(levels));
      }
    }
    for (std::size_t block = 1; block <= protocol_.blocks; ++block) {
      const bool practice_block = block <= protocol_.practice.blocks;
      for (std::size_t s = 0; s < protocol_.stages.size(); ++s) {
        if (block == 1) practice_trials(s);
        for (std::size_t rep = 1; rep <= protocol_.repetitions; ++rep)
          for (const Condition& c : ordered(s)) add(block, s, practice_block, rep, c);
      }
    }
  }

 private:
  // Passes over the stage, each ordered like a repetition, cut at the count.
  void practice_trials(std::size_t s) {
    std::size_t left = protocol_.practice.trials;
    while (left > 0) {
      for (const Condition& c : ordered(s)) {
        if (left == 0) break;
        add(1, s, true, 0, c);
        --left;
      }
    }
  }

  // One complete pass over the stage's conditions in the scheme's order.
  std::vector<Condition> ordered(std::size_t s) {
    std::vector<Condition> cs = conditions_[s];
    switch (protocol_.order.scheme) {
      case OrderScheme::Fixed: break;
      case OrderScheme::Random: fisher_yates(std::span<Condition>(cs), engine_); break;
      case OrderScheme::LatinSquare: {
        // The factor's levels (those the stage takes) in the participant's
        // Williams row; within a level, the other factors in listed order.
        const std::size_t f = protocol_.order.factor;
        const std::vector<std::size_t>& levels = protocol_.stages[s].allowed[f];
        std::vector<Condition> out;
        for (const std::size_t k : williams_row(levels.size(), plan_.latin_rows[s]))
          for (const Condition& c : cs)
            if (c[f] == levels[k]) out.push_back(c);
        cs = std::move(out);
        break;
      }
    }
    return cs;
  }

  void add(std::size_t block, std::size_t stage, bool practice, std::size_t repetition, const Condition& c) {
    Trial t;
    t.index = plan_.trials.size() + 1;
    t.block = block;
    t.stage = stage;
    t.practice = practice;
    t.repetition = repetition;
    t.levels = c;
    if (const auto* pointing = std::get_if<PointingSettings>(&protocol_.settings)) t.targets = targets(*pointing, t);
    plan_.trials.push_back(std::move(t));
  }

  // Back and forth (§4.6.1.3, Fig. 58): odd acquisitions go out to the
  // target `amplitude` away, even ones come back to home; all targets share
  // the condition's width.
  std::vector<Target> targets(const PointingSettings& s, const Trial& t) {
    const double amplitude = *protocol_.factors[s.amplitude_factor].levels[t.levels[s.amplitude_factor]].amplitude_rad;
    const double width = *protocol_.factors[s.width_factor].levels[t.levels[s.width_factor]].width_rad;
    int first = 1;
    switch (s.first_direction) {
      case Direction::Positive: first = 1; break;
      case Direction::Negative: first = -1; break;
      case Direction::Alternate: first = t.index % 2 == 1 ? 1 : -1; break;
      case Direction::Random: first = uniform_below(engine_, 2) == 0 ? 1 : -1; break;
    }
    std::vector<Target> out;
    for (unsigned a = 1; a <= s.acquisitions; ++a) {
      const bool out_leg = a % 2 == 1;
      out.push_back({a, out_leg ? first * amplitude : 0.0, width, out_leg ? first : -first});
    }
    return out;
  }

  const Protocol& protocol_;
  Plan& plan_;
  Engine engine_;
  std::vector<std::vector<Condition>> conditions_;  // per stage, listed order
};

}  // namespace

Plan plan(const Protocol& protocol, std::string_view participant_code, std::size_t participant_index) {
  check_participant_code(participant_code);
  Plan out;
  out.study = protocol.study;
  out.participant = std::string(participant_code);
  out.participant_index = participant_index;
  out.seed = participant_seed(protocol.seed, participant_code);
  Planner(protocol, out).run();
  return out;
}

const Level& trial_level(const Protocol& protocol, const Trial& trial, std::size_t factor) {
  if (factor >= protocol.factors.size() || trial.levels.size() != protocol.factors.size())
    throw std::out_of_range("trial_level: no such factor in this trial");
  return protocol.factors[factor].levels.at(trial.levels[factor]);
}

std::string condition_label(const Protocol& protocol, const Trial& trial) {
  std::string label;
  for (std::size_t f = 0; f < protocol.factors.size(); ++f)
    label += (f ? " " : "") + protocol.factors[f].name + "=" + trial_level(protocol, trial, f).name;
  return label;
}

}  // namespace knoblab::study
