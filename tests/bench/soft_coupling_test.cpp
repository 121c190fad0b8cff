// A soft gripper between the camera's motor and the knob, on the second
// plant: the knob rings against it at tens of Hz, and the encoder on the
// motor does not see the knob's motion. Discovery simulates the knob behind
// the coupling (apps/discovery/src/coupled_knob.hpp); these tests hold that
// simulation against the plant, written apart from it, and the finding
// against the coupling the plant had.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "findings.hpp"
#include "../../apps/discovery/src/coupled_knob.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "two_body_plant.hpp"

namespace {

using knoblab::test::finding;
using knoblab::test::param;

using namespace knoblab;
using discovery::detail::CouplingSpec;
using discovery::detail::KnobDynamics;

constexpr double kInertia = 5e-5;   // kg·m²
constexpr double kCoulomb = 1e-3;   // N·m
constexpr double kViscous = 5e-4;   // N·m·s/rad
constexpr double kDetent = 11e-3;   // N·m
constexpr double kDetentPeriod = 1.0 / 12;  // rad of travel per rad of phase: 12 per revolution

// A detented knob with stick–slip (breakaway 5 mN·m) through a coupling of
// `stiffness` at damping ratio `zeta`, on the Table 3 sweep.
bench::TwoBodyConfig knob_behind(double stiffness, double zeta) {
  bench::TwoBodyConfig c;
  c.knob.inertia = kInertia;
  c.knob.coulomb_pos = c.knob.coulomb_neg = kCoulomb;
  c.knob.viscous_pos = c.knob.viscous_neg = kViscous;
  c.knob.static_excess = 4e-3;
  c.knob.stribeck_speed = 0.01;
  c.knob.detent_amplitude = kDetent;
  c.knob.detent_period = kDetentPeriod;
  c.coupling.stiffness = stiffness;
  c.coupling.damping = bench::Coupling::damping_for(zeta, stiffness, kInertia);
  c.camera.torque_noise_rms = 0.1e-3;
  return c;
}

double rms(const std::vector<double>& a, const std::vector<double>& b) {
  double ss = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) ss += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(ss / static_cast<double>(a.size()));
}

TEST(SoftCoupling, TheSimulatedKnobReadsThePlantsCouplingTorqueWithTheKnobsOwnTerms) {
  // The knob's true terms and coupling, the exact motor angle: what is left
  // is the two integrators' difference, under a tenth of the 6.5 mN·m RMS
  // coupling torque (measured: 0.20 mN·m, mostly the breakaways, where the
  // plant's Stribeck curve and the simulation's single breakaway level part).
  bench::TwoBodyConfig c = knob_behind(20.0, 0.15);
  c.camera.encoder_counts_per_rev = 0;
  c.camera.torque_noise_rms = 0.0;
  const bench::TwoBodyRun run = bench::run_two_body(c);
  fit::PrepOptions raw;
  raw.filter = false;
  const fit::FitData d = fit::prepare(run.capture, raw);
  std::vector<double> omega(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) omega[i] = run.truth.knob_omega[i];
  KnobDynamics knob;
  knob.inertia = kInertia;
  knob.breakaway = kCoulomb + c.knob.static_excess;
  knob.torque = [](double theta, double w) {
    const double friction = w > 0 ? kCoulomb + kViscous * w : w < 0 ? -kCoulomb + kViscous * w : 0.0;
    return friction + kDetent * std::sin(theta / kDetentPeriod);
  };
  const std::vector<double> motor_omega = [&] {
    std::vector<double> w(d.size());
    const bench::MotorPath path(c.stimulus, c.seconds);
    for (std::size_t i = 0; i < d.size(); ++i) w[i] = path.at(d.t[i]).omega;
    return w;
  }();
  const auto sim = discovery::detail::simulate_coupled_knob(
      d.t, run.truth.motor_theta, motor_omega, CouplingSpec{20.0, c.coupling.damping / 20.0}, knob);
  const std::vector<double> zero(d.size(), 0.0);
  const double size = rms(run.truth.coupling_torque, zero);
  const double error = rms(sim.torque, run.truth.coupling_torque);
  EXPECT_GT(size, 3e-3);
  EXPECT_LT(error, 0.1 * size) << "coupling torque RMS " << size * 1e3 << " mN·m, error " << error * 1e3;
  EXPECT_LT(rms(sim.theta, run.truth.knob_theta), 1e-4);
}

TEST(SoftCoupling, AStuckKnobHoldsUntilTheWoundCouplingExceedsItsBreakaway) {
  // The motor turns at 0.1 rad/s against a knob held up to 5 mN·m through
  // 20 N·m/rad: the coupling winds 0.25 mrad (2.5 ms) before the knob moves.
  constexpr double k = 20.0, hold = 5e-3;
  std::vector<double> t, theta, omega;
  for (int i = 0; i <= 100; ++i) {
    t.push_back(i * 1e-4);
    theta.push_back(0.1 * t.back());
    omega.push_back(0.1);
  }
  KnobDynamics knob;
  knob.inertia = kInertia;
  knob.breakaway = hold;
  knob.torque = [](double, double w) { return w > 0 ? 1e-3 : w < 0 ? -1e-3 : 0.0; };
  const auto sim = discovery::detail::simulate_coupled_knob(t, theta, omega, CouplingSpec{k, 0.0}, knob);
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (k * theta[i] < 0.95 * hold) {
      EXPECT_TRUE(sim.stuck[i]) << "at " << t[i] << " s";
      EXPECT_EQ(sim.theta[i], 0.0);
      EXPECT_NEAR(sim.torque[i], k * theta[i], 1e-12);
    }
  }
  // Broken away, it slides and sticks again (stick–slip), never backwards.
  EXPECT_NE(std::find(sim.stuck.begin(), sim.stuck.end(), 0), sim.stuck.end());
  EXPECT_GT(sim.theta.back(), 0.0);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_GE(sim.omega[i], 0.0) << "at " << t[i] << " s";
}

