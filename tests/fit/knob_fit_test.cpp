// fit_knob on synthetic data where the truth is known exactly.
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/fit/validation_data.hpp"
#include "knoblab/model/trajectory.hpp"

namespace knoblab::fit {
namespace {

// A capture-like data set: Table 3's spatial sweep (±1 rad, 0 → 0.5 Hz over
// 5 s at 5 kHz) through `model` with Gaussian torque noise; `ar` > 0 makes
// the noise AR(1)-correlated, as filtered sensor noise is.
FitData sweep_data(const model::ThesisModel<double>& m, double noise_sd, std::uint64_t seed,
                   double ar = 0.0, double seconds = 5.0) {
  const model::SweptSine sweep = model::SweptSine::spatial();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, noise_sd * std::sqrt(1 - ar * ar));
  FitData d;
  d.rate_hz = 5000;
  double e = 0.0;
  for (int n = 0; n < static_cast<int>(seconds * 5000); ++n) {
    const double t = n / 5000.0;
    const auto k = sweep.at(t);
    e = ar * e + normal(rng);
    d.t.push_back(t), d.theta.push_back(k.theta), d.omega.push_back(k.omega);
    d.alpha.push_back(k.alpha), d.torque.push_back(m.torque(k) + e);
  }
  return d;
}

// A moderate-detents-like knob, SI units.
model::ThesisModel<double> knob(double detents_per_rev, double A) {
  const double p[] = {4.9e-5, 1.1e-3, 4.8e-4, 1.1e-3, 5.6e-4, A, 1.0 / detents_per_rev, 0.4};
  return model::ThesisModel<double>::from_params(p);
}

double cost(const FitData& d, const model::ThesisModel<double>& m) {
  double s = 0;
  for (std::size_t i = 0; i < d.size(); ++i) s += std::pow(m.torque(d.kinematics(i)) - d.torque[i], 2);
  return s;
}

TEST(KnobFit, FindsTheDetentPeriodWhereAStartOneDetentOffIsTrapped) {
  const FitData d = sweep_data(knob(12, 0.011), 0.4e-3, 3);
  const FitResult r = fit_knob(d);
  ASSERT_TRUE(r.detents);
  EXPECT_NEAR(1.0 / r.value("P_pos"), 12.0, 0.05);
  EXPECT_NEAR(r.value("A_pos"), 0.011, 0.0003);

  // The same fit started the way the thesis did, from a hand guess of the
  // period (here 18 instead of 12 per revolution: 12 rad of detent phase
  // off over the ±1 rad captured), stays in a local minimum.
  std::vector<double> guess = r.params;
  guess[model::kP_pos] = 1.0 / 18.0;
  guess[model::kS_pos] = 0.0;
  FitOptions o;
  o.start = guess;
  o.stick_band = false;
  const FitResult trapped = fit_knob(d, o);
  EXPECT_GT(std::abs(1.0 / trapped.value("P_pos") - 12.0), 0.3);
  EXPECT_GT(cost(d, thesis_model(trapped)), 1.5 * cost(d, thesis_model(r)));
}

TEST(KnobFit, AKnobWithoutDetentsGetsNoDetentTerm) {
  const FitData d = sweep_data(knob(12, 0.0), 0.4e-3, 4);
  const FitResult r = fit_knob(d);
  EXPECT_FALSE(r.detents);
  EXPECT_GT(r.detent_false_alarm, 1e-4);
  EXPECT_EQ(r.value("A_pos"), 0.0);
  EXPECT_FALSE(r.fitted[model::kA_pos]);
  EXPECT_FALSE(r.fitted[model::kP_pos]);
  EXPECT_EQ(r.se[model::kA_pos], 0.0);
  EXPECT_NEAR(r.value("M_acc"), 4.9e-5, 0.05 * 4.9e-5);
  EXPECT_NEAR(r.value("C_vel_pos"), 1.1e-3, 0.05e-3);
}

TEST(KnobFit, SmallDetentsWellAboveTheNoiseAreFound) {
  // 30 detents of 0.3 mN·m under 0.4 mN·m of noise: subtle, but 25 000 samples show them.
  const FitData d = sweep_data(knob(30, 0.3e-3), 0.4e-3, 5);
  const FitResult r = fit_knob(d);
  ASSERT_TRUE(r.detents);
  EXPECT_NEAR(1.0 / r.value("P_pos"), 30.0, 0.3);
  EXPECT_LT(r.detent_false_alarm, 1e-6);
}

TEST(KnobFit, DetentsCanBeForcedOrRefused) {
  const FitData d = sweep_data(knob(12, 0.011), 0.4e-3, 6);
  FitOptions none;
  none.detents = FitOptions::Detents::None;
  EXPECT_FALSE(fit_knob(d, none).detents);
  const FitData flat = sweep_data(knob(12, 0.0), 0.4e-3, 6);
  FitOptions force;
  force.detents = FitOptions::Detents::Force;
  EXPECT_TRUE(fit_knob(flat, force).detents);
}

TEST(KnobFit, CorrelatedNoiseWidensTheIntervalsEnoughToCoverTheTruth) {
  // AR(1) noise with ρ = 0.95: the textbook σ²(JᵀJ)⁻¹ would be ~6× too narrow.
  const auto truth = knob(12, 0.011);
  const double p_true[] = {4.9e-5, 1.1e-3, 4.8e-4, 1.1e-3, 5.6e-4, 0.011, 1.0 / 12, 0.4};
  int covered = 0, pairs = 0;
  double inflation = 0;
  FitOptions no_stick;
  no_stick.stick_band = false;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const FitResult r = fit_knob(sweep_data(truth, 0.5e-3, seed, 0.95), no_stick);
    inflation += r.covariance_inflation / 12;
    for (std::size_t k = 0; k < 8; ++k, ++pairs) {
      covered += (r.ci95[k][0] <= p_true[k] && p_true[k] <= r.ci95[k][1]) ? 1 : 0;
    }
  }
  EXPECT_GT(inflation, 5.0);
  EXPECT_GE(static_cast<double>(covered) / pairs, 0.85) << covered << " of " << pairs;
}

