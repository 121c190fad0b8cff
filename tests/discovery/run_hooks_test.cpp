// discover()'s RunHooks: the candidates it reports one by one, and a
// cancellation between candidates ends it with fit::Cancelled.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "effect_data.hpp"
#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::discovery {
namespace {

struct Seen {
  std::string stage;
  std::size_t done = 0, total = 0;
};

TEST(DiscoveryRunHooks, ReportsTheBaseFitThenEachCandidateOfTheRound) {
  const fit::FitData d = test_data::with_effect(1, nullptr);
  std::vector<Seen> seen;
  DiscrepancyOptions opt;
  opt.effects = {EffectId::Gravity, EffectId::Stribeck, EffectId::Offset};
  opt.hooks.progress = [&](std::string_view stage, std::size_t done, std::size_t total) {
    seen.push_back({std::string(stage), done, total});
  };
  opt.hooks.cancelled = [] { return false; };
  const DiscrepancyResult r = discover(d, opt);
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.front().stage, "fitting the base model");
  EXPECT_EQ(seen.back().stage, "residual tests");
  std::vector<std::size_t> round1;
  for (const Seen& s : seen)
    if (s.stage == "trying candidates, round 1") {
      EXPECT_EQ(s.total, 3u);
      round1.push_back(s.done);
    }
  EXPECT_EQ(round1, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_GT(r.train_rows, 0u);
}

TEST(DiscoveryRunHooks, ACancellationBetweenCandidatesThrowsCancelled) {
  const fit::FitData d = test_data::with_effect(1, nullptr);
  std::size_t reached = 0;  // the last candidate reported
  bool in_candidates = false;
  DiscrepancyOptions opt;
  opt.hooks.progress = [&](std::string_view stage, std::size_t done, std::size_t) {
    in_candidates = stage.starts_with("trying candidates");
    if (in_candidates) reached = done;
  };
  // Cancelled once the second candidate is under way.
  opt.hooks.cancelled = [&] { return in_candidates && reached >= 1; };
  EXPECT_THROW(discover(d, opt), fit::Cancelled);
  EXPECT_EQ(reached, 1u);  // it stopped before the third
}

}  // namespace
}  // namespace knoblab::discovery