TEST(SoftCoupling, TheSimulatorRefusesACouplingOrKnobWithoutStiffnessOrInertia) {
  const std::vector<double> t{0.0, 1e-4}, x{0.0, 0.0};
  KnobDynamics knob;
  knob.inertia = kInertia;
  knob.torque = [](double, double) { return 0.0; };
  EXPECT_THROW(discovery::detail::simulate_coupled_knob(t, x, x, CouplingSpec{0.0, 0.0}, knob), std::invalid_argument);
  knob.inertia = 0.0;
  EXPECT_THROW(discovery::detail::simulate_coupled_knob(t, x, x, CouplingSpec{20.0, 0.0}, knob), std::invalid_argument);
}

// Discovery on the rig's capture with α from the motor encoder, as a rig
// without an accelerometer records it.
discovery::DiscrepancyResult discover_through_encoder(const bench::TwoBodyConfig& c) {
  const bench::TwoBodyRun run = bench::run_two_body(c);
  fit::PrepOptions encoder;
  encoder.alpha = fit::AlphaSource::Encoder;
  return discovery::discover(fit::prepare(run.capture, encoder));
}

class SoftGripper : public ::testing::TestWithParam<double> {};

TEST_P(SoftGripper, IsNamedComplianceWithItsStiffnessThroughTheEncoder) {
  // The soft couplings real grippers and shaft adapters have (10–30 N·m/rad,
  // ζ 0.15, ringing at 100–120 Hz against this knob), α from the 640 000-
  // count motor encoder as a rig without an accelerometer records it. Read
  // off the measured torque, the knob's acceleration is the torque's second
  // derivative over k, all noise; simulated, the coupling is found (measured
  // 15.6 and 28.3 N·m/rad, held-out RMS down 35 % and 50 %).
  const double stiffness = GetParam();
  const discovery::DiscrepancyResult r = discover_through_encoder(knob_behind(stiffness, 0.15));
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const discovery::Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, discovery::EffectId::Compliance) << discovery::to_json(r);
  if (const discovery::Finding* c = finding(r, discovery::EffectId::Compliance)) {
    std::printf("stiffness %.3g N·m/rad: found %.3g, zeta %.2g, held-out %.3f -> %.3f mN·m\n", stiffness,
                param(*c, "stiffness_Nm_per_rad"), param(*c, "zeta"), c->heldout_rmse_before_Nm * 1e3,
                c->heldout_rmse_after_Nm * 1e3);
    EXPECT_GT(param(*c, "stiffness_Nm_per_rad"), stiffness / 1.35);
    EXPECT_LT(param(*c, "stiffness_Nm_per_rad"), stiffness * 1.35);
    EXPECT_LT(c->heldout_rmse_after_Nm, 0.8 * c->heldout_rmse_before_Nm);
  }
}

INSTANTIATE_TEST_SUITE_P(TensOfNewtonMetresPerRadian, SoftGripper, ::testing::Values(20.0, 30.0));

TEST(SoftCoupling, AHeavyKnobsCouplingIsNamedByTheFormTheHeldOutRowsFavour) {
  // The thesis' high-inertia radio knob (Table 7: 0.28 mN·m/(rad/s²), no
  // detents, 17 mN·m breakaway) behind 60 N·m/rad at ζ 0.1 (ringing at
  // 74 Hz). On the training rows the twist form fits better (the noise
  // τ̈/k brings in); held out it improves a few blocks tenfold and loses in
  // half, where the simulated form improves every block.
  bench::TwoBodyConfig c;
  c.knob.inertia = 2.8e-4;
  c.knob.coulomb_pos = c.knob.coulomb_neg = 3.8e-3;
  c.knob.viscous_pos = c.knob.viscous_neg = 0.5e-3;
  c.knob.static_excess = 13e-3;
  c.knob.stribeck_speed = 0.0075;
  c.coupling.stiffness = 60.0;
  c.coupling.damping = bench::Coupling::damping_for(0.1, 60.0, c.knob.inertia);
  c.camera.torque_noise_rms = 0.1e-3;
  const discovery::DiscrepancyResult r = discover_through_encoder(c);
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  EXPECT_EQ(r.findings.front().effect, discovery::EffectId::Compliance) << discovery::to_json(r);
  if (const discovery::Finding* f = finding(r, discovery::EffectId::Compliance)) {
    std::printf("found %.3g N·m/rad, held-out %.3f -> %.3f mN·m\n", param(*f, "stiffness_Nm_per_rad"),
                f->heldout_rmse_before_Nm * 1e3, f->heldout_rmse_after_Nm * 1e3);
    EXPECT_GT(param(*f, "stiffness_Nm_per_rad"), 60.0 / 1.35);
    EXPECT_LT(param(*f, "stiffness_Nm_per_rad"), 60.0 * 1.35);
  }
}

}  // namespace
