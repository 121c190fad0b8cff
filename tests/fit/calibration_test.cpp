// The calibration fits hapticd runs (Table 4, Eq. 12, Eq. 2) and the linear
// least squares under them, on synthetic data: the values, the errors for
// too little data, and the 95% confidence intervals' coverage.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "knoblab/fit/calibration.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/linear_lsq.hpp"

namespace knoblab::fit {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kSeeds = 200;

// The realtime loop carries these inside its controller: no allocation, and
// copied as plain bytes.
static_assert(std::is_trivially_copyable_v<RunningStats>);
static_assert(std::is_trivially_copyable_v<LinearLsq<1>>);
static_assert(std::is_trivially_copyable_v<LinearLsq<4>>);
static_assert(std::is_trivially_copyable_v<AccelGainAccumulator>);
static_assert(std::is_trivially_copyable_v<GravityAccumulator>);

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }

// ---- the fits' values ----

TEST(CalibrationFit, ErrorStatsOfAKnownOffsetAndNoise) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.0018);
  std::vector<double> cmd, meas;
  for (int i = 0; i < 25000; ++i) {
    const double c = 0.1 * std::sin(1e-3 * i);
    cmd.push_back(c);
    meas.push_back(c - 0.0010 + noise(rng));  // commanded − measured = 1 mN·m ± 1.8
  }
  const ErrorStats s = error_stats(cmd, meas);
  EXPECT_EQ(s.n, 25000);
  EXPECT_NEAR(s.mean, 0.0010, 3e-5);
  EXPECT_NEAR(s.sd, 0.0018, 4e-5);
  EXPECT_NEAR(s.mean_ci95, 1.95996 * s.sd / std::sqrt(25000.0), 1e-3 * s.mean_ci95);
}

TEST(CalibrationFit, TooLittleDataIsAClearError) {
  const std::vector<double> one{1.0};
  EXPECT_THROW(error_stats(one, one), FitDataError);
  const std::vector<double> two{1.0, 2.0};
  EXPECT_THROW(fit_accel_gain(two, two), FitDataError);
  EXPECT_THROW(fit_gravity(two, two, two, two), FitDataError);
  EXPECT_THROW(error_stats(one, two), FitDataError);
  GravityAccumulator only_cw;
  for (int i = 0; i < 100; ++i) only_cw.add(0.06 * i, std::sin(0.06 * i), false);
  try {
    (void)only_cw.fit();
    FAIL() << "a one-direction gravity fit must not succeed";
  } catch (const FitDataError& e) {
    EXPECT_NE(std::string(e.what()).find("each direction"), std::string::npos) << e.what();
  }
  // Constant angle: sin, cos and 1 are collinear — singular, not garbage.
  const std::vector<double> th(50, 0.3), y(50, 1.0);
  EXPECT_THROW(fit_gravity(th, y, th, y), FitDataError);
  // All-zero volts: no gain to invert.
  const std::vector<double> zeros(50, 0.0), alpha(50, 3.0);
  EXPECT_THROW(fit_accel_gain(zeros, alpha), FitDataError);
}

TEST(CalibrationFit, LinearLsqIsExactOnNoiseFreeData) {
  LinearLsq<3> lsq;
  EXPECT_THROW((void)lsq.solve(), FitDataError);
  for (int i = 0; i < 4; ++i) lsq.add({1.0, 0.1 * i, std::sin(i)}, 2.0 - 3.0 * 0.1 * i + 0.5 * std::sin(i));
  EXPECT_THROW((void)lsq.solve(), FitDataError);  // n = N + 1: no residual dof to spare
  lsq.add({1.0, 0.4, std::sin(4.0)}, 2.0 - 3.0 * 0.4 + 0.5 * std::sin(4.0));
  const auto s = lsq.solve();
  EXPECT_EQ(s.n, 5);
  EXPECT_EQ(s.dof, 2);
  EXPECT_NEAR(s.beta[0], 2.0, 1e-9);
  EXPECT_NEAR(s.beta[1], -3.0, 1e-9);
  EXPECT_NEAR(s.beta[2], 0.5, 1e-9);
  EXPECT_NEAR(s.residual_sd, 0.0, 1e-6);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) EXPECT_DOUBLE_EQ(s.cov[i][j], s.cov[j][i]);
}

