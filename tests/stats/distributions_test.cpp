// The distribution functions against scipy.stats / scipy.special, across the
// degrees of freedom the studies produce (real ones after a sphericity
// correction) and deep into the tails, where p-values live.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "knoblab/stats/distributions.hpp"
#include "reference.hpp"

namespace knoblab::stats {
namespace {

using test::expect_relative;
using test::scipy_reference;

// The codes scipy_reference.py's distributions check reads.
enum Code { kNormal = 0, kT = 1, kChi2 = 2, kF = 3, kBeta = 4, kGamma = 5 };

struct Case {
  Code code;
  double x, a, b;
};

// Among them the thesis' §4.4–4.6 results: F = 10.8 on (11, 88), F = 5.79 on
// (4.48, 62.7) after a sphericity correction, χ² = 49.49 on 6.
const Case kCases[] = {
    {kNormal, -8, 0, 0},      {kNormal, -1.5, 0, 0},   {kNormal, 0, 0, 0},
    {kNormal, 2, 0, 0},       {kNormal, 9, 0, 0},      {kT, 0.5, 1, 0},
    {kT, -2, 2, 0},           {kT, -1.3, 3.5, 0},      {kT, 3, 10, 0},
    {kT, 12, 5, 0},           {kT, 2.5, 100, 0},       {kT, 40, 30, 0},
    {kT, 1.96, 1e4, 0},       {kChi2, 0.01, 1, 0},     {kChi2, 3.84, 1, 0},
    {kChi2, 5, 3, 0},         {kChi2, 49.49, 6, 0},    {kChi2, 0.5, 0.7, 0},
    {kChi2, 100, 10, 0},      {kChi2, 1200, 1000, 0},  {kChi2, 900, 1000, 0},
    {kF, 1.41, 3, 27},        {kF, 10.8, 11, 88},      {kF, 5.79, 4.48, 62.7},
    {kF, 0.1, 2, 5},          {kF, 50, 1, 8},          {kF, 3, 2.2, 17.6},
    {kF, 1e3, 3, 30},         {kF, 0.98, 100, 500},    {kBeta, 0.3, 2, 3},
    {kBeta, 0.999, 0.5, 40},  {kBeta, 1e-4, 7, 0.5},   {kBeta, 0.6, 300, 200},
    {kGamma, 0.5, 0.5, 0},    {kGamma, 30, 10, 0},     {kGamma, 3, 40, 0},
    {kGamma, 520, 500, 0},
};

TEST(Distributions, TailsAndCdfsMatchScipy) {
  test::Table rows;
  for (const Case& c : kCases) rows.push_back({double(c.code), c.x, c.a, c.b});
  const test::Values ref = scipy_reference("distributions", rows);
  for (std::size_t i = 0; i < std::size(kCases); ++i) {
    const Case& c = kCases[i];
    const std::string sf = "sf." + std::to_string(i), cdf = "cdf." + std::to_string(i);
    SCOPED_TRACE("case " + std::to_string(i));
    switch (c.code) {
      case kNormal:
        expect_relative(normal_sf(c.x), ref, sf);
        expect_relative(normal_cdf(c.x), ref, cdf);
        break;
      case kT:
        expect_relative(t_sf(c.x, c.a), ref, sf);
        expect_relative(t_cdf(c.x, c.a), ref, cdf);
        expect_relative(t_two_sided_p(c.x, c.a), ref, "two_sided." + std::to_string(i));
        break;
      case kChi2:
        expect_relative(chi2_sf(c.x, c.a), ref, sf);
        expect_relative(chi2_cdf(c.x, c.a), ref, cdf);
        break;
      case kF:
        expect_relative(f_sf(c.x, c.a, c.b), ref, sf);
        expect_relative(f_cdf(c.x, c.a, c.b), ref, cdf);
        break;
      case kBeta:
        expect_relative(incomplete_beta(c.a, c.b, c.x), ref, cdf);
        break;
      case kGamma:
        expect_relative(gamma_p(c.a, c.x), ref, cdf);
        expect_relative(gamma_q(c.a, c.x), ref, sf);
        break;
    }
  }
}

TEST(Distributions, ClosedFormsHold) {
  // t with 1 df is Cauchy; χ² with 2 df is exponential; F(1, ν) is t²;
  // χ² with 1 df is a squared normal.
  for (const double t : {0.3, 1.0, 7.0}) {
    EXPECT_NEAR(t_sf(t, 1), 0.5 - std::atan(t) / std::numbers::pi, 1e-15);
    EXPECT_NEAR(f_sf(t * t, 1, 9), t_two_sided_p(t, 9), 1e-15);
    EXPECT_NEAR(chi2_sf(t * t, 1), 2 * normal_sf(t), 1e-15);
  }
  for (const double x : {0.1, 2.0, 60.0})
    EXPECT_NEAR(chi2_sf(x, 2) / std::exp(-x / 2), 1.0, 1e-13);
  EXPECT_EQ(t_sf(0, 4), 0.5);
  EXPECT_EQ(f_sf(0, 2, 3), 1.0);
  EXPECT_EQ(chi2_sf(std::numeric_limits<double>::infinity(), 3), 0.0);
  EXPECT_EQ(t_two_sided_p(-std::numeric_limits<double>::infinity(), 3), 0.0);
}

TEST(Distributions, InvalidArgumentsThrowInsteadOfReturningNan) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(t_sf(1, 0), std::invalid_argument);
  EXPECT_THROW(t_sf(nan, 3), std::invalid_argument);
  EXPECT_THROW(chi2_sf(1, -2), std::invalid_argument);
  EXPECT_THROW(f_sf(1, 2, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(f_cdf(1, nan, 3), std::invalid_argument);
  EXPECT_THROW(normal_cdf(nan), std::invalid_argument);
  EXPECT_THROW(incomplete_beta(1, 1, 1.5), std::invalid_argument);
  EXPECT_THROW(incomplete_beta(0, 1, 0.5), std::invalid_argument);
  EXPECT_THROW(gamma_p(1, -1), std::invalid_argument);
  EXPECT_THROW(gamma_q(0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::stats
