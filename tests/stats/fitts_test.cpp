// Rotary Fitts' law: the thesis' Eq. 18 against its Table 27, the
// effective-width throughput against numpy, the MT–ID line against
// scipy.stats.linregress.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "knoblab/stats/fitts.hpp"
#include "reference.hpp"

namespace knoblab::stats {
namespace {

using test::expect_relative;

TEST(Fitts, WelfordIndexReproducesTable27InBaseTen) {
  // Table 27: 30° targets of 1.4° and 11.3° have ID 1.3 and 0.5. (Its 200°
  // columns, 143.4 and 18.2, are A/W + 0.5 with the log left out.)
  EXPECT_NEAR(welford_index_of_difficulty(30, 1.4, 10), 1.3, 0.05);
  EXPECT_NEAR(welford_index_of_difficulty(30, 11.3, 10), 0.5, 0.05);
  EXPECT_NEAR(std::pow(10, welford_index_of_difficulty(200, 1.4, 10)), 143.4, 0.05);
  EXPECT_NEAR(std::pow(10, welford_index_of_difficulty(200, 11.3, 10)), 18.2, 0.05);
  // In bits, Welford's form: log2(30/1.4 + 0.5).
  EXPECT_NEAR(welford_index_of_difficulty(30, 1.4, 2), std::log2(30 / 1.4 + 0.5), 1e-14);
}

// End-points (signed overshoot, degrees) and movement times (s) of one
// condition, generated.
struct Condition {
  std::vector<double> endpoints, times;
};

Condition condition(unsigned seed, std::size_t n) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> overshoot(0.3, 1.1), time(0.9, 0.15);
  Condition c;
  for (std::size_t i = 0; i < n; ++i) {
    c.endpoints.push_back(std::round(overshoot(rng) * 1000) / 1000);
    c.times.push_back(std::round(std::abs(time(rng)) * 1000) / 1000);
  }
  return c;
}

TEST(Fitts, EffectiveThroughputMatchesNumpy) {
  const Condition c = condition(17, 36);
  test::Table rows;
  for (std::size_t i = 0; i < c.endpoints.size(); ++i) rows.push_back({c.endpoints[i], c.times[i], 30.0});
  const test::Values ref = test::scipy_reference("effective_throughput", rows);
  const EffectiveThroughput e = effective_throughput(30, c.endpoints, c.times);
  expect_relative(endpoint_spread(c.endpoints).variance, ref, "variance");
  expect_relative(e.effective_width, ref, "effective_width");
  expect_relative(e.index_of_difficulty, ref, "index_of_difficulty");
  expect_relative(e.throughput, ref, "throughput");
}

TEST(Fitts, LineFitMatchesScipyLinregress) {
  // Four A/W conditions × 20 trials, as Figures 61–62 plot them.
  std::vector<double> id, mt;
  unsigned seed = 50;
  for (const double amplitude : {30.0, 200.0})
    for (const double width : {1.4, 11.3}) {
      const Condition c = condition(seed++, 20);
      const double d = welford_index_of_difficulty(amplitude, width, 2);
      for (const double t : c.times) {
        id.push_back(d);
        mt.push_back(t + 0.05 * d);
      }
    }
  const LineFit f = fit_line(id, mt);
  const test::Values ref = test::scipy_reference("linregress", test::columns(id, mt));
  expect_relative(f.slope, ref, "slope");
  expect_relative(f.intercept, ref, "intercept");
  expect_relative(f.r_squared, ref, "r_squared");
}

TEST(Fitts, DegenerateDataThrowsInvalidArgument) {
  const std::vector<double> one = {1.0}, same = {2.0, 2.0, 2.0}, times = {0.8, 0.9, 1.0};
  EXPECT_THROW(welford_index_of_difficulty(30, 0, 2), std::invalid_argument);
  EXPECT_THROW(welford_index_of_difficulty(30, 1, 1), std::invalid_argument);
  EXPECT_THROW(endpoint_spread(one), std::invalid_argument);
  EXPECT_THROW(effective_throughput(30, same, times), std::invalid_argument);  // We = 0
  EXPECT_THROW(effective_throughput(30, times, std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(effective_throughput(-30, times, times), std::invalid_argument);
  EXPECT_THROW(fit_line(same, times), std::invalid_argument);  // one ID: no slope
  EXPECT_THROW(fit_line(times, same), std::invalid_argument);  // constant MT: no r²
  EXPECT_THROW(fit_line(one, one), std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::stats