TEST(CalibrationFit, RecoversAccelGainWithNoise) {
  // Eq. 12: α_true = C_cal·V; V carries the motion, α_true (commanded) is
  // what we regress on. Noise as the simulated ADXL202 (σ 8.7 rad/s²).
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 8.7);
  const double C = 1148.0;
  std::vector<double> v, a, th;
  for (int i = 0; i < 50000; ++i) {
    const double t = i * 1e-4;
    const double alpha = 40.0 * std::sin(2 * kPi * 2.0 * t) * (1.0 + t);
    const double theta = 0.8 * std::sin(2 * kPi * 0.7 * t);
    const double grav = 300.0 * std::sin(theta + 0.4) + 5.0;  // not compensated
    v.push_back((alpha + grav + noise(rng)) / C);
    a.push_back(alpha);
    th.push_back(theta);
  }
  const AccelGainFit f = fit_accel_gain(v, a, th);
  EXPECT_TRUE(f.with_gravity);
  EXPECT_EQ(f.n, 50000);
  EXPECT_EQ(f.dof, 50000 - 4);
  EXPECT_NEAR(f.C_cal, C, 3.0 * f.C_cal_se + 1e-9);
  EXPECT_LT(f.C_cal_se, 0.01 * C);
  EXPECT_NEAR(f.C_cal_ci95, 1.96 * f.C_cal_se, 1e-3 * f.C_cal_se);
  EXPECT_NEAR(f.residual_sd, 8.7, 0.3);
  EXPECT_NEAR(f.grav_A, 300.0, 3.0);
  EXPECT_NEAR(f.grav_C, 0.4, 0.02);
  EXPECT_NEAR(f.grav_D, 5.0, 1.0);

  // Without gravity in the signal, the plain Eq. 12 (no intercept) fit.
  std::vector<double> v2;
  for (std::size_t i = 0; i < a.size(); ++i) v2.push_back((a[i] + noise(rng)) / C);
  const AccelGainFit p = fit_accel_gain(v2, a);
  EXPECT_FALSE(p.with_gravity);
  EXPECT_EQ(p.dof, 50000 - 1);
  EXPECT_NEAR(p.C_cal, C, 0.01 * C);
  EXPECT_GT(p.C_cal_se, 0.0);
}

