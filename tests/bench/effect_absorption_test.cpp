// The sweep's effect size: what of an effect's torque the clean knob's Eq. 6
// cannot take up (bench/discrepancy/absorption.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "absorption.hpp"

namespace {

using namespace knoblab;

constexpr double kPi = std::numbers::pi;

// A swept-sine-like motion at 5 kHz: a chirp in angle, with its exact ω and α.
fit::FitData swept_motion() {
  fit::FitData d;
  d.rate_hz = 5000.0;
  for (int i = 0; i < 40000; ++i) {
    const double t = i / d.rate_hz;
    const double f = 0.5 + 0.25 * t;  // Hz
    const double phase = 2.0 * kPi * (0.5 * t + 0.125 * t * t);
    d.t.push_back(t);
    d.theta.push_back(std::sin(phase));
    d.omega.push_back(2.0 * kPi * f * std::cos(phase));
    d.alpha.push_back(2.0 * kPi * 0.25 * std::cos(phase) - std::pow(2.0 * kPi * f, 2) * std::sin(phase));
    d.torque.push_back(0.0);
  }
  return d;
}

std::vector<std::size_t> moving_rows(const fit::FitData& d) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (std::abs(d.omega[i]) > 0.1) rows.push_back(i);
  return rows;
}

std::array<double, model::kThesisParamCount> detent_knob() {
  std::array<double, model::kThesisParamCount> p{};
  p[model::kM_acc] = 5e-5;
  p[model::kC_vel_neg] = 1.1e-3;
  p[model::kB_vel_neg] = 0.5e-3;
  p[model::kC_vel_pos] = 1.0e-3;
  p[model::kB_vel_pos] = 0.6e-3;
  p[model::kA_pos] = 11e-3;
  p[model::kP_pos] = 1.0 / 12.0;
  p[model::kS_pos] = 0.3;
  return p;
}

// The clean knob's torque on the motion, plus `extra`.
fit::FitData with_torque(fit::FitData d, const std::array<double, model::kThesisParamCount>& p,
                         const std::vector<double>& extra) {
  const auto m = model::ThesisModel<double>::from_params(p.data());
  for (std::size_t i = 0; i < d.size(); ++i) d.torque[i] = m.torque(d.kinematics(i)) + extra[i];
  return d;
}

double rms(const std::vector<double>& x, const std::vector<std::size_t>& rows) {
  double s = 0.0;
  for (const std::size_t i : rows) s += x[i] * x[i];
  return std::sqrt(s / static_cast<double>(rows.size()));
}

TEST(EffectAbsorption, MoreOfEq6sOwnTermsIsTakenUpWhole) {
  const fit::FitData d = swept_motion();
  const auto rows = moving_rows(d);
  const auto p = detent_knob();
  auto q = p;
  q[model::kM_acc] *= 1.3;
  q[model::kB_vel_pos] += 0.4e-3;
  q[model::kC_vel_neg] += 0.5e-3;
  q[model::kA_pos] *= 1.01;
  q[model::kS_pos] += 1e-3;
  const auto m0 = model::ThesisModel<double>::from_params(p.data());
  const auto m1 = model::ThesisModel<double>::from_params(q.data());
  std::vector<double> change(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) change[i] = m1.torque(d.kinematics(i)) - m0.torque(d.kinematics(i));
  const fit::FitData clean = with_torque(d, p, std::vector<double>(d.size(), 0.0));
  EXPECT_LT(bench::unabsorbed_rms(p, clean, with_torque(d, p, change), rows), 2e-3 * rms(change, rows));
}

// A PID loop tracks the stimulus a little differently with an effect in the
// plant: the torque Eq. 6 predicts of that motion is no part of the effect.
TEST(EffectAbsorption, TheTorqueOfAChangedMotionThatEq6PredictsIsNoEffect) {
  const fit::FitData d = swept_motion();
  const auto rows = moving_rows(d);
  const auto p = detent_knob();
  fit::FitData moved = d;
  for (std::size_t i = 0; i < d.size(); ++i) {
    moved.theta[i] = 1.02 * d.theta[i] + 0.01;
    moved.omega[i] = 1.02 * d.omega[i];
    moved.alpha[i] = 1.02 * d.alpha[i];
  }
  const std::vector<double> none(d.size(), 0.0);
  const fit::FitData clean = with_torque(d, p, none), captured = with_torque(moved, p, none);
  std::vector<double> change(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) change[i] = captured.torque[i] - clean.torque[i];
  EXPECT_GT(rms(change, rows), 1e-3);
  EXPECT_LT(bench::unabsorbed_rms(p, clean, captured, rows), 1e-9);
}

TEST(EffectAbsorption, AQuadraticDragIsMostlyViscousDampingAndTheRestIsLeft) {
  const fit::FitData d = swept_motion();
  const auto rows = moving_rows(d);
  std::vector<double> drag(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) drag[i] = 1e-4 * d.omega[i] * std::abs(d.omega[i]);
  const auto p = detent_knob();
  const fit::FitData clean = with_torque(d, p, std::vector<double>(d.size(), 0.0));
  const double left = bench::unabsorbed_rms(p, clean, with_torque(d, p, drag), rows), whole = rms(drag, rows);
  EXPECT_LT(left, 0.5 * whole);
  EXPECT_GT(left, 0.05 * whole);
}

TEST(EffectAbsorption, ATorqueNoEq6TermResemblesIsLeftWhole) {
  const fit::FitData d = swept_motion();
  const auto rows = moving_rows(d);
  std::vector<double> ripple(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) ripple[i] = 2e-3 * std::sin(17.3 * d.theta[i] * 2.0 * kPi);
  const auto p = detent_knob();
  const fit::FitData clean = with_torque(d, p, std::vector<double>(d.size(), 0.0));
  EXPECT_NEAR(bench::unabsorbed_rms(p, clean, with_torque(d, p, ripple), rows), rms(ripple, rows), 0.05 * rms(ripple, rows));
}

// With A = 0 the detent's period and phase have no sensitivity (the
// basis loses them) but its amplitude does: a sine at the fitted period and
// phase is still taken up, one at another period is not.
TEST(EffectAbsorption, AKnobWithoutDetentsTakesUpASineAtItsFittedPeriodOnly) {
  const fit::FitData d = swept_motion();
  const auto rows = moving_rows(d);
  auto p = detent_knob();
  p[model::kA_pos] = 0.0;
  std::vector<double> viscous(d.size()), own(d.size()), other(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    viscous[i] = 1e-3 * d.omega[i];
    own[i] = 2e-3 * std::sin(d.theta[i] / p[model::kP_pos] + p[model::kS_pos]);
    other[i] = 2e-3 * std::sin(17.3 * d.theta[i] * 2.0 * kPi);
  }
  const fit::FitData clean = with_torque(d, p, std::vector<double>(d.size(), 0.0));
  EXPECT_LT(bench::unabsorbed_rms(p, clean, with_torque(d, p, viscous), rows), 1e-6 * rms(viscous, rows));
  EXPECT_LT(bench::unabsorbed_rms(p, clean, with_torque(d, p, own), rows), 1e-6 * rms(own, rows));
  EXPECT_NEAR(bench::unabsorbed_rms(p, clean, with_torque(d, p, other), rows), rms(other, rows), 0.05 * rms(other, rows));
}

}  // namespace
