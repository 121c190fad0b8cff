// Pearson and Spearman correlation against scipy.stats (pearsonr,
// spearmanr).
#include <gtest/gtest.h>

#include <stdexcept>

#include "knoblab/stats/correlation.hpp"
#include "reference.hpp"
#include "study_data.hpp"

namespace knoblab::stats {
namespace {

using test::expect_relative;

TEST(Pearson, MatchesScipy) {
  const auto y = test::scores(25, 2, 31, 0.2, 0.3);
  const CorrelationResult r = pearson(test::column(y, 0), test::column(y, 1));
  const test::Values ref = test::scipy_reference("pearson", test::columns(test::column(y, 0), test::column(y, 1)));
  expect_relative(r.r, ref, "r");
  expect_relative(r.p, ref, "p");
  EXPECT_EQ(r.n, 25u);
}

TEST(Spearman, TiedRatingsMatchScipy) {
  // Rating against a continuous measure (Tables 23–25: rating vs EMG, SC).
  const auto ratings = test::ratings(30, 2, 14);
  const auto scores = test::scores(30, 2, 15);
  std::vector<double> rating = test::column(ratings, 0), measure = test::column(scores, 0);
  for (std::size_t i = 0; i < measure.size(); ++i) measure[i] += 0.4 * rating[i];
  const CorrelationResult r = spearman(rating, measure);
  const test::Values ref = test::scipy_reference("spearman", test::columns(rating, measure));
  expect_relative(r.r, ref, "r");
  expect_relative(r.p, ref, "p");
  // Both samples tied: ratings against ratings.
  const CorrelationResult both = spearman(test::column(ratings, 0), test::column(ratings, 1));
  const test::Values both_ref =
      test::scipy_reference("spearman", test::columns(test::column(ratings, 0), test::column(ratings, 1)));
  expect_relative(both.r, both_ref, "r");
  expect_relative(both.p, both_ref, "p");
}

TEST(Correlation, PerfectAndDegenerateData) {
  const std::vector<double> x = {1, 2, 3, 4}, y = {2, 4, 6, 8}, down = {9, 7, 5, 1};
  EXPECT_EQ(pearson(x, y).r, 1.0);
  EXPECT_EQ(pearson(x, y).p, 0.0);
  EXPECT_EQ(spearman(x, down).r, -1.0);
  EXPECT_EQ(spearman(x, down).p, 0.0);
  const std::vector<double> constant = {5, 5, 5, 5}, two = {1, 2}, three = {1, 2, 3};
  EXPECT_THROW(pearson(x, constant), std::invalid_argument);
  EXPECT_THROW(spearman(constant, x), std::invalid_argument);
  EXPECT_THROW(pearson(two, two), std::invalid_argument);  // n − 2 = 0 df
  EXPECT_THROW(spearman(x, three), std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::stats