TEST(CalibrationFit, RecoversGravityAndAveragingCancelsLag) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 8.7);
  const double A = 327.0, C = -1.1, D = 12.0, lag = 0.05;  // rad of phase lag
  std::vector<double> th1, y1, th2, y2;
  for (int i = 0; i < 40000; ++i) {
    const double th = 0.3 + 2 * kPi * i / 40000.0;
    th1.push_back(th);  // θ increasing: the sensor reports the angle lag earlier
    y1.push_back(A * std::sin(th - lag + C) + D + noise(rng));
    const double thb = 0.3 + 2 * kPi - 2 * kPi * i / 40000.0;
    th2.push_back(thb);
    y2.push_back(A * std::sin(thb + lag + C) + D + noise(rng));
  }
  const GravityFit g = fit_gravity(th1, y1, th2, y2);
  EXPECT_NEAR(g.cw.C, C - lag, 0.005);   // each direction alone is biased …
  EXPECT_NEAR(g.ccw.C, C + lag, 0.005);
  EXPECT_NEAR(g.C, C, 0.005);            // … the average is not
  // The lag moves neither amplitude: A is their mean, not the averaged
  // coefficients' A·cos(lag) (0.41 lower).
  EXPECT_NEAR(g.A, A, 0.2);
  EXPECT_NEAR(g.D, D, 0.3);
  EXPECT_DOUBLE_EQ(g.B, 1.0);
  // Per direction: the regression's standard errors, σ·√(2/n) for the
  // sin/cos amplitude, that over A for the phase, σ/√n for the offset.
  const double se_amp = 8.7 * std::sqrt(2.0 / 40000.0);
  for (const GravityDirectionFit* d : {&g.cw, &g.ccw}) {
    EXPECT_EQ(d->n, 40000);
    EXPECT_EQ(d->dof, 40000 - 3);
    EXPECT_NEAR(d->A_se, se_amp, 0.05 * se_amp);
    EXPECT_NEAR(d->C_se, se_amp / A, 0.05 * se_amp / A);
    EXPECT_NEAR(d->D_se, 8.7 / std::sqrt(40000.0), 0.05 * 8.7 / std::sqrt(40000.0));
  }
  // Combined: A and D from the two directions' spread (1 dof), C from the
  // regressions (≈ 2n − 6 dof).
  EXPECT_DOUBLE_EQ(g.A_se, 0.5 * std::abs(g.cw.A - g.ccw.A));
  EXPECT_NEAR(g.A_ci95, 12.7062 * g.A_se, 1e-4 * g.A_se + 1e-12);
  EXPECT_NEAR(g.D_ci95, 12.7062 * g.D_se, 1e-4 * g.D_se + 1e-12);
  EXPECT_NEAR(g.C_se, se_amp / A / std::sqrt(2.0), 0.05 * se_amp / A);
  EXPECT_GT(g.C_dof, 0.99 * (2 * 40000 - 6));
  EXPECT_LE(g.C_dof, 2 * 40000 - 6);
  EXPECT_NEAR(g.C_ci95, 1.96 * g.C_se, 1e-3 * g.C_se);
  // A negative-amplitude convention never comes out: A ≥ 0, C wrapped.
  const GravityDirectionFit n = gravity_from_coefficients(-3.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(n.A, 3.0);
  EXPECT_NEAR(std::abs(n.C), kPi, 1e-12);
}

// ---- the 95% intervals cover the truth about 95% of the time ----
//
// 200 seeds: the count of covering intervals is Binomial(200, 0.95), SD 1.5 %,
// so 90–99 % holds unless something is wrong. Small samples make the point of
// Student's t: with few dof, z = 1.96 would cover far less often (3 dof:
// 86 %), which this range rejects.

double fraction(int hits) { return static_cast<double>(hits) / kSeeds; }

TEST(CalibrationFit, SlopeIntervalCoversTheTruth) {
  const double k = 2.5;
  int hits = 0, hits_z = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    std::mt19937_64 rng(1000 + seed);
    std::normal_distribution<double> noise(0.0, 0.3);
    LinearLsq<1> lsq;
    for (int i = 1; i <= 4; ++i) lsq.add({0.5 * i}, k * 0.5 * i + noise(rng));  // 3 dof
    const auto s = lsq.solve();
    ASSERT_EQ(s.dof, 3);
    EXPECT_NEAR(s.ci95[0], 3.18245 * s.se[0], 1e-4 * s.se[0]);
    if (std::abs(s.beta[0] - k) <= s.ci95[0]) ++hits;
    if (std::abs(s.beta[0] - k) <= 1.959964 * s.se[0]) ++hits_z;
  }
  std::printf("slope: t interval covers %.1f %%, z interval %.1f %%\n", 100 * fraction(hits), 100 * fraction(hits_z));
  EXPECT_GE(fraction(hits), 0.90);
  EXPECT_LE(fraction(hits), 0.99);
  EXPECT_LT(hits_z, hits);
}

TEST(CalibrationFit, InterceptAndSlopeIntervalsCoverTheTruth) {
  int hits_a = 0, hits_b = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    std::mt19937_64 rng(2000 + seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    LinearLsq<2> lsq;
    for (int i = 0; i < 7; ++i) lsq.add({1.0, static_cast<double>(i)}, 4.0 - 0.7 * i + noise(rng));  // 5 dof
    const auto s = lsq.solve();
    if (std::abs(s.beta[0] - 4.0) <= s.ci95[0]) ++hits_a;
    if (std::abs(s.beta[1] + 0.7) <= s.ci95[1]) ++hits_b;
  }
  EXPECT_GE(fraction(hits_a), 0.90);
  EXPECT_LE(fraction(hits_a), 0.99);
  EXPECT_GE(fraction(hits_b), 0.90);
  EXPECT_LE(fraction(hits_b), 0.99);
}

