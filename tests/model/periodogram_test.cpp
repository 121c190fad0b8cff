// Angular periodogram: detent period and phase from torque vs. angle on a
// back-and-forth swept-sine capture.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "knoblab/model/models.hpp"
#include "knoblab/model/periodogram.hpp"
#include "knoblab/model/trajectory.hpp"

namespace knoblab::model {
namespace {

struct Capture {
  std::vector<double> theta, torque;
};

// Eq. 9: the Table 3 spatial sweep, 30 000 samples at 5 kHz.
template <typename TorqueOf>
Capture capture(TorqueOf torque_of, double noise, unsigned seed) {
  const SweptSine sweep = SweptSine::spatial();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Capture c;
  for (int n = 1; n <= 30000; ++n) {
    const Kinematics<double> k = sweep.at(n / 5000.0);
    c.theta.push_back(k.theta);
    c.torque.push_back(torque_of(k) + noise * uniform(rng));
  }
  return c;
}

// Detents plus friction (sgn ω, asymmetric), damping, a little inertia.
ThesisModel<double> knob(double cycles_per_rev, double amplitude, double phase) {
  ThesisModel<double> m;
  m.inertia.M = 0.005;
  m.friction = {0.4, 0.05, 0.6, 0.08};
  m.detents.A = amplitude;
  m.detents.P = 1.0 / cycles_per_rev;
  m.detents.S = phase;
  return m;
}

void expect_detents_found(double cycles, double amplitude, double phase) {
  const ThesisModel<double> m = knob(cycles, amplitude, phase);
  const Capture c = capture([&](const Kinematics<double>& k) { return m.torque(k); }, 0.3, 11);
  const AngularPeriodogram pg = angular_periodogram(c.theta, c.torque, 1.0, 50.0, 0.1);
  EXPECT_NEAR(pg.peak.frequency, cycles, 0.01 * cycles);
  // Not exact: over a chirp that ends mid-cycle, sgn(ω) and α are not
  // balanced at each θ and leak a few percent of amplitude into any f.
  EXPECT_NEAR(pg.peak.amplitude, amplitude, 0.1 * amplitude);
  EXPECT_NEAR(std::remainder(pg.peak.phase - phase, 2 * std::numbers::pi), 0.0, 0.1);
}

TEST(AngularPeriodogram, Finds12DetentsPerRevolution) { expect_detents_found(12.0, 0.8, 0.4); }

TEST(AngularPeriodogram, Finds30DetentsPerRevolution) { expect_detents_found(30.0, 0.5, -2.0); }

TEST(AngularPeriodogram, RecoversThesisEq10DetentsAfterRemovingOtherParts) {
  // Thesis Fig. 17 (bottom): τ_pos = τ − τ_acc − τ_vel, with Eq. 11 noise.
  const double p[kThesisParamCount] = {0.4, 1.5, 1.0, 2.0, 1.5, 1.0, 0.2, 0.9};
  const ThesisModel<double> m = ThesisModel<double>::from_params(p);
  const Capture c = capture(
      [&](const Kinematics<double>& k) {
        const TorqueParts<double> parts = m.parts(k);
        return parts.total() - parts.acc - parts.vel;
      },
      2.0, 3);
  const AngularPeriodogram pg = angular_periodogram(c.theta, c.torque, 0.5, 20.0, 0.05);
  EXPECT_NEAR(1.0 / pg.peak.frequency, 0.2, 0.002);
  EXPECT_NEAR(pg.peak.amplitude, 1.0, 0.05);
  EXPECT_NEAR(pg.peak.phase, 0.9, 0.05);
}

TEST(AngularPeriodogram, GridPowerMatchesDirectFit) {
  // The rotation recurrence must agree with evaluating sin/cos directly.
  const ThesisModel<double> m = knob(12.0, 0.8, 0.4);
  const Capture c = capture([&](const Kinematics<double>& k) { return m.torque(k); }, 0.3, 5);
  const AngularPeriodogram pg = angular_periodogram(c.theta, c.torque, 0.0, 40.0, 0.3);
  for (std::size_t i = 0; i < pg.frequency.size(); i += 7) {
    const SinusoidFit fit = fit_sinusoid(c.theta, c.torque, pg.frequency[i]);
    EXPECT_NEAR(pg.power[i], fit.power, 1e-9) << pg.frequency[i];
  }
  EXPECT_EQ(pg.power.front(), 0.0);  // f = 0 explains nothing beyond the mean
  EXPECT_NEAR(pg.frequency.back(), 39.9, 1e-9);
}

TEST(AngularPeriodogram, ExactSinusoidIsFullyExplained) {
  std::vector<double> theta, y;
  for (int i = 0; i < 500; ++i) {
    theta.push_back(std::sin(0.013 * i) * 2.0);  // back and forth
    y.push_back(0.7 * std::sin(8.0 * theta.back() - 1.1) + 0.25);
  }
  const SinusoidFit fit = fit_sinusoid(theta, y, 8.0);
  EXPECT_NEAR(fit.power, 1.0, 1e-12);
  EXPECT_NEAR(fit.amplitude, 0.7, 1e-12);
  EXPECT_NEAR(fit.phase, -1.1, 1e-12);
  EXPECT_NEAR(fit.offset, 0.25, 1e-12);
}

TEST(AngularPeriodogram, ThirtyThousandSamplesFiveHundredFrequenciesIsFast) {
  const ThesisModel<double> m = knob(30.0, 0.5, 0.0);
  const Capture c = capture([&](const Kinematics<double>& k) { return m.torque(k); }, 0.3, 9);
  const auto start = std::chrono::steady_clock::now();
  const AngularPeriodogram pg = angular_periodogram(c.theta, c.torque, 0.1, 50.0, 0.1);
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(pg.frequency.size(), 500u);
  EXPECT_LT(took.count(), 0.5);
}

TEST(AngularPeriodogram, ConstantSignalHasNoPower) {
  const std::vector<double> theta{0.0, 0.1, 0.3, 0.2, 0.5}, y(5, 2.0);
  const AngularPeriodogram pg = angular_periodogram(theta, y, 1.0, 5.0, 1.0);
  for (double p : pg.power) EXPECT_EQ(p, 0.0);
  EXPECT_EQ(pg.peak.amplitude, 0.0);
  EXPECT_EQ(pg.peak.offset, 2.0);
}

TEST(AngularPeriodogram, RejectsBadArguments) {
  const std::vector<double> a{0.0, 1.0, 2.0}, b{0.0, 1.0};
  EXPECT_THROW(angular_periodogram(a, b, 1.0, 2.0, 0.1), std::invalid_argument);
  EXPECT_THROW(angular_periodogram(b, b, 1.0, 2.0, 0.1), std::invalid_argument);
  EXPECT_THROW(angular_periodogram(a, a, 1.0, 2.0, 0.0), std::invalid_argument);
  EXPECT_THROW(angular_periodogram(a, a, 3.0, 2.0, 0.1), std::invalid_argument);
  EXPECT_THROW(angular_periodogram(a, a, -1.0, 2.0, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::model
