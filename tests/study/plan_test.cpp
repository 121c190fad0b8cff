// Plans: deterministic, complete, practice first and flagged, ordered as the
// scheme says, with pointing targets back and forth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include "examples.hpp"
#include "knoblab/study/latin_square.hpp"
#include "knoblab/study/plan.hpp"
#include "python_reference.hpp"

namespace knoblab::study {
namespace {

using test::example;
using test::example_json;
using Condition = std::vector<std::size_t>;

std::vector<Condition> orders(const Plan& p) {
  std::vector<Condition> out;
  for (const Trial& t : p.trials) out.push_back(t.levels);
  return out;
}

// The conditions a stage takes, in no particular order.
std::multiset<Condition> stage_conditions(const Protocol& protocol, std::size_t s) {
  std::multiset<Condition> out;
  std::vector<Condition> partial = {{}};
  for (const auto& allowed : protocol.stages[s].allowed) {
    std::vector<Condition> next;
    for (const Condition& c : partial)
      for (const std::size_t level : allowed) {
        next.push_back(c);
        next.back().push_back(level);
      }
    partial = std::move(next);
  }
  out.insert(partial.begin(), partial.end());
  return out;
}

TEST(Plan, TheSamePlanComesFromTheSameInput) {
  for (const auto& name : test::example_names()) {
    const Protocol p = example(name);
    EXPECT_EQ(plan(p, "P07", 6).trials, plan(p, "P07", 6).trials) << name;
    EXPECT_EQ(plan(p, "P07", 6).trials, plan(example(name), "P07", 6).trials) << name;
  }
}

TEST(Plan, AnotherParticipantGetsAnotherOrder) {
  for (const auto& name : test::example_names()) {
    const Protocol p = example(name);
    EXPECT_NE(orders(plan(p, "P01", 0)), orders(plan(p, "P02", 1))) << name;
  }
}

TEST(Plan, ARandomOrderDependsOnTheCodeNotTheIndex) {
  const Protocol p = example("pointing.json");
  EXPECT_EQ(plan(p, "P01", 0).trials, plan(p, "P01", 5).trials);
}

TEST(Plan, AnotherStudySeedGivesAnotherOrder) {
  nlohmann::json file = example_json("pointing.json");
  const Plan a = plan(parse_protocol(file), "P01", 0);
  file["seed"] = file["seed"].get<std::uint64_t>() + 1;
  EXPECT_NE(orders(a), orders(plan(parse_protocol(file), "P01", 0)));
}

TEST(Plan, AnInvalidParticipantCodeIsRefused) {
  const Protocol p = example("textures.json");
  EXPECT_THROW(plan(p, "Alice", 0), std::invalid_argument);
  EXPECT_THROW(plan(p, "", 0), std::invalid_argument);
}

TEST(Plan, IndicesCountFromOneInRunOrder) {
  const Plan p = plan(example("list-selection.json"), "P03", 2);
  for (std::size_t i = 0; i < p.trials.size(); ++i) EXPECT_EQ(p.trials[i].index, i + 1);
}

// Every stage of every block runs each of its conditions exactly once per
// repetition, and the practice trials come on top.
TEST(Plan, EveryConditionRunsOncePerRepetitionInEveryStageOfEveryBlock) {
  for (const auto& name : test::example_names()) {
    const Protocol p = example(name);
    for (const char* code : {"P01", "P02", "X9"}) {
      const Plan pl = plan(p, code, 3);
      std::map<std::tuple<std::size_t, std::size_t, std::size_t>, std::multiset<Condition>> passes;
      std::size_t practice_trials = 0;
      for (const Trial& t : pl.trials) {
        if (t.repetition == 0) {
          ++practice_trials;
          continue;
        }
        passes[{t.block, t.stage, t.repetition}].insert(t.levels);
      }
      EXPECT_EQ(passes.size(), p.blocks * p.stages.size() * p.repetitions) << name;
      for (const auto& [key, conditions] : passes)
        EXPECT_EQ(conditions, stage_conditions(p, std::get<1>(key))) << name << " block " << std::get<0>(key);
      EXPECT_EQ(practice_trials, p.practice.trials * p.stages.size()) << name;
    }
  }
}

TEST(Plan, TrialCountsAreTheThesisProcedures) {
  EXPECT_EQ(plan(example("pointing.json"), "P01", 0).trials.size(), 4u * 28u);  // 4 blocks of 28
  EXPECT_EQ(plan(example("matching-novice.json"), "P01", 0).trials.size(), 3u * 5u);
  EXPECT_EQ(plan(example("matching-expert.json"), "P01", 0).trials.size(), 5u);
  EXPECT_EQ(plan(example("list-selection.json"), "P01", 0).trials.size(), 2u * 2u + 2u * 2u * 7u);
  EXPECT_EQ(plan(example("textures.json"), "P01", 0).trials.size(), 12u + 12u);
}

// Practice trials open their stage in the first block; practice blocks open
// the plan; practice is flagged and nothing else is.
TEST(Plan, PracticeComesFirstAndIsFlagged) {
  for (const auto& name : test::example_names()) {
    const Protocol p = example(name);
    const Plan pl = plan(p, "P11", 10);
    std::set<std::size_t> stages_started;
    for (const Trial& t : pl.trials) {
      const bool practice_trial = t.repetition == 0;
      const bool in_practice_block = t.block <= p.practice.blocks;
      EXPECT_EQ(t.practice, practice_trial || in_practice_block) << name << " trial " << t.index;
      if (practice_trial) {
        EXPECT_EQ(t.block, 1u);
        EXPECT_FALSE(stages_started.contains(t.stage)) << name << ": practice after the stage began";
      } else {
        stages_started.insert(t.stage);
      }
    }
    // Practice blocks come before any analysed trial.
    bool analysed_seen = false;
    for (const Trial& t : pl.trials) {
      if (!t.practice) analysed_seen = true;
      if (analysed_seen) {
        EXPECT_GT(t.block, p.practice.blocks) << name;
      }
    }
  }
}

TEST(Plan, PointingsFirstBlockIsPracticeAndTheOtherThreeAreAnalysed) {
  const Plan pl = plan(example("pointing.json"), "P01", 0);
  for (const Trial& t : pl.trials) EXPECT_EQ(t.practice, t.block == 1);
}

TEST(Plan, TexturesOpenWithOneFullPracticePass) {
  const Plan pl = plan(example("textures.json"), "P01", 0);
  std::set<std::size_t> practised;
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_TRUE(pl.trials[i].practice);
    practised.insert(pl.trials[i].levels[0]);
  }
  EXPECT_EQ(practised.size(), 12u);
  for (std::size_t i = 12; i < pl.trials.size(); ++i) EXPECT_FALSE(pl.trials[i].practice);
}

TEST(Plan, PracticeTrialsBeyondOnePassStartAnotherPass) {
  nlohmann::json file = example_json("matching-expert.json");
  file["practice"] = {{"trials", 7}};
  const Protocol p = parse_protocol(file);
  const Plan pl = plan(p, "P01", 0);
  std::multiset<std::size_t> first_five;
  for (std::size_t i = 0; i < 5; ++i) first_five.insert(pl.trials[i].levels[0]);
  EXPECT_EQ(first_five, (std::multiset<std::size_t>{0, 1, 2, 3, 4}));
  for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(pl.trials[i].repetition, 0u);
  EXPECT_EQ(pl.trials.size(), 12u);
}

TEST(Plan, NovicesMatchTheKnobsWithoutDetentsFirstEachRepetitionShuffled) {
  const Protocol p = example("matching-novice.json");
  std::set<Condition> first_orders;
  for (std::size_t i = 0; i < 20; ++i) {
    const Plan pl = plan(p, "P" + std::to_string(i + 10), i);
    ASSERT_EQ(pl.trials.size(), 15u);
    for (std::size_t k = 0; k < 15; ++k) {
      const Trial& t = pl.trials[k];
      EXPECT_EQ(t.stage, k < 6 ? 0u : 1u);
      EXPECT_EQ(t.levels[0] < 2, k < 6) << condition_label(p, t);
      EXPECT_EQ(t.repetition, k < 6 ? k / 2 + 1 : (k - 6) / 3 + 1);
    }
    first_orders.insert({pl.trials[6].levels[0], pl.trials[7].levels[0], pl.trials[8].levels[0]});
  }
  EXPECT_GT(first_orders.size(), 1u);  // the detent knobs' order varies between participants
}

TEST(Plan, ListSelectionRunsFreeformExplorationBeforeTargetFinding) {
  const Protocol p = example("list-selection.json");
  const auto& s = std::get<ListSelectionSettings>(p.settings);
  const Plan pl = plan(p, "P05", 4);
  bool target_seen = false;
  for (const Trial& t : pl.trials) {
    const bool freeform = t.levels[s.context_factor] == s.freeform_level;
    if (!freeform) target_seen = true;
    EXPECT_FALSE(freeform && target_seen) << t.index;
  }
  ASSERT_EQ(pl.trials.size(), 32u);
  EXPECT_TRUE(pl.trials[0].practice && pl.trials[1].practice);
  EXPECT_TRUE(pl.trials[16].practice && pl.trials[17].practice);  // target finding's two
  EXPECT_FALSE(pl.trials[2].practice || pl.trials[18].practice);
}

TEST(Plan, AFixedOrderIsTheListedOrderFirstFactorSlowest) {
  nlohmann::json file = example_json("pointing.json");
  file["order"] = {{"scheme", "fixed"}};
  const Plan pl = plan(parse_protocol(file), "P01", 0);
  for (std::size_t i = 0; i < 28; ++i) EXPECT_EQ(pl.trials[i].levels, (Condition{i / 4, i / 2 % 2, i % 2}));
  for (std::size_t i = 28; i < pl.trials.size(); ++i) EXPECT_EQ(pl.trials[i].levels, pl.trials[i % 28].levels);
}

TEST(Plan, ALatinSquareOrdersTheFactorByTheParticipantsWilliamsRow) {
  nlohmann::json file = example_json("pointing.json");
  file["order"] = {{"scheme", "latin_square"}, {"factor", "knob"}};
  const Protocol p = parse_protocol(file);
  for (std::size_t participant = 0; participant < 16; ++participant) {
    const Plan pl = plan(p, "P" + std::to_string(participant + 1), participant);
    ASSERT_EQ(pl.latin_rows, (std::vector<std::size_t>{participant % 14}));
    const auto row = williams_row(7, participant);
    for (std::size_t block = 0; block < 4; ++block)
      for (std::size_t i = 0; i < 28; ++i) {
        const Trial& t = pl.trials[block * 28 + i];
        // Knobs in row order, each with its four amplitude × width conditions in listed order.
        EXPECT_EQ(t.levels, (Condition{row[i / 4], i / 2 % 2, i % 2})) << participant;
      }
  }
  // Participants 14 apart share a row; their codes do not matter.
  EXPECT_EQ(orders(plan(p, "P01", 0)), orders(plan(p, "P15", 14)));
}

TEST(Plan, ALatinSquareOverAStagesLevelsIsBalancedWithinTheStage) {
  nlohmann::json file = example_json("matching-novice.json");
  file["order"] = {{"scheme", "latin_square"}, {"factor", "knob"}};
  const Protocol p = parse_protocol(file);
  // Stage "with-detents" takes C, D, E: a 3-level square, 6 rows, each
  // ordered pair adjacent twice across the six participants.
  std::map<std::pair<std::size_t, std::size_t>, int> adjacent;
  for (std::size_t participant = 0; participant < 6; ++participant) {
    const Plan pl = plan(p, "P" + std::to_string(participant + 1), participant);
    EXPECT_EQ(pl.latin_rows, (std::vector<std::size_t>{participant % 2, participant}));
    ++adjacent[{pl.trials[6].levels[0], pl.trials[7].levels[0]}];
    ++adjacent[{pl.trials[7].levels[0], pl.trials[8].levels[0]}];
  }
  EXPECT_EQ(adjacent.size(), 6u);
  for (const auto& [pair, count] : adjacent) EXPECT_EQ(count, 2) << pair.first << " before " << pair.second;
}

TEST(Plan, PointingTrialsGoOutAndBackThreeTimesWithTheConditionsTargets) {
  const Protocol p = example("pointing.json");
  const auto& s = std::get<PointingSettings>(p.settings);
  const Plan pl = plan(p, "P01", 0);
  std::set<int> first_directions;
  for (const Trial& t : pl.trials) {
    ASSERT_EQ(t.targets.size(), 3u);
    const double amplitude = *trial_level(p, t, s.amplitude_factor).amplitude_rad;
    const double width = *trial_level(p, t, s.width_factor).width_rad;
    const int d = t.targets[0].direction;
    first_directions.insert(d);
    for (unsigned a = 0; a < 3; ++a) {
      EXPECT_EQ(t.targets[a].acquisition, a + 1);
      EXPECT_EQ(t.targets[a].width_rad, width);
      EXPECT_EQ(t.targets[a].direction, a == 1 ? -d : d);
      EXPECT_EQ(t.targets[a].centre_rad, a == 1 ? 0.0 : d * amplitude);
    }
  }
  EXPECT_EQ(first_directions, (std::set<int>{-1, 1}));  // random first direction
  for (const auto& name : {"matching-novice.json", "textures.json"})
    for (const Trial& t : plan(example(name), "P01", 0).trials) EXPECT_TRUE(t.targets.empty());
}

TEST(Plan, AFixedFirstDirectionIsKeptAndAlternateAlternates) {
  nlohmann::json file = example_json("pointing.json");
  file["pointing"]["first_direction"] = "negative";
  for (const Trial& t : plan(parse_protocol(file), "P01", 0).trials) EXPECT_EQ(t.targets[0].direction, -1);
  file["pointing"]["first_direction"] = "alternate";
  for (const Trial& t : plan(parse_protocol(file), "P01", 0).trials)
    EXPECT_EQ(t.targets[0].direction, t.index % 2 == 1 ? 1 : -1);
}

// The whole pointing plan as the Python re-implementation of the plan rules
// makes it: one shuffle of the 28 listed conditions per block, then one
// direction draw per trial.
TEST(Plan, APointingPlanMatchesAnIndependentPythonReimplementation) {
  const Protocol p = example("pointing.json");
  for (const char* code : {"P01", "P19"}) {
    const Plan pl = plan(p, code, 0);
    std::ostringstream expected;
    expected << "seed " << pl.seed << "\n";
    for (std::size_t block = 1; block <= 4; ++block) {
      expected << "block " << block;
      for (std::size_t i = 0; i < 28; ++i) {
        const Condition& c = pl.trials[(block - 1) * 28 + i].levels;
        expected << " " << c[0] * 4 + c[1] * 2 + c[2];
      }
      expected << "\ndirections " << block;
      for (std::size_t i = 0; i < 28; ++i) expected << " " << pl.trials[(block - 1) * 28 + i].targets[0].direction;
      expected << "\n";
    }
    const std::string output =
        test::run_python_reference("pointing " + std::to_string(p.seed) + " " + code + " 4 28");
    EXPECT_EQ(output, expected.str()) << code;
  }
}

TEST(Plan, ConditionLabelsNameEachFactorsLevel) {
  const Protocol p = example("pointing.json");
  Trial t;
  t.levels = {1, 1, 0};
  EXPECT_EQ(condition_label(p, t), "knob=low-friction amplitude=A200 width=W1.4");
}

}  // namespace
}  // namespace knoblab::study
