// Discrepancy discovery on captures of the simulated moderate-detents knob
// (Table 3 sweep through the PID, 8 s at 5 kHz): an effect concealed in the
// plant is named with its parameters, the clean knob gets no finding. A
// small slice of the concealed-effect benchmark, through the same simulator.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "findings.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/sim/presets.hpp"
#include "simulation.hpp"

namespace knoblab::cli {
namespace {

using knoblab::test::param;

discovery::DiscrepancyResult discover_with(const std::string& effects,
                                           const std::string& knob = "moderate-detents",
                                           const discovery::DiscrepancyOptions& opt = {}) {
  SimulationRequest req;
  req.knob_name = knob;
  req.knob = *sim::presets::knob(req.knob_name);
  req.seconds = 8.0;
  req.effects = model::parse_effect_specs(effects);
  const SimulationResult s = simulate(req, nullptr);
  return discovery::discover(fit::prepare(s.capture), opt);
}

TEST(DiscrepancySim, CleanKnobHasNoFinding) {
  const auto r = discover_with("");
  EXPECT_TRUE(r.findings.empty()) << discovery::to_json(r);
  EXPECT_EQ(r.final_model.heldout_rows, r.base.heldout_rows);
  EXPECT_TRUE(discovery::same_rows_sentence(r).empty());
  // Nothing added, the same forward view; under a millirad over 20 ms.
  EXPECT_EQ(r.final_model.forward_rmse_rad, r.base.forward_rmse_rad);
  EXPECT_LT(r.base.forward_rmse_rad, 1e-3);
}

TEST(DiscrepancySim, ASecondPeriodicTorqueIsNamedWithItsPeriod) {
  // 1 mN·m at 17.3 cycles/rev beside 11 mN·m detents at 12/rev.
  const auto r = discover_with("periodic_torque:amplitude_Nm=0.001,period_rad=0.36316811075498007,phase_rad=0.3");
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const discovery::Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, discovery::EffectId::PeriodicTorque) << discovery::to_json(r);
  EXPECT_NEAR(param(f, "cycles_per_rev"), 17.3, 0.3);
  EXPECT_NEAR(param(f, "amplitude_Nm"), 0.001, 0.0002);
  EXPECT_LT(f.heldout_rmse_after_Nm, 0.8 * f.heldout_rmse_before_Nm);
  // The forward view agrees: driven by the measured torque, the model with
  // the cogging term follows the recorded angle more closely (1.35 → 0.49
  // mrad when measured).
  EXPECT_LT(r.final_model.forward_rmse_rad, 0.6 * r.base.forward_rmse_rad);
  EXPECT_GT(r.final_model.forward_rmse_rad, 0.0);
}

TEST(DiscrepancySim, StribeckFrictionIsNamed) {
  const auto r = discover_with("stribeck:static_excess_Nm=0.0012,stribeck_velocity_rad_s=0.5");
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  EXPECT_EQ(r.findings.front().effect, discovery::EffectId::Stribeck) << discovery::to_json(r);
  EXPECT_GT(param(r.findings.front(), "static_excess_Nm"), 0.0);
}

TEST(DiscrepancySim, ATorqueChannelDelayIsNamedWithItsLength) {
  // 0.73 ms on moderate-detents: a lag Eq. 6 partly takes up (a lagged B·ω
  // reads as inertia). Near each reversal the delayed inputs enter the stick
  // band; compared on rows both models describe, the delay is found near its
  // length (0.65 ms measured; the clean knob's own best shift is −0.1 ms),
  // not at the third of it the reversal rows pulled it to.
  const auto r = discover_with("time_delay:delay_s=0.00073");
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const discovery::Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, discovery::EffectId::TimeDelay) << discovery::to_json(r);
  EXPECT_NEAR(param(f, "delay_s"), 0.73e-3, 0.2e-3);
  EXPECT_LT(f.heldout_rmse_after_Nm, 0.7 * f.heldout_rmse_before_Nm);
  // Driven by the torque the channel shows δ later, the forward view is the
  // clean knob's again (0.75 → 0.49 mrad measured).
  EXPECT_LT(r.final_model.forward_rmse_rad, 0.8 * r.base.forward_rmse_rad);
}

