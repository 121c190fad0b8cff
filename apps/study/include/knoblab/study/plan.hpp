// One participant's trial plan: every trial of a protocol in the order it is
// run, made deterministically from the protocol and the participant
// (docs/studies.md, "Plan rules").
//
//   for each block b = 1 … blocks            (practice when b ≤ practice.blocks)
//     for each stage, in the file's order
//       practice.trials practice trials       (first block only)
//       for each repetition r = 1 … repetitions
//         the stage's conditions, each once, in the order scheme's order
//
// A condition is one level of every factor; a stage's conditions are the
// combinations of the levels it allows, first factor varying slowest.
// Random orders draw from one std::mt19937_64 seeded with
// participant_seed(protocol.seed, code), in plan order: each pass (a
// repetition, or a pass practice trials are taken from) is shuffled when it
// is reached, and a pointing study with a random first direction then draws
// once for each trial as it is added.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/study/protocol.hpp"

namespace knoblab::study {

// One target of a pointing trial, relative to the home position where the
// trial starts: acquisitions alternate between a target `amplitude` away and
// a target back at home, each reached by a movement in `direction`.
struct Target {
  unsigned acquisition = 0;  // 1-based
  double centre_rad = 0;     // from the home position
  double width_rad = 0;
  int direction = 0;         // +1: towards positive θ, −1: towards negative θ
  bool operator==(const Target&) const = default;
};

struct Trial {
  std::size_t index = 0;       // 1-based position in the plan
  std::size_t block = 0;       // 1-based
  std::size_t stage = 0;       // index into Protocol::stages
  bool practice = false;       // run, not analysed
  std::size_t repetition = 0;  // 1-based; 0 for a stage's practice trials
  std::vector<std::size_t> levels;  // per factor: index into its levels
  std::vector<Target> targets;      // pointing only
  bool operator==(const Trial&) const = default;
};

struct Plan {
  std::string study;
  std::string participant;
  std::size_t participant_index = 0;
  std::uint64_t seed = 0;               // participant_seed(study seed, code)
  // latin_square only: per stage, the Williams row of the stage's levels of
  // the order's factor (participant_index mod the square's rows).
  std::vector<std::size_t> latin_rows;
  std::vector<Trial> trials;
};

// Throws std::invalid_argument for an invalid participant code.
// participant_index counts participants from 0; it picks the Williams row
// (index mod the number of rows) and nothing else.
Plan plan(const Protocol& protocol, std::string_view participant_code, std::size_t participant_index);

// The level of factor `factor` in this trial.
const Level& trial_level(const Protocol& protocol, const Trial& trial, std::size_t factor);

// "knob=low-friction amplitude=A30 width=W1.4": for logs and test messages.
std::string condition_label(const Protocol& protocol, const Trial& trial);

}  // namespace knoblab::study
