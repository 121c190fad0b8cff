// Friedman and Wilcoxon signed-rank tests against scipy.stats
// (friedmanchisquare; wilcoxon with its defaults and with
// method="asymptotic", with and without the continuity correction).
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "knoblab/stats/nonparametric.hpp"
#include "reference.hpp"
#include "study_data.hpp"

namespace knoblab::stats {
namespace {

using test::expect_relative;

TEST(Friedman, TiedRatingsMatchScipy) {
  // Study 2/3 shaped: 15 participants rate 7 knob renderings on 1–9.
  const auto y = test::ratings(15, 7, 3);
  const FriedmanResult r = friedman(y);
  EXPECT_LT(r.tie_correction, 1.0);  // ratings tie within subjects
  EXPECT_EQ(r.df, 6);
  const test::Values ref = test::scipy_reference("friedman", y);
  expect_relative(r.statistic, ref, "statistic");
  expect_relative(r.p, ref, "p");
}

TEST(Friedman, ContinuousScoresMatchScipy) {
  const auto y = test::scores(10, 4, 21);
  const FriedmanResult r = friedman(y);
  EXPECT_EQ(r.tie_correction, 1.0);
  const test::Values ref = test::scipy_reference("friedman", y);
  expect_relative(r.statistic, ref, "statistic");
  expect_relative(r.p, ref, "p");
}

TEST(Friedman, DegenerateDataThrowsInvalidArgument) {
  using Rows = std::vector<std::vector<double>>;
  EXPECT_THROW(friedman(Rows{{1, 2, 3}}), std::invalid_argument);               // n = 1
  EXPECT_THROW(friedman(Rows{{1, 2}, {2, 1}, {1, 3}}), std::invalid_argument);  // k = 2
  EXPECT_THROW(friedman(Rows{{1, 2, 3}, {1, 2}}), std::invalid_argument);
  EXPECT_THROW(friedman(Rows{{5, 5, 5}, {2, 2, 2}}), std::invalid_argument);    // all tied
}

// Ours against scipy's default call and its normal approximation, both
// continuity settings.
void expect_wilcoxon_matches_scipy(const std::vector<double>& x, const std::vector<double>& y,
                                   WilcoxonMethod expected_auto_method) {
  const test::Values ref = test::scipy_reference("wilcoxon", test::columns(x, y));
  const WilcoxonResult automatic = wilcoxon(x, y);
  EXPECT_EQ(automatic.method, expected_auto_method);
  expect_relative(automatic.statistic, ref, "statistic");
  expect_relative(automatic.p, ref, "p");
  for (const bool cc : {false, true}) {
    const WilcoxonResult normal = wilcoxon(x, y, {WilcoxonMethod::normal, cc});
    const std::string suffix = cc ? "normal_cc" : "normal";
    expect_relative(normal.p, ref, "p_" + suffix);
    expect_relative(std::abs(normal.z), ref, "abs_z_" + suffix);
  }
}

TEST(Wilcoxon, ExactPWithoutTiesMatchesScipy) {
  for (const std::size_t n : {5u, 20u, 50u}) {
    SCOPED_TRACE(n);
    const auto y = test::scores(n, 2, 40 + static_cast<unsigned>(n), 0.5);
    expect_wilcoxon_matches_scipy(test::column(y, 0), test::column(y, 1), WilcoxonMethod::exact);
  }
}

TEST(Wilcoxon, TiesAndZerosInSmallSamplesMatchScipysExactPermutation) {
  // 12 rating pairs: ties and zero differences; scipy enumerates all 2¹²
  // sign flips, as the exact method here does.
  const auto y = test::ratings(12, 2, 1);
  const WilcoxonResult r = wilcoxon(test::column(y, 0), test::column(y, 1));
  ASSERT_TRUE(r.ties);
  ASSERT_GT(r.zeros, 0u);
  expect_wilcoxon_matches_scipy(test::column(y, 0), test::column(y, 1), WilcoxonMethod::exact);
}

TEST(Wilcoxon, TiesAndZerosInLargerSamplesMatchScipysNormalApproximation) {
  const auto y = test::ratings(40, 2, 9);
  const WilcoxonResult r = wilcoxon(test::column(y, 0), test::column(y, 1));
  ASSERT_TRUE(r.ties);
  ASSERT_GT(r.zeros, 0u);
  expect_wilcoxon_matches_scipy(test::column(y, 0), test::column(y, 1), WilcoxonMethod::normal);
}

TEST(Wilcoxon, AboveFiftyPairsUsesTheNormalApproximationLikeScipy) {
  const auto y = test::scores(60, 2, 12, 0.3);
  expect_wilcoxon_matches_scipy(test::column(y, 0), test::column(y, 1), WilcoxonMethod::normal);
}

TEST(Wilcoxon, ZeroDifferencesAreDroppedBeforeRanking) {
  const std::vector<double> x = {3, 5, 2, 8, 4, 6, 7, 1}, y = {3, 2, 2, 3, 5, 6, 1, 1};
  const WilcoxonResult with_zeros = wilcoxon(x, y);
  EXPECT_EQ(with_zeros.zeros, 4u);
  EXPECT_EQ(with_zeros.n, 4u);
  // The same as the four nonzero pairs alone: differences 3, 5, −1, 6.
  const std::vector<double> x4 = {5, 8, 4, 7}, y4 = {2, 3, 5, 1};
  const WilcoxonResult without = wilcoxon(x4, y4);
  EXPECT_EQ(with_zeros.r_plus, 9);
  EXPECT_EQ(with_zeros.r_minus, 1);
  EXPECT_EQ(with_zeros.statistic, without.statistic);
  EXPECT_EQ(with_zeros.p, without.p);  // exact both times (8 pairs, 4 pairs)
  EXPECT_DOUBLE_EQ(with_zeros.p, 2 * 2.0 / 16);  // R+ ≥ 9 in 2 of 16 sign patterns
}

TEST(Wilcoxon, DegenerateDataThrowsInvalidArgument) {
  const std::vector<double> a = {1, 2, 3}, b = {1, 2}, nan = {1, std::numeric_limits<double>::quiet_NaN(), 3};
  EXPECT_THROW(wilcoxon(a, b), std::invalid_argument);
  EXPECT_THROW(wilcoxon(a, a), std::invalid_argument);  // every difference zero
  EXPECT_THROW(wilcoxon(a, nan), std::invalid_argument);
  EXPECT_THROW(wilcoxon({}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::stats