TEST(DiscrepancySim, AClippedTorqueSensorIsNamedWithItsLimit) {
  // The sensor clips at ±14.6 mN·m, under the knob's 22.6 mN·m peaks: 4.7 %
  // of the samples sit on the limit as recorded. The Table 6 low-pass rings
  // at each corner, so the flat tops are looked for before it.
  const auto r = discover_with("saturation:limit_Nm=0.0146");
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const discovery::Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, discovery::EffectId::Saturation) << discovery::to_json(r);
  EXPECT_NEAR(param(f, "limit_Nm"), 0.0146, 0.0003);
  EXPECT_LT(f.heldout_rmse_after_Nm, 0.8 * f.heldout_rmse_before_Nm);
}

TEST(DiscrepancySim, PlayBeforeTheDetentMechanismIsNamedWithItsWidth) {
  // 3.2 mrad of play on moderate-detents, whose static friction (20 mN·m)
  // outholds its detents (11 mN·m): after each reversal the mechanism
  // stands while the knob crosses the play, and the sensor reads next to
  // nothing. Discovery's mechanism must stand there too (the base fit's
  // breakaway level), not snap ahead on the detent's pull.
  const auto r = discover_with("backlash:width_rad=0.0032");
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const discovery::Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, discovery::EffectId::Backlash) << discovery::to_json(r);
  EXPECT_NEAR(param(f, "width_rad"), 0.0032, 0.0008);
  EXPECT_LT(f.heldout_rmse_after_Nm, 0.6 * f.heldout_rmse_before_Nm);
}

TEST(DiscrepancySim, ASofterGripperCouplingIsNamedComplianceWithItsStiffness) {
  // High-friction through a 56 N·m/rad coupling instead of the default 100
  // (the benchmark's concealed size). The knob stands at each reversal while
  // the motor winds the coupling up to the 150 mN·m breakaway: a rigid model
  // sees the encoder move and predicts kinetic friction there, hysteresis or
  // a delay only bend that ramp. The compliance model finds the knob standing
  // (twist-corrected speed) and predicts the wound-up torque from the motor's
  // motion (41.6 N·m/rad measured, ζ 0.51).
  const auto r = discover_with("compliance:stiffness_Nm_per_rad=55.7", "high-friction");
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const discovery::Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, discovery::EffectId::Compliance) << discovery::to_json(r);
  EXPECT_GT(param(f, "stiffness_Nm_per_rad"), 55.7 / 1.5);
  EXPECT_LT(param(f, "stiffness_Nm_per_rad"), 55.7 * 1.5);
  EXPECT_LT(f.heldout_rmse_after_Nm, 0.8 * f.heldout_rmse_before_Nm);
  // Forward, the model moves the knob and the encoder reads it plus the
  // twist: the trajectories agree better (5.75 → 5.36 mrad measured; 5.85
  // when the twist was left out).
  EXPECT_LT(r.final_model.forward_rmse_rad, r.base.forward_rmse_rad);
}

TEST(DiscrepancySim, ALargerButInconsistentGainDoesNotVetoAConsistentOne) {
  // Moderate-detents through a 16.7 N·m/rad coupling (the benchmark's
  // concealed size). A spurious delay gains more on the held-out rows (9 %),
  // but from a few blocks' breakaways (t < 0); the coupling's twist gains
  // less (6 % on the rows both describe) in every block (t 6.4). The
  // consistent one is kept, and the delay's larger gain lowers its confidence.
  const auto r = discover_with("compliance:stiffness_Nm_per_rad=16.7", "moderate-detents");
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const discovery::Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, discovery::EffectId::Compliance) << discovery::to_json(r);
  EXPECT_GE(f.t_stat, 3.0);
  double delay_gain = 0.0;
  for (const discovery::CandidateScore& c : r.candidates)
    if (c.round == 0 && c.effect == discovery::EffectId::TimeDelay) delay_gain = c.heldout_gain;
  EXPECT_GT(delay_gain, 1.0 - f.heldout_rmse_after_Nm / f.heldout_rmse_before_Nm) << discovery::to_json(r);
  EXPECT_LT(f.confidence, 0.5);
  // The twist leaves out the rows where the knob creeps through a breakaway,
  // which hold most of the base's residual: base → final reads far more than
  // the finding's own gain, so the result also states both on the same rows.
  EXPECT_LT(r.final_model.heldout_rows, r.base.heldout_rows);
  EXPECT_GT(r.base.heldout_rmse_Nm, 1.5 * r.same_rows.base_Nm);
  ASSERT_EQ(r.findings.size(), 1u);  // then the finding's own figures are base → final
  EXPECT_NEAR(r.same_rows.base_Nm, f.heldout_rmse_before_Nm, 1e-12);
  EXPECT_NEAR(r.same_rows.final_Nm, f.heldout_rmse_after_Nm, 1e-12);
  EXPECT_EQ(r.same_rows.rows, r.final_model.heldout_rows);
  const std::string same = discovery::same_rows_sentence(r);
  EXPECT_NE(same.find("on the " + std::to_string(r.same_rows.rows) + " both describe"), std::string::npos)
      << same;
}

