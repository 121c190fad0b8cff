// Swept sine of thesis Eq. 8: derivatives, frequency, presets.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "knoblab/model/trajectory.hpp"

namespace knoblab::model {
namespace {

constexpr double kPi = std::numbers::pi;

// Largest |θ̇|, |θ̈| seen over [0, t_end], for scale-relative tolerances.
double max_abs(double t_end, auto f) {
  double m = 0.0;
  for (double t = 0.0; t <= t_end; t += 1e-3) m = std::max(m, std::abs(f(t)));
  return m;
}

// Five-point central difference, error ~ h⁴·f⁽⁵⁾/30.
double numeric_derivative(auto f, double t) {
  const double h = 1e-4;
  return (8.0 * (f(t + h) - f(t - h)) - (f(t + 2 * h) - f(t - 2 * h))) / (12.0 * h);
}

void expect_exact_derivatives(const SweptSine& s, double t_end) {
  const double w_scale = max_abs(t_end, [&](double t) { return s.omega(t); });
  const double a_scale = max_abs(t_end, [&](double t) { return s.alpha(t); });
  for (double t = 0.0; t < t_end; t += 0.0137) {
    const double dtheta = numeric_derivative([&](double x) { return s.theta(x); }, t);
    const double domega = numeric_derivative([&](double x) { return s.omega(x); }, t);
    EXPECT_NEAR(s.omega(t), dtheta, 1e-8 * w_scale) << "t = " << t;
    EXPECT_NEAR(s.alpha(t), domega, 1e-8 * a_scale) << "t = " << t;
  }
}

TEST(SweptSine, DerivativesOfSpatialPresetAreExact) {
  // Eq. 9 runs the Table 3 sweep for 6 s (30 000 samples at 5 kHz).
  expect_exact_derivatives(SweptSine::spatial(), 6.0);
}

TEST(SweptSine, DerivativesOfFastNonZeroStartSweepAreExact) {
  expect_exact_derivatives(SweptSine{2.0, 40.0, 0.3, 2.0}, 2.0);
  expect_exact_derivatives(SweptSine{5.0, 1.0, 0.1, 1.5}, 1.5);  // downward sweep
}

TEST(SweptSine, PrintedThesisSecondDerivativeIsNotTheDerivative) {
  // Eq. 8 as printed: first term −4π²c/d²·u·sin φ (u not squared).
  const SweptSine s = SweptSine::spatial();
  const double t = 5.0;
  const double u = (s.b - s.a) * t / s.d + s.a;
  const double phi = s.chirp().phase(t);
  const double printed = -4 * kPi * kPi * s.c / (s.d * s.d) * u * std::sin(phi) +
                         2 * kPi * s.c * (s.b - s.a) / (s.d * s.d) * std::cos(phi);
  const double numeric = numeric_derivative([&](double x) { return s.omega(x); }, t);
  EXPECT_NEAR(s.alpha(t), numeric, 1e-8);
  EXPECT_GT(std::abs(printed - numeric), 1.0);
}

TEST(SweptSine, FrequencyRunsFromAOverDToBOverD) {
  const SweptSine s{0.6, 4.5, 1.0, 3.0};
  EXPECT_DOUBLE_EQ(s.frequency_hz(0.0), 0.2);
  EXPECT_DOUBLE_EQ(s.frequency_hz(3.0), 1.5);
  // It is the phase rate over 2π.
  const double h = 1e-6, t = 1.3;
  const double numeric = (s.chirp().phase(t + h) - s.chirp().phase(t - h)) / (2 * h) / (2 * kPi);
  EXPECT_NEAR(s.frequency_hz(t), numeric, 1e-8);
}

TEST(SweptSine, FromHzHitsTheRequestedEndFrequencies) {
  const SweptSine s = SweptSine::from_hz(0.5, 12.0, 0.2, 4.0);
  EXPECT_DOUBLE_EQ(s.frequency_hz(0.0), 0.5);
  EXPECT_DOUBLE_EQ(s.frequency_hz(4.0), 12.0);
  EXPECT_DOUBLE_EQ(s.c, 0.2);
}

TEST(SweptSine, EqualEndsGiveAPureSine) {
  const SweptSine s{2.0, 2.0, 0.5, 4.0};  // 2/4 = 0.5 Hz
  for (double t = 0.0; t < 5.0; t += 0.31) {
    const double w = 2 * kPi * 0.5;
    EXPECT_NEAR(s.theta(t), 0.5 * std::sin(w * t), 1e-12);
    EXPECT_NEAR(s.omega(t), 0.5 * w * std::cos(w * t), 1e-12);
    EXPECT_NEAR(s.alpha(t), -0.5 * w * w * std::sin(w * t), 1e-12);
    EXPECT_DOUBLE_EQ(s.frequency_hz(t), 0.5);
  }
}

TEST(SweptSine, AtBundlesTheThreeSignals) {
  const SweptSine s = SweptSine::spatial();
  for (double t = 0.0; t < 6.0; t += 0.77) {
    const Kinematics<double> k = s.at(t);
    EXPECT_DOUBLE_EQ(k.theta, s.theta(t));
    EXPECT_DOUBLE_EQ(k.omega, s.omega(t));
    EXPECT_DOUBLE_EQ(k.alpha, s.alpha(t));
  }
}

TEST(SweptSine, Table3Presets) {
  constexpr SweptSine sp = SweptSine::spatial();
  constexpr SweptSine tq = SweptSine::torque_test();
  EXPECT_EQ(sp.a, 0.0);
  EXPECT_EQ(sp.b, 1.5);
  EXPECT_EQ(sp.c, 1.0);
  EXPECT_EQ(sp.d, 3.0);
  EXPECT_EQ(tq.a, 0.0);
  EXPECT_EQ(tq.b, 1.5);
  EXPECT_EQ(tq.c, 0.02);
  EXPECT_EQ(tq.d, 3.0);
  EXPECT_EQ(sp.theta(0.0), 0.0);
  EXPECT_EQ(sp.omega(0.0), 0.0);  // a = 0 starts at rest
}

// Eq. 8 has no end: Table 3's sweep runs at t/6 Hz for as long as it runs.
TEST(SweptSine, Table3SweepKeepsSpeedingUpPastDAndPassesFiftyRadPerSecondBeforeAMinute) {
  const SweptSine s = SweptSine::spatial();
  EXPECT_DOUBLE_EQ(s.frequency_hz(6.0), 1.0);
  EXPECT_NEAR(s.frequency_hz(46.5), 7.75, 1e-12);
  EXPECT_NEAR(s.frequency_hz(60.0), 10.0, 1e-12);
  EXPECT_NEAR(s.peak_speed(60.0), 2 * kPi * 10.0, 1e-9);  // rad/s at c = 1 rad
  // 50 rad/s = c·2π·t/6 at t = 150/π s = 47.7 s.
  EXPECT_NEAR(s.time_at_peak_speed(50.0), 150.0 / kPi, 1e-9);
  EXPECT_NEAR(s.peak_speed(s.time_at_peak_speed(50.0)), 50.0, 1e-9);
  // The envelope bounds θ̇ over the cycle around any t.
  for (double t = 40.0; t < 60.0; t += 1e-3) ASSERT_LE(std::abs(s.omega(t)), s.peak_speed(t) + 1e-9);
}

TEST(SweptSine, TimeAtPeakSpeedForFasterStartsDownwardSweepsAndPureSines) {
  const SweptSine up{2.0, 40.0, 0.3, 2.0};  // 1 Hz → 20 Hz over 2 s
  EXPECT_EQ(up.time_at_peak_speed(0.1), 0.0);  // already faster at the start
  const double t = up.time_at_peak_speed(20.0);
  EXPECT_NEAR(up.peak_speed(t), 20.0, 1e-9);
  EXPECT_GT(t, 0.0);
  // Downward: u falls through 0 and its magnitude grows again, negative.
  const SweptSine down{1.0, -5.0, 0.5, 1.0};
  const double td = down.time_at_peak_speed(10.0);
  EXPECT_NEAR(down.peak_speed(td), 10.0, 1e-9);
  EXPECT_LT(down.frequency_hz(td), 0.0);
  const SweptSine pure{2.0, 2.0, 0.5, 4.0};
  EXPECT_EQ(pure.time_at_peak_speed(100.0), std::numeric_limits<double>::infinity());
}

TEST(TorqueSweep, HasTheSameChirpShape) {
  const TorqueSweep tq{0.0, 1.5, 0.15, 3.0};
  const SweptSine same{0.0, 1.5, 0.15, 3.0};
  for (double t = 0.0; t < 6.0; t += 0.113) EXPECT_DOUBLE_EQ(tq.torque(t), same.theta(t));
  const TorqueSweep hz = TorqueSweep::from_hz(1.0, 10.0, 0.05, 2.0);
  EXPECT_DOUBLE_EQ(hz.frequency_hz(0.0), 1.0);
  EXPECT_DOUBLE_EQ(hz.frequency_hz(2.0), 10.0);
}

}  // namespace
}  // namespace knoblab::model