TEST(KnobFit, Render4RecoversTheRenderingModel) {
  // Eq. 14: M θ̈ + B θ̇ + A sin(θ/P) (+ a phase, where the capture started).
  model::ThesisModel<double> m;
  m.inertia.M = 2e-5;
  m.friction = {0, 3e-4, 0, 3e-4};
  m.detents.A = 8e-3, m.detents.P = 1.0 / 20, m.detents.S = -1.1;
  const FitData d = sweep_data(m, 0.3e-3, 8);
  FitOptions o;
  o.model = ModelKind::Render4;
  const FitResult r = fit_knob(d, o);
  ASSERT_EQ(r.names.size(), 5u);
  EXPECT_EQ(r.names[1], "B_vel");
  EXPECT_NEAR(r.value("M_acc"), 2e-5, 0.5e-6);
  EXPECT_NEAR(r.value("B_vel"), 3e-4, 0.1e-4);
  EXPECT_NEAR(r.value("A_pos"), 8e-3, 0.1e-3);
  EXPECT_NEAR(1.0 / r.value("P_pos"), 20.0, 0.05);
  EXPECT_NEAR(r.value("S_pos"), -1.1, 0.02);
}

TEST(KnobFit, SummaryFiguresAreConsistent) {
  ValidationSpec spec;
  const FitData d = make_validation_data(spec);
  const FitResult r = fit_knob(d);
  // Uniform noise of 4 peak-to-peak has σ = 4/√12.
  EXPECT_NEAR(r.rmse_Nm, 4.0 / std::sqrt(12.0), 0.02);
  EXPECT_NEAR(r.residual_sd, r.rmse_Nm, 1e-3);
  const double n = static_cast<double>(r.samples);
  EXPECT_NEAR(r.bic, n * std::log(r.rmse_Nm * r.rmse_Nm) + 8 * std::log(n), 1e-6 * std::abs(r.bic));
  EXPECT_GT(r.fit_percent, 50.0);
  EXPECT_LT(r.fit_percent, 100.0);
  EXPECT_GT(r.iterations, 0);
  EXPECT_GT(r.seconds, 0.0);
  EXPECT_FALSE(r.stick.has_value());  // Eq. 10 has no stick band
  for (std::size_t k = 0; k < 8; ++k) {
    EXPECT_NEAR(r.ci95[k][1] - r.params[k], r.t95 * r.se[k], 1e-12);
    EXPECT_NEAR(r.covariance[k * 8 + k], r.se[k] * r.se[k], 1e-15 + 1e-9 * r.se[k] * r.se[k]);
  }
}

TEST(KnobFit, PredictionBandsAndParts) {
  const FitData d = make_validation_data(ValidationSpec{});
  const FitResult r = fit_knob(d);
  const Prediction p = predict(r, d);
  ASSERT_EQ(p.tau.size(), d.size());
  double mean_curve = 0;
  int inside = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_NEAR(p.tau[i], p.acc[i] + p.vel[i] + p.pos[i], 1e-12);
    EXPECT_GT(p.observation_half[i], p.curve_half[i]);
    mean_curve += p.curve_half[i] / static_cast<double>(d.size());
    inside += std::abs(d.torque[i] - p.tau[i]) <= p.observation_half[i] ? 1 : 0;
  }
  // The fit's figure averages evenly strided rows (~8 000), predict every row.
  EXPECT_NEAR(mean_curve, r.ci95_torque_Nm, 1e-3 * mean_curve);
  // Uniform noise: ±1.96σ = ±2.26 covers all of ±2, so nearly every sample.
  EXPECT_GT(inside, static_cast<int>(0.95 * static_cast<double>(d.size())));
}

TEST(KnobFit, RejectsDataThatCannotIdentifyTheModel) {
  FitData d;
  for (int i = 0; i < 10; ++i) {
    d.t.push_back(i), d.theta.push_back(0), d.omega.push_back(0), d.alpha.push_back(0), d.torque.push_back(0);
  }
  EXPECT_THROW(fit_knob(d), FitDataError);
}

}  // namespace
}  // namespace knoblab::fit