TEST(DiscrepancySim, AOncePerRevolutionTorqueOnAKnobWithoutDetentsIsNotCalledDetents) {
  // 2 mN·m once per revolution on the detent-free high-inertia knob: the base
  // detent search takes it for 1.6 "detents" per revolution, fewer than two
  // periods inside the ±1 rad sweep. It must come back under the name of a
  // position trend, not sit in the base as detents. Over ±1 rad, sin θ and
  // θ − θ³/6 cannot be told apart: gravity or spring.
  const auto r = discover_with("gravity:amplitude_Nm=0.002", "high-inertia");
  double A = -1.0;
  for (const auto& [n, v] : r.base.params)
    if (n == "A_pos") A = v;
  EXPECT_EQ(A, 0.0) << discovery::to_json(r);
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const discovery::EffectId e = r.findings.front().effect;
  EXPECT_TRUE(e == discovery::EffectId::Gravity || e == discovery::EffectId::Spring) << discovery::to_json(r);
  EXPECT_LT(r.final_model.heldout_rmse_Nm, 0.85 * r.base.heldout_rmse_Nm);
}


TEST(DiscrepancySim, ASpringReturnKnobIsNamedSpringWithBothTermsAndNothingElse) {
  // A knob without detents on a hardening return spring (0.05 N·m/rad, 0.02 N·m/rad³).
  const auto r = discover_with("spring:stiffness_Nm_per_rad=0.05,cubic_Nm_per_rad3=0.02", "high-inertia");
  ASSERT_EQ(r.findings.size(), 1u) << discovery::to_json(r);
  const discovery::Finding& f = r.findings[0];
  EXPECT_EQ(f.effect, discovery::EffectId::Spring) << discovery::to_json(r);
  EXPECT_NEAR(param(f, "stiffness_Nm_per_rad"), 0.05, 0.005);
  EXPECT_NEAR(param(f, "cubic_Nm_per_rad3"), 0.02, 0.005);
  EXPECT_NEAR(param(f, "centre_rad"), 0.0, 0.02);
  EXPECT_NE(f.explanation.find("hardening"), std::string::npos) << f.explanation;
}


// On the non-sine-detents knob, after its detents' shape and play, a small lag
// is left that a time delay (1 parameter) and a compliant coupling (2) both
// explain, the coupling 1.1 % better on held-out data.
TEST(DiscrepancySim, OfTwoNamesForOneResidualTheSimplerWinsUnlessTheRicherIsClearlyBetter) {
  const auto names = [](const discovery::DiscrepancyResult& r) {
    std::vector<discovery::EffectId> out;
    for (const discovery::Finding& f : r.findings) out.push_back(f.effect);
    return out;
  };
  const auto has = [](const std::vector<discovery::EffectId>& v, discovery::EffectId id) {
    return std::find(v.begin(), v.end(), id) != v.end();
  };
  const auto parsimonious = discover_with("", "non-sine-detents");
  const auto found = names(parsimonious);
  ASSERT_TRUE(has(found, discovery::EffectId::TimeDelay)) << discovery::to_json(parsimonious);
  EXPECT_FALSE(has(found, discovery::EffectId::Compliance)) << discovery::to_json(parsimonious);
  bool said = false;
  for (const discovery::Finding& f : parsimonious.findings)
    said = said || (f.effect == discovery::EffectId::TimeDelay &&
                    f.explanation.find("Preferred to compliance (2 parameters against 1)") != std::string::npos &&
                    f.explanation.find("under the 2 % a richer name must win by") != std::string::npos);
  EXPECT_TRUE(said) << discovery::to_json(parsimonious);

  discovery::DiscrepancyOptions any_gain;
  any_gain.parsimony_margin = 0.0;  // the best held-out error wins, whatever it costs
  const auto richest = names(discover_with("", "non-sine-detents", any_gain));
  EXPECT_TRUE(has(richest, discovery::EffectId::Compliance));
  EXPECT_FALSE(has(richest, discovery::EffectId::TimeDelay));
}

}  // namespace
}  // namespace knoblab::cli
