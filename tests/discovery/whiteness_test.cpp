// Residual tests (whiteness.hpp): the χ² tail against scipy, Ljung–Box on
// white and AR(1) noise, independence from the input, fit %, and which trace
// rows the figures use.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "knoblab/discovery/whiteness.hpp"

namespace knoblab::discovery {
namespace {

// ./run shell python3 -c "from scipy.stats import chi2; print(repr(chi2.sf(X, K)))"
// and scipy.special.gammaincc(A, X) for the Q(a, x) rows.
TEST(Whiteness, ChiSquareTailMatchesScipy) {
  struct Point {
    double x, dof, sf;
  };
  for (const Point& p : {Point{3.841458820694124, 1, 0.04999999999999989},
                         Point{37.56623478662507, 20, 0.009999999999999967},
                         Point{10.0, 25, 0.996652640733739},
                         Point{25.0, 25, 0.46237366292661375},
                         Point{40.0, 25, 0.02916439562315211},
                         Point{100.0, 25, 6.274266201376244e-11},
                         Point{30.0, 51, 0.9916543942853495},
                         Point{300.0, 51, 5.719317047478375e-37},
                         Point{1000.0, 25, 5.8180164715881416e-195},
                         Point{0.001, 2, 0.9995001249791693},
                         Point{3.0, 7, 0.8850022316431506}}) {
    EXPECT_NEAR(chi2_sf(p.x, p.dof), p.sf, 1e-10 * p.sf) << "x " << p.x << ", dof " << p.dof;
  }
  EXPECT_NEAR(gamma_q(0.5, 0.1), 0.6547208460185768, 1e-12);
  EXPECT_NEAR(gamma_q(2.5, 1.0), 0.8491450360846096, 1e-12);
  EXPECT_NEAR(gamma_q(12.5, 30.0), 0.00010455486131526446, 1e-15);
  EXPECT_NEAR(gamma_q(1.0, 5.0), std::exp(-5.0), 1e-15);
  EXPECT_EQ(gamma_q(3.0, 0.0), 1.0);
  EXPECT_TRUE(std::isnan(gamma_q(-1.0, 1.0)));
}

std::vector<double> white(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> v(n);
  for (double& x : v) x = g(rng);
  return v;
}

std::vector<double> ar1(std::size_t n, double phi, unsigned seed) {
  std::vector<double> v = white(n, seed);
  for (std::size_t i = 1; i < n; ++i) v[i] += phi * v[i - 1];
  return v;
}

// A smooth input like a knob's velocity: a sine sweep, 7 cycles over n rows.
std::vector<double> sweep(std::size_t n) {
  std::vector<double> u(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) / static_cast<double>(n);
    u[i] = 2.0 * std::cos(2 * std::numbers::pi * (3.0 * s + 4.0 * s * s));
  }
  return u;
}

TEST(Whiteness, WhiteNoiseIsRarelyRejected) {
  int rejected = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Correlation c = whiteness({white(3000, seed), {}, {}});
    ASSERT_EQ(c.lags.size(), kDefaultMaxLag);
    EXPECT_NEAR(c.band, kBand99 / std::sqrt(3000.0), 1e-12);
    rejected += c.p < 0.01 ? 1 : 0;
  }
  EXPECT_LE(rejected, 2);
}

TEST(Whiteness, Ar1ResidualIsRejected) {
  const Correlation c = whiteness({ar1(3000, 0.5, 7), {}, {}});
  EXPECT_LT(c.p, 1e-6);
  EXPECT_NEAR(c.r[0], 0.5, 0.06);
  EXPECT_GT(c.r[0], c.band);
}

TEST(Whiteness, LagPairsNeverSpanARun) {
  // AR(1) noise, but every row its own run: no pair, no correlation.
  Series s{ar1(500, 0.9, 3), {}, {}};
  for (std::size_t i = 1; i < 500; ++i) s.run_starts.push_back(i);
  const Correlation c = whiteness(s);
  for (const double r : c.r) EXPECT_EQ(r, 0.0);
  EXPECT_NEAR(c.p, 1.0, 1e-12);
}

