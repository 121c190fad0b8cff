// Repeated-measures ANOVA against base R: anova.mlm's sphericity test
// (F, dfs, p, the Greenhouse–Geisser and Huynh–Feldt epsilons and their p)
// and aov's subject stratum (the sums of squares).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "knoblab/stats/rm_anova.hpp"
#include "reference.hpp"
#include "study_data.hpp"

namespace knoblab::stats {
namespace {

using test::expect_relative;

void expect_matches_r(const RmAnovaResult& r, const test::Values& ref) {
  expect_relative(r.f, ref, "f");
  expect_relative(r.f, ref, "aov_f");
  expect_relative(r.df1, ref, "df1");
  expect_relative(r.df2, ref, "df2");
  expect_relative(r.p, ref, "p");
  expect_relative(r.epsilon_gg, ref, "epsilon_gg");
  expect_relative(r.p_gg, ref, "p_gg");
  expect_relative(r.epsilon_hf, ref, "epsilon_hf");
  expect_relative(r.p_hf, ref, "p_hf");
  expect_relative(r.ss_conditions, ref, "ss_conditions");
  expect_relative(r.ss_error, ref, "ss_error");
  expect_relative(r.ss_subjects, ref, "ss_subjects");
  const double eta = ref.at("ss_conditions") / (ref.at("ss_conditions") + ref.at("ss_error"));
  EXPECT_NEAR(r.partial_eta_squared, eta, 1e-9 * eta);
}

TEST(RmAnova, GreenhouseGeisserMatchesR) {
  // 12 subjects × 5 conditions, spreads growing 3× across conditions:
  // clearly non-spherical (ε well below 1, Huynh–Feldt below 1 too).
  const auto y = test::scores(12, 5, 7, 0.6, 0.5);
  const RmAnovaResult r = rm_anova(y);
  EXPECT_LT(r.epsilon_gg, 0.8);
  EXPECT_LT(r.epsilon_hf, 1.0);
  EXPECT_GE(r.epsilon_gg, 1.0 / 4);
  EXPECT_GT(r.p_gg, r.p);
  expect_matches_r(r, test::r_rm_anova_reference(y));
}

TEST(RmAnova, HuynhFeldtAboveOneIsCappedForItsPValueAsInR) {
  // Near-spherical data: ε_HF > 1 is reported as is, its p uses ε = 1.
  const auto y = test::scores(10, 3, 1, 0.3, 0.0);
  const RmAnovaResult r = rm_anova(y);
  ASSERT_GT(r.epsilon_hf, 1.0);
  EXPECT_EQ(r.p_hf, r.p);
  expect_matches_r(r, test::r_rm_anova_reference(y));
}

TEST(RmAnova, TwoConditionsEqualThePairedTTest) {
  const auto y = test::scores(9, 2, 5);
  const RmAnovaResult r = rm_anova(y);
  const test::Values ref = test::scipy_reference("ttest_rel", test::columns(test::column(y, 0), test::column(y, 1)));
  EXPECT_NEAR(r.f, ref.at("t") * ref.at("t"), 1e-9 * r.f);
  expect_relative(r.p, ref, "p");
  EXPECT_NEAR(r.epsilon_gg, 1.0, 1e-12);  // one contrast: nothing to correct
  EXPECT_NEAR(r.p_gg, r.p, 1e-12);
}

TEST(RmAnova, DegenerateDataThrowsInvalidArgument) {
  using Rows = std::vector<std::vector<double>>;
  EXPECT_THROW(rm_anova(Rows{}), std::invalid_argument);
  EXPECT_THROW(rm_anova(Rows{{1, 2, 3}}), std::invalid_argument);             // n = 1
  EXPECT_THROW(rm_anova(Rows{{1, 2, 3}, {2, 3, 5}}), std::invalid_argument);  // n = 2
  EXPECT_THROW(rm_anova(Rows{{1}, {2}, {3}}), std::invalid_argument);         // k = 1
  EXPECT_THROW(rm_anova(Rows{{1, 2}, {2, 3}, {3}}), std::invalid_argument);   // incomplete case
  EXPECT_THROW(rm_anova(Rows{{1, 2}, {2, std::numeric_limits<double>::quiet_NaN()}, {3, 1}}),
               std::invalid_argument);
  EXPECT_THROW(rm_anova(Rows{{4, 4}, {4, 4}, {4, 4}}), std::invalid_argument);  // constant
  // Every subject = its offset + the same condition effects: no error term.
  try {
    rm_anova(Rows{{1.1, 2.2, 3.7}, {2.1, 3.2, 4.7}, {0.6, 1.7, 3.2}});
    ADD_FAILURE() << "no within-subject error must throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no within-subject error"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace knoblab::stats