TEST(CalibrationFit, Table4MeanIntervalCoversTheTruth) {
  int hits = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    std::mt19937_64 rng(3000 + seed);
    std::normal_distribution<double> err(0.0010, 0.0018);
    RunningStats r;
    for (int i = 0; i < 4; ++i) r.add(err(rng));  // 3 dof
    const ErrorStats s = r.stats();
    EXPECT_NEAR(s.mean_ci95, 3.18245 * s.sd / 2.0, 1e-4 * s.sd);
    if (std::abs(s.mean - 0.0010) <= s.mean_ci95) ++hits;
  }
  EXPECT_GE(fraction(hits), 0.90);
  EXPECT_LE(fraction(hits), 0.99);
}

TEST(CalibrationFit, AccelGainIntervalCoversTheTruth) {
  // V = α/C_cal + noise: the plain fit on 6 samples (5 dof), and with the
  // gravity terms on 40 (36 dof).
  const double C = 1148.0;
  int hits_plain = 0, hits_grav = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    std::mt19937_64 rng(4000 + seed);
    std::normal_distribution<double> noise(0.0, 8.7);
    AccelGainAccumulator plain(false), grav(true);
    for (int i = 0; i < 6; ++i) {
      const double alpha = 50.0 * (i - 2.5);
      plain.add((alpha + noise(rng)) / C, alpha, 0.0);
    }
    for (int i = 0; i < 40; ++i) {
      const double alpha = 60.0 * std::sin(0.9 * i);
      const double theta = 2 * kPi * i / 40.0;
      grav.add((alpha + 300.0 * std::sin(theta + 0.4) + 5.0 + noise(rng)) / C, alpha, theta);
    }
    const AccelGainFit p = plain.fit();
    ASSERT_EQ(p.dof, 5);
    if (std::abs(p.C_cal - C) <= p.C_cal_ci95) ++hits_plain;
    const AccelGainFit g = grav.fit();
    ASSERT_EQ(g.dof, 36);
    if (std::abs(g.C_cal - C) <= g.C_cal_ci95) ++hits_grav;
  }
  EXPECT_GE(fraction(hits_plain), 0.90);
  EXPECT_LE(fraction(hits_plain), 0.99);
  EXPECT_GE(fraction(hits_grav), 0.90);
  EXPECT_LE(fraction(hits_grav), 0.99);
}

TEST(CalibrationFit, GravityIntervalsCoverTheTruth) {
  // A lag the two directions cancel, and noise; 300 samples a direction.
  const double A = 327.0, C = -1.1, D = 12.0, lag = 0.05;
  int hits_A = 0, hits_C = 0, hits_D = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    std::mt19937_64 rng(5000 + seed);
    std::normal_distribution<double> noise(0.0, 8.7);
    GravityAccumulator acc;
    for (int i = 0; i < 300; ++i) {
      const double th = 0.3 + 2 * kPi * i / 300.0;
      acc.add(th, A * std::sin(th - lag + C) + D + noise(rng), false);
      const double thb = 0.3 + 2 * kPi - 2 * kPi * i / 300.0;
      acc.add(thb, A * std::sin(thb + lag + C) + D + noise(rng), true);
    }
    const GravityFit g = acc.fit();
    if (std::abs(g.A - A) <= g.A_ci95) ++hits_A;
    if (std::abs(wrap(g.C - C)) <= g.C_ci95) ++hits_C;
    if (std::abs(g.D - D) <= g.D_ci95) ++hits_D;
  }
  std::printf("gravity: A covered %.1f %%, C %.1f %%, D %.1f %%\n", 100 * fraction(hits_A), 100 * fraction(hits_C),
              100 * fraction(hits_D));
  for (int hits : {hits_A, hits_C, hits_D}) {
    EXPECT_GE(fraction(hits), 0.90);
    EXPECT_LE(fraction(hits), 0.99);
  }
}

}  // namespace
}  // namespace knoblab::fit