TEST(Whiteness, TooFewRowsGiveNoP) {
  EXPECT_TRUE(std::isnan(whiteness({white(20, 1), {}, {}}).p));
  EXPECT_TRUE(std::isnan(independence({white(20, 1), white(20, 2), {}}).p));
}

TEST(Independence, ResidualProportionalToTheInputIsRejected) {
  const std::size_t n = 3000;
  for (const bool smooth : {false, true}) {
    const std::vector<double> u = smooth ? sweep(n) : white(n, 11);
    std::vector<double> e = white(n, 12);
    EXPECT_GT(independence({e, u, {}}).p, 0.01) << "smooth " << smooth;
    for (std::size_t i = 0; i < n; ++i) e[i] += 0.5 * u[i];
    const Correlation c = independence({e, u, {}});
    EXPECT_LT(c.p, 1e-6) << "smooth " << smooth;
    ASSERT_EQ(c.lags.size(), 2 * kDefaultMaxLag + 1);
    EXPECT_GT(c.r[kDefaultMaxLag], c.band);  // lag 0
  }
}

TEST(Independence, NoiseIndependentOfTheInputIsRarelyRejected) {
  // White and coloured (AR(1)) residuals beside a smooth input: the band
  // allows for both being autocorrelated.
  int rejected_white = 0, rejected_ar = 0;
  const std::vector<double> u = sweep(3000);
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Correlation w = independence({white(3000, seed), u, {}});
    EXPECT_NEAR(w.band, kBand99 / std::sqrt(3000.0), 0.3 * kBand99 / std::sqrt(3000.0));
    rejected_white += w.p < 0.01 ? 1 : 0;
    rejected_ar += independence({ar1(3000, 0.8, seed), u, {}}).p < 0.01 ? 1 : 0;
  }
  EXPECT_LE(rejected_white, 2);
  EXPECT_LE(rejected_ar, 2);
}

TEST(FitPercent, AsMatlabsCompare) {
  const std::vector<double> y = {1.0, 2.0, 3.0, 4.0};
  EXPECT_NEAR(fit_percent(y, {0.0, 0.0, 0.0, 0.0}), 100.0, 1e-12);
  EXPECT_NEAR(fit_percent(y, {-1.5, -0.5, 0.5, 1.5}), 0.0, 1e-12);  // ŷ = mean
  EXPECT_NEAR(fit_percent(y, {0.5, -0.5, 0.5, -0.5}), 100.0 * (1.0 - 1.0 / std::sqrt(5.0)), 1e-12);
}

// Training rows t = 0 … 0.499, held-out rows in two blocks every 2 ms.
ResidualTrace trace_with_blocks(std::size_t held_per_block) {
  ResidualTrace tr;
  auto add = [&](double t, bool held) {
    tr.t.push_back(t);
    for (auto* v : {&tr.theta, &tr.omega, &tr.torque, &tr.before, &tr.after}) v->push_back(t);
    tr.heldout.push_back(held ? 1 : 0);
  };
  for (std::size_t i = 0; i < 250; ++i) add(0.002 * static_cast<double>(i), false);
  for (const double start : {1.0, 2.0})
    for (std::size_t i = 0; i < held_per_block; ++i) add(start + 0.002 * static_cast<double>(i), true);
  return tr;
}

TEST(FigureRows, HeldOutRowsCutAtGapsWithTheirSpacing) {
  const TraceRows rows = figure_rows(trace_with_blocks(150));
  EXPECT_TRUE(rows.heldout);
  ASSERT_EQ(rows.rows.size(), 300u);
  EXPECT_EQ(rows.rows.front(), 250u);
  EXPECT_NEAR(rows.row_spacing_s, 0.002, 1e-12);
  EXPECT_EQ(rows.run_starts, std::vector<std::size_t>{150});
}

TEST(FigureRows, AllRowsWhenTooFewAreHeldOut) {
  const TraceRows rows = figure_rows(trace_with_blocks(50));
  EXPECT_FALSE(rows.heldout);
  EXPECT_EQ(rows.rows.size(), 350u);
  // Breaks: training → held-out, and the held-out blocks' gap.
  EXPECT_EQ(rows.run_starts, (std::vector<std::size_t>{250, 300}));
}

}  // namespace
}  // namespace knoblab::discovery
